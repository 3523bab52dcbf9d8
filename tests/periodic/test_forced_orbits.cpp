// Forced periodic orbits of the damped reduced NBM equations by shooting on
// the exact flow (method.md §9): the linear limit against the frequency
// response of the full damped model, a forced bilinear oscillator against
// brute-force time integration to steady state, and the Floquet multipliers
// against the decay of a perturbation seen by that integration; the
// summary's stability verdict and its criterion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>


#include "base/errors.hpp"
#include "bilinear_oscillator.hpp"
#include "forced_models.hpp"
#include "linalg/dense_eigen.hpp"
#include "oscillators.hpp"
#include "periodic/periodic_orbit.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::Bilinear;
using nbm_test::ForcedChain;
using nbm_test::internal;
using Complex = std::complex<double>;

// With the gap out of reach the orbit is the linear steady response of the
// full damped model M u'' + C u' + K u = F(t) (massless contact dof, so the
// nodal boundary relation is its contact row): u(t) = K^-1 F0 +
// sum_k Re(Z_k^-1 (Fc_k - i Fs_k) e^{i k w t}), Z_k = K - (k w)^2 M + i k w C.
TEST(ForcedOrbit, LinearLimitIsTheFrequencyResponseOfTheDampedModel) {
  ForcedChain chain;
  chain.n = 4;
  const Index n = chain.n;
  Vector F0(n), Fc1(n), Fs1(n), Fc2(n);
  for (Index i = 0; i < n; ++i)
    F0(i) = 0.1 * (i - 1), Fc1(i) = 1 - 0.3 * i, Fs1(i) = 0.2 * i, Fc2(i) = 0.1 * std::sin(i + 1.0);
  const auto field = chain.field(internal(F0));
  nbm::Damping damping;
  damping.a_M = 0.05, damping.b_K = 0.01;
  const Matrix M = chain.M(), K = chain.K(), C = damping.a_M * M + damping.b_K * K;
  for (double w : {0.4, 0.9, 2.3}) {
    nbm::HarmonicLoad load;
    load.omega = w;
    load.cos = {internal(Fc1), internal(Fc2)};
    load.sin = {internal(Fs1)};
    const nbm::ExactFlow flow(field, damping, load);

    Vector u = K.ldlt().solve(internal(F0)), v = Vector::Zero(n + 1);
    const std::vector<Eigen::VectorXcd> Fhat = {
        internal(Fc1).cast<Complex>() - Complex(0, 1) * internal(Fs1).cast<Complex>(),
        internal(Fc2).cast<Complex>()};
    for (int k = 0; k < 2; ++k) {
      const double W = (k + 1) * w;
      const Eigen::MatrixXcd Z = K.cast<Complex>() - W * W * M.cast<Complex>() +
                                 Complex(0, W) * C.cast<Complex>();
      const Eigen::VectorXcd U = Z.partialPivLu().solve(Fhat[k]);
      u += U.real();
      v += (Complex(0, W) * U).real();
    }
    for (int m : {1, 2}) {
      const nbm::PeriodicProblem forced(flow, m);
      const auto orbit =
          nbm::shoot(forced, Vector::Zero(n), Vector::Zero(n), forced.period(), {});
      EXPECT_TRUE(orbit.switches.empty());
      EXPECT_LT((orbit.u0 - u.head(n)).norm(), 1e-10 * u.norm()) << "w " << w << " m " << m;
      EXPECT_LT((orbit.v0 - v.head(n)).norm(), 1e-10 * std::max(v.norm(), u.norm() * w))
          << "w " << w << " m " << m;
      EXPECT_LE(orbit.iterations, 2) << "the flow is affine: Newton converges in one step";
      EXPECT_TRUE(orbit.stable);

      // Multipliers: exp(lambda T) with lambda the eigenvalues of the
      // reduced first-order system.
      const Matrix Mr = M.topLeftCorner(n, n), Kr = chain.reduced_K();
      const Matrix Cr = damping.a_M * Mr + damping.b_K * Kr;
      Matrix A = Matrix::Zero(2 * n, 2 * n);
      A.topRightCorner(n, n) = Matrix::Identity(n, n);
      A.bottomLeftCorner(n, n) = -Mr.inverse() * Kr;
      A.bottomRightCorner(n, n) = -Mr.inverse() * Cr;
      const Eigen::VectorXcd lambda = nbm::general_eigen(A, false).values;
      std::vector<double> expected, got;
      for (Index j = 0; j < 2 * n; ++j)
        expected.push_back(std::exp(lambda(j).real() * orbit.period));
      for (const auto& mu : orbit.multipliers) got.push_back(std::abs(mu));
      std::sort(expected.begin(), expected.end());
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got.size(), expected.size());
      for (std::size_t j = 0; j < got.size(); ++j)
        EXPECT_NEAR(got[j], expected[j], 1e-10) << "w " << w << " m " << m << " j " << j;
    }
  }
}

nbm::PeriodicOrbit shoot(const Bilinear& b, const nbm::ReducedField& field, int m = 1,
                         Vector u0 = Vector::Zero(1), Vector v0 = Vector::Zero(1),
                         int transient_periods = 0) {
  const nbm::ExactFlow flow(field, b.damping(), b.load());
  nbm::ShootingOptions o;
  o.transient_periods = transient_periods;
  const nbm::PeriodicProblem forced(flow, m);
  return nbm::shoot(forced, u0, v0, forced.period(), o);
}

TEST(ForcedOrbit, BilinearOscillatorMatchesBruteForceTimeIntegration) {
  for (double w : {0.8, 1.2}) {
    Bilinear b;
    b.w = w;
    const auto field = b.oscillator().field();
    // Guess: the linear response without the obstacle, settled over 5
    // periods of the exact flow (from the guess itself Newton stalls at
    // w = 1.2: the period map is only piecewise smooth).
    const Complex Q = b.F / Complex(b.k - w * w, b.a_M * w);
    const auto orbit = shoot(b, field, 1, Vector::Constant(1, Q.real()),
                             Vector::Constant(1, (Complex(0, w) * Q).real()), 5);
    EXPECT_GE(orbit.switches.size(), 2u) << "the orbit must reach the obstacle";
    EXPECT_LT(orbit.periodicity_residual, 1e-11);
    EXPECT_TRUE(orbit.stable);
    const Eigen::Vector2d x = b.steady_state();
    // RK4 at 40000 steps per period: the kink of [u - g]_+ at the switches
    // leaves 6.9e-9 at w = 1.2 and 1.5e-10 at w = 0.8 (measured).
    EXPECT_NEAR(orbit.u0(0), x(0), 2e-8) << "w " << w;
    EXPECT_NEAR(orbit.v0(0), x(1), 2e-8) << "w " << w;
    // Liouville: with a massless boundary and a_M only, det X = exp(-a_M T).
    EXPECT_NEAR(orbit.monodromy.determinant(), std::exp(-b.a_M * orbit.period), 1e-11);
    // The same orbit is a fixed point of the doubled period map, with the
    // squared multipliers.
    const auto twice = shoot(b, field, 2, orbit.u0, orbit.v0);
    EXPECT_NEAR(twice.u0(0), orbit.u0(0), 1e-12);
    EXPECT_NEAR(std::abs(twice.multipliers[0]), std::norm(orbit.multipliers[0]), 1e-10);
  }
}

TEST(ForcedOrbit, FloquetMultipliersPredictTheDecayOfAPerturbation) {
  Bilinear b;
  const auto field = b.oscillator().field();
  const auto orbit = shoot(b, field);
  ASSERT_TRUE(orbit.stable);
  const Eigen::Vector2d star(orbit.u0(0), orbit.v0(0)), delta(1e-5, -0.6e-5);
  const int periods = 30;
  const Eigen::Vector2d d = b.integrate(star + delta, periods) - star;
  Matrix XN = Matrix::Identity(2, 2);
  for (int p = 0; p < periods; ++p) XN = orbit.monodromy * XN;
  const Eigen::Vector2d predicted = XN * delta;
  EXPECT_LT((d - predicted).norm(), 1e-3 * predicted.norm()) << d.transpose() << "\n"
                                                              << predicted.transpose();
  // Rate per period seen by the integration against the largest |mu|.
  const double rate = std::pow(d.norm() / delta.norm(), 1.0 / periods);
  EXPECT_NEAR(rate, std::abs(orbit.multipliers[0]), 0.02 * std::abs(orbit.multipliers[0]));
}

// Near the resonance the hardening bilinear oscillator has three coexisting
// orbits at w = 1.3: a small one without contact, a large one with contact
// (both stable) and, between them, a saddle. Time integration leaves the
// saddle at the rate of its multiplier, towards one stable orbit or the
// other depending on the side of the perturbation.
TEST(ForcedOrbit, AnOrbitFlaggedUnstableIsLeftByTimeIntegration) {
  Bilinear b;
  b.w = 1.3;
  const auto field = b.oscillator().field();
  const auto saddle = shoot(b, field, 1, Vector::Constant(1, 0.9 * std::cos(3.0)),
                            Vector::Constant(1, -0.9 * b.w * std::sin(3.0)));
  ASSERT_FALSE(saddle.stable);
  const auto mu = saddle.multipliers[0];
  ASSERT_GT(std::abs(mu), 1.05);
  ASSERT_EQ(mu.imag(), 0);
  const auto small = shoot(b, field, 1, Vector::Constant(1, 0.1), Vector::Zero(1));
  const auto large = shoot(b, field, 1, Vector::Constant(1, -0.95), Vector::Constant(1, 2.7));
  ASSERT_TRUE(small.stable && large.stable);
  ASSERT_TRUE(small.switches.empty());
  ASSERT_FALSE(large.switches.empty());

  const nbm::GeneralEigen eig = nbm::general_eigen(saddle.monodromy, true);
  Index j = 0;
  eig.values.cwiseAbs().maxCoeff(&j);
  const Eigen::Vector2d unstable = eig.vectors.col(j).real().normalized();
  const Eigen::Vector2d star(saddle.u0(0), saddle.v0(0));
  std::vector<Eigen::Vector2d> ends;
  for (double side : {1.0, -1.0}) {
    const Eigen::Vector2d delta = side * 1e-6 * unstable;
    const int periods = 10;
    const Eigen::Vector2d d = b.integrate(star + delta, periods) - star;
    const double rate = std::pow(d.norm() / delta.norm(), 1.0 / periods);
    EXPECT_NEAR(rate, std::abs(mu), 0.02 * std::abs(mu)) << "side " << side;
    ends.push_back(b.steady_state(star + delta));
  }
  // One side settles on each stable orbit (RK4 error as in the test above).
  const Eigen::Vector2d xs(small.u0(0), small.v0(0)), xl(large.u0(0), large.v0(0));
  const double to_small = std::min((ends[0] - xs).norm(), (ends[1] - xs).norm());
  const double to_large = std::min((ends[0] - xl).norm(), (ends[1] - xl).norm());
  EXPECT_LT(to_small, 2e-8);
  EXPECT_LT(to_large, 2e-8);
}

// The summary's stability verdict names the criterion that gave it: every
// |multiplier| < 1 for a forced orbit (no trivial multiplier), every
// |multiplier| <= 1 + margin for an autonomous one (the trivial 1 of the
// time shift included). The orbits: the stable small orbit and the saddle
// of the test above, and a free linear oscillation of the same oscillator
// (undamped, unforced, below the gap: both multipliers exactly on the unit
// circle).
TEST(ForcedOrbit, SummaryStatesTheStabilityCriterionOfTheOrbitsKind) {
  Bilinear b;
  b.w = 1.3;
  const auto field = b.oscillator().field();
  const auto small = shoot(b, field, 1, Vector::Constant(1, 0.1), Vector::Zero(1));
  const auto saddle = shoot(b, field, 1, Vector::Constant(1, 0.9 * std::cos(3.0)),
                            Vector::Constant(1, -0.9 * b.w * std::sin(3.0)));
  ASSERT_LT(std::abs(small.multipliers[0]), 1);
  ASSERT_GT(std::abs(saddle.multipliers[0]), 1.05);
  auto verdict = [](const nbm::PeriodicOrbit& o) {
    const std::string s = nbm::summary(o);
    return s.substr(s.find("\nstability ") + 1);
  };
  EXPECT_EQ(verdict(small),
            "stability stable (forced orbit: every |multiplier| < 1; no trivial multiplier)\n");
  EXPECT_EQ(verdict(saddle),
            "stability unstable (forced orbit: a |multiplier| >= 1; no trivial multiplier)\n");

  nbm::PeriodicOrbit free;
  free.u0 = Vector::Constant(1, 0.2 * b.g), free.v0 = Vector::Zero(1);
  free.period = 2 * M_PI / std::sqrt(b.k);
  nbm::analyse_orbit(field, free);
  ASSERT_TRUE(free.switches.empty());
  for (const auto& mu : free.multipliers) ASSERT_NEAR(std::abs(mu), 1, 1e-12);
  EXPECT_EQ(verdict(free),
            "stability stable (autonomous orbit: every |multiplier| <= 1 + 1e-06, the trivial "
            "multiplier 1 of the time shift included)\n");
}

TEST(ForcedOrbit, BadInputIsANamedError) {
  Bilinear b;
  const auto field = b.oscillator().field();
  const nbm::ExactFlow unforced(field);
  EXPECT_THROW(nbm::PeriodicProblem(unforced, 1), nbm::InputError);
  nbm::HarmonicLoad load;
  load.omega = 1.2;
  load.cos = {Eigen::Vector2d(0.2, 0)};
  const nbm::ExactFlow flow(field, nbm::Damping{}, load);
  EXPECT_THROW(nbm::PeriodicProblem(flow, 0), nbm::InputError);
  const nbm::PeriodicProblem forced(flow, 1);
  const double T = forced.period();
  auto message = [&](const nbm::ShootingOptions& o, const Vector& u = Vector::Zero(1),
                     double period = NAN) {
    try {
      nbm::shoot(forced, u, Vector::Zero(1), std::isnan(period) ? T : period, o);
    } catch (const nbm::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nbm::ShootingOptions o;
  o.transient_periods = -1;
  EXPECT_NE(message(o).find("forced orbit: transient_periods must be >= 0"), std::string::npos);
  EXPECT_NE(message({}, Vector::Zero(2)).find("initial state of size 2"), std::string::npos);
  EXPECT_NE(message({}, Vector::Constant(1, NAN)).find("non-finite"), std::string::npos);
  // The excitation fixes the period and the time origin: no other period,
  // no amplitude or phase condition.
  EXPECT_NE(message({}, Vector::Zero(1), 1.01 * T).find("is not the excitation's"),
            std::string::npos);
  for (int k = 0; k < 3; ++k) {
    nbm::ShootingOptions c;
    if (k == 0) c.half_period = true;
    if (k == 1) c.amplitude = 0.1;
    if (k == 2) c.arclength = nbm::ShootingOptions::Arclength{Vector::Ones(3), Vector::Zero(3)};
    EXPECT_NE(message(c).find("are an autonomous orbit's"), std::string::npos) << k;
  }
}

}  // namespace
