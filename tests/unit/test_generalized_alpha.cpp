// Generalized-alpha and HHT-alpha (method.md §5.4) through nbm::Solver, on
// the linear test problem: two masses on springs, joined through a contact
// node between them that never touches (its nodal boundary relation holds it
// at their mean), moving together: u'' + omega^2 u = 0. The expected
// values come from the closed-form amplification matrix of Chung and
// Hulbert's recurrence, built here from its three equations (not from the
// code's true-acceleration form), and from the exact solution cos(omega t).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>

#include <Eigen/Dense>

#include "api/solver.hpp"
#include "base/errors.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"
#include "time/generalized_alpha.hpp"

namespace {

using nbm::SchemeParameters;
using nbm::Solver;
using nbm::SolverOptions;
using nbm_test::expect_throw_with;
using StdVec = std::vector<double>;

constexpr double kStiffness = 4.0;    // the spring from the mass to the ground
constexpr double kCoupling = 50.0;    // the spring from the mass to the contact node
constexpr double kMass = 1.0, kContactMass = 0.25;
constexpr double kMassCoupling = 0.05;  // M_02 = M_12: the graph mass redistribution follows

// The closed-form amplification matrix of the recurrence (method.md §5.4)
//   (1 - am) b1 + am b0 = -Omega^2 ((1 - af) u1 + af u0)   (dt = 1 units)
//   u1 = u0 + v0 + (1/2 - beta) b0 + beta b1
//   v1 = v0 + (1 - gamma) b0 + gamma b1
// on X = (u, dt v, dt^2 b): X_{n+1} = A X_n.
Eigen::Matrix3d amplification(const SchemeParameters& p, double Omega) {
  const double O2 = Omega * Omega;
  Eigen::Matrix3d L, R;
  L << (1 - p.alpha_f) * O2, 0, 1 - p.alpha_m,  //
      1, 0, -p.beta,                            //
      0, 1, -p.gamma;
  R << -p.alpha_f * O2, 0, -p.alpha_m,  //
      1, 1, 0.5 - p.beta,               //
      0, 1, 1 - p.gamma;
  return L.partialPivLu().solve(R);
}

double spectral_radius(const Eigen::Matrix3d& A) {
  return A.eigenvalues().cwiseAbs().maxCoeff();
}

// The oscillator through the solver: dofs 0 and 1 the masses (at x = 0 and
// x = 2), dof 2 the contact node (x = 1; normal +1, a gap it never reaches)
// joined to both. The relation holds u_2 = (u_0 + u_1) / 2, and u_0 = u_1
// from a symmetric start: the three move as one, a translation, whose mass
// (the sum of M's entries) is the same whether the contact node keeps its
// mass (mass "consistent") or it is redistributed to the masses
// ("redistributed", which reproduces translations).
struct Oscillator {
  nbm::CooMatrix M, K;
  nbm::ContactDescription contact;
  SolverOptions options;
  explicit Oscillator(const std::string& scheme, double rho_inf, const std::string& mass,
                      double dt) {
    M.rows = M.cols = K.rows = K.cols = 3;
    M.i = {0, 1, 2, 0, 2, 1, 2};
    M.j = {0, 1, 2, 2, 0, 2, 1};
    M.value = {kMass, kMass, kContactMass, kMassCoupling, kMassCoupling, kMassCoupling,
               kMassCoupling};
    K.i = {0, 0, 1, 1, 2, 2, 2};
    K.j = {0, 2, 1, 2, 0, 1, 2};
    K.value = {kStiffness + kCoupling, -kCoupling, kStiffness + kCoupling, -kCoupling,
               -kCoupling,           -kCoupling, 2 * kCoupling};
    contact.dofs = {2};
    contact.normals = {1.0};
    contact.gaps = {1e6};
    options.mass = nbm_test::mass_named(mass);
    if (mass == "redistributed") options.positions = {0.0, 2.0, 1.0};
    options.scheme = nbm_test::scheme_named(scheme);
    options.rho_inf = rho_inf;
    options.dt = dt;
  }
  static double omega() {
    return std::sqrt(2 * kStiffness / (2 * kMass + kContactMass + 4 * kMassCoupling));
  }
};

struct Case {
  std::string scheme;
  double rho_inf;
  std::string mass;
};

std::string name(const ::testing::TestParamInfo<Case>& info) {
  std::string n = info.param.scheme + "_" + std::to_string(int(100 * info.param.rho_inf)) + "_" +
                  info.param.mass;
  for (char& c : n)
    if (c == '-') c = '_';
  return n;
}

SchemeParameters parameters_of(const Case& c) {
  return c.scheme == "hht-alpha" ? nbm::hht_alpha(c.rho_inf) : nbm::generalized_alpha(c.rho_inf);
}

class GeneralizedAlpha : public ::testing::TestWithParam<Case> {};

TEST_P(GeneralizedAlpha, FollowsTheClosedFormAmplificationStepByStep) {
  // Omega = omega dt from the resolved (0.1) to the unresolved (20) range.
  const Case c = GetParam();
  const SchemeParameters p = parameters_of(c);
  for (const double Omega : {0.1, 0.7, 2.0, 20.0}) {
    SCOPED_TRACE("Omega = " + std::to_string(Omega));
    const double omega = Oscillator::omega(), dt = Omega / omega;
    Oscillator o(c.scheme, c.rho_inf, c.mass, dt);
    Solver s(o.M, o.K, o.contact, o.options);
    StdVec u = {1.0, 1.0, 1.0}, v = {0.3, 0.3, 0.3}, F = {0.0, 0.0, 0.0};
    s.initialize(u, v, F);
    const Eigen::Matrix3d A = amplification(p, Omega);
    // b_0 = a_0 = -omega^2 u_0: the scheme starts from the true acceleration.
    Eigen::Vector3d X(1.0, dt * 0.3, -Omega * Omega * 1.0);
    double scale = 0;
    for (int n = 1; n <= 60; ++n) {
      s.step(u, v, F);
      X = A * X;
      scale = std::max(scale, X.head<2>().cwiseAbs().maxCoeff());
      ASSERT_NEAR(u[0], X(0), 1e-11 * scale) << "step " << n;
      ASSERT_NEAR(dt * v[0], X(1), 1e-11 * scale) << "step " << n;
      ASSERT_NEAR(u[1], u[0], 1e-13 * scale);  // the symmetric mode only
      ASSERT_NEAR(u[2], u[0], 1e-13 * scale);  // the open contact node follows
    }
    EXPECT_EQ(s.active()[0], 0);
  }
}

TEST_P(GeneralizedAlpha, RhoInfIsTheSpectralRadiusAtInfiniteFrequency) {
  // The closed form at Omega -> infinity, and the solver on it at
  // Omega = 1e4 (the high modes of a fine mesh at a large step): round-off
  // grows like Omega^2 eps there, hence the tolerance.
  const Case c = GetParam();
  const SchemeParameters p = parameters_of(c);
  EXPECT_NEAR(spectral_radius(amplification(p, 1e7)), c.rho_inf, 1e-4);
  const double dt = 1e4 / Oscillator::omega();
  Oscillator o(c.scheme, c.rho_inf, c.mass, dt);
  Solver s(o.M, o.K, o.contact, o.options);
  StdVec u = {1.0, 1.0, 1.0}, v = {0.0, 0.0, 0.0}, F = {0.0, 0.0, 0.0};
  s.initialize(u, v, F);
  Eigen::Vector3d X(1.0, 0.0, -1e8);
  const Eigen::Matrix3d A = amplification(p, 1e4);
  for (int n = 1; n <= 40; ++n) {
    s.step(u, v, F);
    X = A * X;
    ASSERT_NEAR(u[0], X(0), 1e-6) << "step " << n;
  }
  // Undamped (rho_inf = 1) the unresolved mode keeps its amplitude; damped,
  // 40 steps take it below 40^2 rho_inf^40 (the Jordan block's growth).
  if (c.rho_inf < 1) {
    EXPECT_LT(std::abs(u[0]), 1600 * std::pow(c.rho_inf, 40) + 1e-6);
  }
}

TEST_P(GeneralizedAlpha, ConvergesAtSecondOrderToTheExactSolution) {
  // |u(T) - cos(omega T)| over three halvings of dt: rate 2.
  const Case c = GetParam();
  const double omega = Oscillator::omega(), T = 3.0;
  std::vector<double> errors;
  for (const int steps : {40, 80, 160, 320}) {
    const double dt = T / steps;
    Oscillator o(c.scheme, c.rho_inf, c.mass, dt);
    Solver s(o.M, o.K, o.contact, o.options);
    StdVec u = {1.0, 1.0, 1.0}, v = {0.0, 0.0, 0.0}, F = {0.0, 0.0, 0.0};
    s.initialize(u, v, F);
    for (int n = 0; n < steps; ++n) s.step(u, v, F);
    errors.push_back(std::abs(u[0] - std::cos(omega * T)));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double rate = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(rate, 1.9) << "refinement " << k << ": " << errors[k - 1] << " -> " << errors[k];
    EXPECT_LT(rate, 2.1) << "refinement " << k;
  }
}

TEST_P(GeneralizedAlpha, RestartsExactlyFromItsAlgorithmicAcceleration) {
  // The algorithmic acceleration is the scheme's state: a restart from
  // (u, v, a, active, state) continues bit for bit; without it, restart()
  // says what is missing.
  const Case c = GetParam();
  Oscillator o(c.scheme, c.rho_inf, c.mass, 0.05);
  Solver run(o.M, o.K, o.contact, o.options);
  StdVec u = {1.0, 1.0, 1.0}, v = {0.0, 0.0, 0.0}, F = {0.0, 0.0, 0.0};
  run.initialize(u, v, F);
  for (int n = 0; n < 7; ++n) run.step(u, v, F);
  StdVec u2 = u, v2 = v;
  const StdVec a = run.acceleration(), state = run.scheme_state();
  EXPECT_EQ(state.size(), 3u);
  Solver again(o.M, o.K, o.contact, o.options);
  again.restart(u2, v2, F, run.time(), a, run.active(), state);
  for (int n = 0; n < 9; ++n) {
    run.step(u, v, F);
    again.step(u2, v2, F);
    ASSERT_EQ(u, u2) << "step " << n;
    ASSERT_EQ(v, v2) << "step " << n;
  }
  Solver missing(o.M, o.K, o.contact, o.options);
  expect_throw_with<nbm::InputError>([&] { missing.restart(u2, v2, F, again.time(), a,
                                                           again.active(), {}); },
                                     {"scheme state", "algorithmic acceleration"});
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, GeneralizedAlpha,
    ::testing::Values(Case{"generalized-alpha", 1.0, "consistent"},
                      Case{"generalized-alpha", 0.8, "consistent"},
                      Case{"generalized-alpha", 0.0, "consistent"},
                      Case{"generalized-alpha", 0.5, "redistributed"},
                      Case{"generalized-alpha", 0.9, "redistributed"},
                      Case{"hht-alpha", 0.7, "consistent"},
                      Case{"hht-alpha", 0.5, "redistributed"}),
    name);

TEST(GeneralizedAlphaParameters, ChungHulbertAndHhtSets) {
  // rho_inf = 1 is the trapezoidal rule at shifted times; HHT has alpha_m = 0.
  const SchemeParameters one = nbm::generalized_alpha(1.0);
  EXPECT_DOUBLE_EQ(one.alpha_m, 0.5);
  EXPECT_DOUBLE_EQ(one.alpha_f, 0.5);
  EXPECT_DOUBLE_EQ(one.beta, 0.25);
  EXPECT_DOUBLE_EQ(one.gamma, 0.5);
  const SchemeParameters hht = nbm::hht_alpha(0.5);
  EXPECT_EQ(hht.alpha_m, 0.0);
  EXPECT_DOUBLE_EQ(hht.alpha_f, 1.0 / 3);
  EXPECT_DOUBLE_EQ(hht.gamma, 0.5 + 1.0 / 3);
  EXPECT_DOUBLE_EQ(hht.beta, 4.0 / 9);
  for (const double rho : {0.0, 0.3, 0.8, 1.0}) {
    // Second order: gamma = 1/2 - alpha_m + alpha_f.
    const SchemeParameters p = nbm::generalized_alpha(rho);
    EXPECT_DOUBLE_EQ(p.gamma, 0.5 - p.alpha_m + p.alpha_f);
  }
}

TEST(GeneralizedAlphaParameters, LowModesAreDampedLessThanByHht) {
  // Chung and Hulbert's design goal: at the same rho_inf, less numerical
  // damping of the resolved modes than HHT-alpha: the loss of amplitude per
  // step, 1 - |lambda| of the principal eigenvalues, at Omega = 0.3.
  // At rho_inf = 1/2 the two sets coincide (alpha_m = 0).
  for (const double rho : {0.6, 0.7, 0.9}) {
    const double ga = 1 - spectral_radius(amplification(nbm::generalized_alpha(rho), 0.3));
    const double hht = 1 - spectral_radius(amplification(nbm::hht_alpha(rho), 0.3));
    EXPECT_LT(ga, 0.9 * hht) << "rho_inf = " << rho;
    EXPECT_GT(ga, 0.0);
  }
  const SchemeParameters ga = nbm::generalized_alpha(0.5), hht = nbm::hht_alpha(0.5);
  EXPECT_EQ(ga.alpha_m, 0.0);
  EXPECT_DOUBLE_EQ(ga.alpha_f, hht.alpha_f);
  EXPECT_DOUBLE_EQ(ga.beta, hht.beta);
  EXPECT_DOUBLE_EQ(ga.gamma, hht.gamma);
}

TEST(GeneralizedAlphaOptions, BadValuesAreNamed) {
  Oscillator o("generalized-alpha", 1.5, "consistent", 0.01);
  expect_throw_with<nbm::InputError>([&] { Solver(o.M, o.K, o.contact, o.options); },
                                     {"rhoInf", "[0, 1]"});
  o.options.scheme = nbm::TimeScheme::kHhtAlpha;
  o.options.rho_inf = 0.4;
  expect_throw_with<nbm::InputError>([&] { Solver(o.M, o.K, o.contact, o.options); },
                                     {"rhoInf", "[1/2, 1]"});
  o.options.scheme = nbm::TimeScheme::kNewmark;
  o.options.rho_inf = 0.8;
  expect_throw_with<nbm::InputError>([&] { Solver(o.M, o.K, o.contact, o.options); },
                                     {"rhoInf", "given with scheme \"newmark\""});
  o.options.scheme = nbm::TimeScheme::kGeneralizedAlpha;
  o.options.beta = 0.3;
  expect_throw_with<nbm::InputError>([&] { Solver(o.M, o.K, o.contact, o.options); },
                                     {"beta", "rhoInf"});
  o.options.beta.reset();
  o.options.energy = nbm::EnergyControl::kBounded;
  expect_throw_with<nbm::InputError>([&] { Solver(o.M, o.K, o.contact, o.options); },
                                     {"energy"});
}

}  // namespace
