// A contact problem and a stepper bundled for the stepper tests, with the
// state exposed in user coordinates (where the test problems are assembled).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "contact/contact_problem.hpp"
#include "contact/mass_redistribution.hpp"
#include "test_problems.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/moreau_jean_stepper.hpp"
#include "time/newmark_stepper.hpp"

namespace nbm_test {

struct Simulation {
  Assembled a;
  std::unique_ptr<nbm::ContactProblem> problem;
  std::unique_ptr<nbm::Stepper> stepper;
  Eigen::VectorXd F_int;  // gravity load in internal coordinates

  Simulation(Assembled assembled, const nbm::ContactDescription& c,
             std::vector<nbm::Index> fixed = {})
      : a(std::move(assembled)) {
    nbm::ContactSet set(a.K.rows(), std::vector<nbm::Index>(c.dofs.begin(), c.dofs.end()),
                        c.normals, to_eigen(c.gaps), fixed);
    problem = std::make_unique<nbm::ContactProblem>(a.M, a.K, std::move(set), fixed);
    F_int = problem->to_internal(a.F);
  }

  void newmark(double dt, nbm::NewmarkParameters p = {}) {
    stepper = std::make_unique<nbm::NewmarkStepper>(*problem, dt, p);
  }
  /// Massless boundary: the problem rebuilt with the redistributed mass
  /// (positions: one row per user dof, its node's coordinates), then the
  /// LCP-per-step Newmark scheme.
  void massless(double dt, const Eigen::MatrixXd& positions, nbm::SchemeParameters scheme = {},
                nbm::EnergyControl energy = nbm::EnergyControl::kBounded) {
    stepper.reset();  // it refers to the problem
    problem = std::make_unique<nbm::ContactProblem>(a.M, a.K, problem->contacts(),
                                                    problem->fixed(), &positions);
    stepper = std::make_unique<nbm::MasslessNewmarkStepper>(
        *problem, dt, scheme, nbm::Damping{}, nbm::ContactColumns::kAuto, energy);
  }
  void moreau_jean(double dt, double restitution) {
    stepper = std::make_unique<nbm::MoreauJeanStepper>(*problem, dt, restitution);
  }
  nbm::CentralDifferenceStepper& explicit_scheme(double dt) {
    auto cd = std::make_unique<nbm::CentralDifferenceStepper>(*problem, dt);
    auto& ref = *cd;
    stepper = std::move(cd);
    return ref;
  }

  void initialize(const Eigen::VectorXd& u_user, const Eigen::VectorXd& v_user) {
    stepper->initialize(problem->to_internal(u_user), problem->to_internal(v_user), F_int);
  }
  nbm::StepReport step() { return stepper->step(F_int); }

  Eigen::VectorXd u() const { return problem->to_user(stepper->u()); }
  Eigen::VectorXd v() const { return problem->to_user(stepper->v()); }
  Eigen::VectorXd acc() const { return problem->to_user(stepper->a()); }
  /// Centre-of-mass displacement along the unit vector dir (per dof of a
  /// node: dir has one entry per component): sum_i m_i u_i / m with the row
  /// sums m_i of M, which is exact for P1 (int rho u = 1' M u).
  double centre(const Eigen::VectorXd& x, const Eigen::VectorXd& dir) const {
    const int dim = static_cast<int>(dir.size());
    Eigen::VectorXd ones(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) ones(i) = dir(i % dim);
    return ones.dot(a.M * x) / a.mass;
  }
  double energy() const { return total_energy(a, u(), v()); }
};

/// The checks of an NBM step's end state: no penetration (1e-12 of the
/// displacement scale, at least u_floor), no tensile reaction, and gaps
/// complementary to reactions (the nodal boundary relation at the new
/// interior displacement); `step` names the step in the messages.
inline void expect_exact_contact(const nbm::Stepper& stepper, double u_floor, int step) {
  const Eigen::VectorXd gap = stepper.gaps(), lambda = stepper.reactions();
  const double u_scale = std::max(u_floor, stepper.u().cwiseAbs().maxCoeff());
  const double f_scale = std::max(1.0, lambda.cwiseAbs().maxCoeff());
  EXPECT_GE(gap.minCoeff(), -1e-12 * u_scale) << "step " << step;
  EXPECT_GE(lambda.minCoeff(), -1e-9 * f_scale) << "step " << step;
  for (nbm::Index i = 0; i < gap.size(); ++i)
    EXPECT_LE(std::min(std::abs(gap(i)) / u_scale, std::abs(lambda(i)) / f_scale), 1e-9)
        << "step " << step << ", contact " << i;
}

}  // namespace nbm_test
