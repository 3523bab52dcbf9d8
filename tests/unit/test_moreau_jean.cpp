// The Moreau-Jean peer (Newton impact law): exact free fall and energy
// conservation in flight (theta = 1/2 is the trapezoidal rule), Newton's law
// w+ = -e w- on every impulsive step, bounded penetration, e = 0 sticks.
#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Bar;
using nbm_test::Simulation;
using Vec = Eigen::VectorXd;

constexpr double kH0 = 0.1;

Simulation falling_bar(double dt, double e, const Bar& b = {}) {
  Simulation s(assemble(b), nbm_test::ground_contact());
  s.moreau_jean(dt, e);
  s.initialize(Vec::Constant(b.n_dofs(), kH0), Vec::Zero(b.n_dofs()));
  return s;
}

TEST(MoreauJean, FreeFallIsExactAndConservesEnergy) {
  const Bar b;
  Simulation s = falling_bar(1e-3, 0.5);
  const double e0 = s.energy();
  EXPECT_NEAR(s.u()(0), kH0, 0);  // the given state is kept (no nodal relation)
  const Vec e1 = Vec::Ones(1);
  for (int k = 1; k <= 100; ++k) {  // the fall takes sqrt(2 h0/g) = 0.141
    s.step();
    const double t = k * 1e-3;
    EXPECT_NEAR(s.centre(s.u(), e1), kH0 - 0.5 * b.g * t * t, 1e-12);
    EXPECT_NEAR(s.centre(s.v(), e1), -b.g * t, 1e-12);
    EXPECT_NEAR(s.energy(), e0, 1e-12 * b.rho * b.L * b.g * kH0);
  }
}

TEST(MoreauJean, NewtonsLawHoldsOnImpulsiveStepsAndPenetrationIsBounded) {
  for (double e : {0.0, 0.5, 1.0}) {
    SCOPED_TRACE("restitution " + std::to_string(e));
    const Bar b;
    const double dt = 1e-3;
    Simulation s = falling_bar(dt, e);
    int impulsive = 0;
    double penetration = 0;
    for (int k = 1; k <= 600; ++k) {
      const double w_before = s.v()(0);  // separation velocity w = -v_n, v_n = -v_0
      s.step();
      const double w_after = s.v()(0);
      const double p = s.stepper->reactions()(0) * dt;
      EXPECT_GE(p, 0.0);
      if (p > 0) {
        ++impulsive;
        EXPECT_NEAR(w_after + e * w_before, 0.0, 1e-10) << "step " << k;
      }
      penetration = std::max(penetration, -s.u()(0));
    }
    EXPECT_GE(impulsive, 1);
    // Position-level penetration is O(dt v_impact), v_impact = sqrt(2 g h0).
    EXPECT_LE(penetration, dt * std::sqrt(2 * b.g * kH0));
  }
}

TEST(MoreauJean, ZeroRestitutionSticksAfterImpact) {
  // The contact end stops at the first impulsive step and keeps a zero
  // normal velocity while the impulse stays positive.
  Simulation s = falling_bar(1e-3, 0.0);
  int k = 0;
  while (s.stepper->reactions()(0) == 0 && k < 1000) {
    s.step();
    ++k;
  }
  ASSERT_LT(k, 1000) << "no impact";
  EXPECT_NEAR(s.v()(0), 0.0, 1e-12);
}

TEST(MoreauJean, OptionsAreChecked) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  for (double e : {-0.1, 1.5, std::nan("")})
    nbm_test::expect_throw_with<nbm::InputError>([&] { s.moreau_jean(1e-3, e); },
                                                 {"restitution", "[0, 1]"});
  const auto a = assemble(b);
  nbm::SolverOptions o;
  o.dt = 1e-3;
  o.restitution = 0.5;  // with Newmark
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::Solver(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), o); },
      {"restitution", "moreau-jean"});
  o.scheme = nbm::TimeScheme::kMoreauJean;
  o.beta = 0.3;
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::Solver(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), o); },
      {"beta", "moreau-jean"});
  o.beta.reset();
  EXPECT_NO_THROW(nbm::Solver(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K),
                              nbm_test::ground_contact(), o));
}

}  // namespace
