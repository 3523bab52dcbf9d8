// The reduced basis of large models (reduced_basis.hpp): orbits of the
// reduced fixed-gap bar converge to the full model's as modes are added,
// and the reported full-model residual measures the reduction error.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "bars.hpp"
#include "periodic/reduced_basis.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Vector;

// The massless fixed-gap bar with N elements and its contact problem.
struct BarModel {
  nbm_test::GapBar bar;
  std::unique_ptr<nbm::ContactProblem> problem;
  explicit BarModel(int N) {
    bar.N = N;
    bar.massless = true;
    problem = bar.problem();
  }
};

// Largest full-model residual along one period of an orbit of the reduced model.
double reduction_residual(const nbm::ReducedBasis& basis, const nbm::PeriodicOrbit& orbit) {
  const auto& field = basis.field();
  std::vector<double> times;
  for (int k = 0; k < 64; ++k) times.push_back(orbit.period * k / 64);
  const auto r = nbm::ExactFlow(field).integrate(orbit.u0, orbit.v0, orbit.period, false, times);
  double worst = 0;
  for (Eigen::Index k = 0; k < r.samples.cols(); ++k) {
    const Vector q = r.samples.col(k).head(field.size());
    worst = std::max(worst, basis.full_residual(q, field.acceleration(q)));
  }
  return worst;
}

TEST(ReducedBasis, OrbitsConvergeToTheFullModelsAsModesAreAdded) {
  BarModel model(40);
  const Vector F = Vector::Zero(model.problem->size());
  const auto full_field = nbm::ReducedField::from(*model.problem, F);
  const Eigen::Index n = full_field.size();
  Vector u0(n);
  for (Eigen::Index k = 0; k < n; ++k)
    u0(k) = nbm_test::continuum_rest_profile(model.bar, 0.3,
                                             model.bar.x_of_interior(static_cast<int>(k)));
  nbm::ShootingOptions s;
  s.half_period = true;
  s.probe = n - 1;
  const auto full = nbm::shoot(full_field, u0, Vector::Zero(n), 3.7, s);
  ASSERT_EQ(full.switches.size(), 2u);
  // The full model's own orbit has a zero residual.
  std::vector<double> errors, residuals;
  for (int modes : {16, 32}) {
    const nbm::ReducedBasis basis(*model.problem, F, modes);
    EXPECT_TRUE(basis.field().massless_boundary());
    EXPECT_EQ(basis.field().size(), modes + 1);  // + one contact shape
    nbm::ShootingOptions r;
    r.half_period = true;
    r.kind = nbm::ShootingOptions::Amplitude::energy;
    r.amplitude = full.energy_start(3);
    const auto orbit = nbm::shoot(basis.field(), basis.reduce(full.u0),
                                  Vector::Zero(basis.size()), full.period, r);
    errors.push_back(std::abs(orbit.period - full.period) / full.period);
    residuals.push_back(reduction_residual(basis, orbit));
    EXPECT_LE(orbit.periodicity_residual, 1e-10);
  }
  std::cout << "relative period error " << errors[0] << " (16 modes), " << errors[1]
            << " (32 modes); full-model residual " << residuals[0] << ", " << residuals[1] << "\n";
  EXPECT_LT(errors[1], 0.01 * errors[0]) << errors[0] << " " << errors[1];
  EXPECT_LT(errors[1], 1e-5);
  EXPECT_LT(residuals[1], residuals[0]);
  EXPECT_LT(residuals[1], 1e-3);
}

TEST(ReducedBasis, RepresentsStaticStatesExactly) {
  // u_O = Psi u_C (static response to a contact displacement) is in range(V).
  BarModel model(30);
  const Vector F = Vector::Zero(model.problem->size());
  const nbm::ReducedBasis basis(*model.problem, F, 3);
  const auto full = nbm::ReducedField::from(*model.problem, F);
  Vector x = Vector::Zero(model.problem->size());
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 0.01 * (i + 1) / x.size();  // linear profile
  const Vector uO = full.restrict(x);
  EXPECT_LE((basis.expand(basis.reduce(uO)) - uO).norm(), 1e-12 * uO.norm());
}

TEST(ReducedBasis, RejectsModesOutOfRange) {
  BarModel model(10);
  const Vector F = Vector::Zero(model.problem->size());
  EXPECT_THROW(nbm::ReducedBasis(*model.problem, F, 0), std::invalid_argument);
  EXPECT_THROW(nbm::ReducedBasis(*model.problem, F, 10), std::invalid_argument);
}

}  // namespace
