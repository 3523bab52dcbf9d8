// Forced harmonic balance (method.md §9): the linear limit against the
// frequency response of the full damped model, and the forced bilinear
// oscillator against shooting on the exact flow (shooting.hpp), which it
// checks: state, convergence in H, Floquet stability.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <iostream>
#include <vector>

#include "base/errors.hpp"
#include "bilinear_oscillator.hpp"
#include "forced_models.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::Bilinear;
using nbm_test::ForcedChain;
using nbm_test::internal;
using Complex = std::complex<double>;

// Harmonic balance of the forced problem of subharmonic m with H harmonics.
nbm::HarmonicBalanceResult balance(const nbm::ExactFlow& flow, const Vector& u0,
                                   const Vector& v0, int H, int m = 1,
                                   nbm::HarmonicBalanceOptions o = {}) {
  const nbm::PeriodicProblem forced(flow, m);
  o.harmonics = H;
  return nbm::harmonic_balance(forced, u0, v0, forced.period(), o);
}

// Shooting on the forced problem (m = 1) after `transient` periods.
nbm::PeriodicOrbit shoot(const nbm::ExactFlow& flow, const Vector& u0, const Vector& v0,
                         int transient = 0) {
  const nbm::PeriodicProblem forced(flow, 1);
  nbm::ShootingOptions s;
  s.transient_periods = transient;
  return nbm::shoot(forced, u0, v0, forced.period(), s);
}

// With the gap out of reach the orbit is the steady response of the full
// damped model (massless contact dof: the nodal boundary relation is its
// contact row), u(t) = K^-1 F0 + sum_k Re(Z_k^-1 (Fc_k - i Fs_k) e^{i k w t}),
// Z_k = K - (k w)^2 M + i k w C: a finite series, which harmonic balance
// holds exactly once H reaches the load's last harmonic.
TEST(ForcedHarmonicBalance, LinearLimitIsTheFrequencyResponseOfTheDampedModel) {
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
  for (int harmonics : {1, 2}) {
    for (double w : {0.4, 0.9, 2.3}) {
      nbm::HarmonicLoad load;
      load.omega = w;
      load.cos = {internal(Fc1)};
      if (harmonics == 2) load.cos.push_back(internal(Fc2));
      load.sin = {internal(Fs1)};
      const nbm::ExactFlow flow(field, damping, load);
      Vector u = K.ldlt().solve(internal(F0)), v = Vector::Zero(n + 1);
      for (int k = 0; k < harmonics; ++k) {
        const double W = (k + 1) * w;
        const Eigen::VectorXcd Fhat =
            k == 0 ? Eigen::VectorXcd(internal(Fc1).cast<Complex>() -
                                      Complex(0, 1) * internal(Fs1).cast<Complex>())
                   : Eigen::VectorXcd(internal(Fc2).cast<Complex>());
        const Eigen::MatrixXcd Z = K.cast<Complex>() - W * W * M.cast<Complex>() +
                                   Complex(0, W) * C.cast<Complex>();
        const Eigen::VectorXcd U = Z.partialPivLu().solve(Fhat);
        u += U.real();
        v += (Complex(0, W) * U).real();
      }
      for (int m : {1, 2}) {
        // H = m harmonics: one harmonic of the series per load harmonic
        // suffices (harmonics = 1); H = 2 m for the second.
        const auto hb = balance(flow, Vector::Zero(n), Vector::Zero(n), harmonics * m, m);
        const std::string where =
            "w " + std::to_string(w) + " m " + std::to_string(m) + " H " + std::to_string(hb.harmonics);
        EXPECT_TRUE(hb.orbit.switches.empty()) << where;
        EXPECT_LT((hb.orbit.u0 - u.head(n)).norm(), 1e-10 * u.norm()) << where;
        EXPECT_LT((hb.orbit.v0 - v.head(n)).norm(), 1e-10 * std::max(v.norm(), u.norm() * w))
            << where;
        EXPECT_LT(hb.orbit.periodicity_residual, 1e-10) << where;
        EXPECT_LT(hb.truncation, 1e-12) << where;  // nothing left beyond H
        EXPECT_LE(hb.orbit.iterations, 2) << "linear: Newton converges in one step";
        EXPECT_TRUE(hb.orbit.stable) << where;
        EXPECT_DOUBLE_EQ(hb.orbit.period, 2 * M_PI * m / w);
      }
    }
  }
}

// Relative distance of two states at t = 0 (velocities by |u| w).
double state_distance(const nbm::PeriodicOrbit& a, const nbm::PeriodicOrbit& b, double w) {
  const double us = b.u0.norm();
  return std::max((a.u0 - b.u0).norm() / us, (a.v0 - b.v0).norm() / (us * w));
}

// Least-squares slope of log(error) against log(H).
double fitted_rate(const std::vector<int>& H, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(H.size());
  for (std::size_t k = 0; k < H.size(); ++k) {
    const double x = std::log(H[k]), y = std::log(error[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The bilinear oscillator with contact: the series converges to the orbit
// shooting finds. With the massless contact dof and mass-proportional
// damping the velocity is continuous and the acceleration jumps at the
// switches (the force kc [u - g]_+ has a kink), so the coefficients decay
// like h^-3. The error of the state at t = 0 oscillates with H (where the
// switching times fall on the harmonics' grid): its rate is fitted over
// H = 10 .. 160 (measured: 3.05, 2.97, 3.11 at w = 0.8, 1.2, 1.3).
TEST(ForcedHarmonicBalance, BilinearOscillatorConvergesToTheShootingOrbit) {
  const std::vector<int> Hs = {10, 14, 20, 28, 40, 57, 80, 113, 160};
  for (double w : {0.8, 1.2, 1.3}) {
    Bilinear b;
    b.w = w;
    const auto field = b.oscillator().field();
    const nbm::ExactFlow flow(field, b.damping(), b.load());
    // At w = 1.3 three orbits coexist (test_forced_orbits.cpp): the large
    // one with contact.
    const Vector u_guess = Vector::Constant(1, w == 1.3 ? -0.95 : 0.3);
    const Vector v_guess = Vector::Constant(1, w == 1.3 ? 2.7 : 0.0);
    const auto shot = shoot(flow, u_guess, v_guess, 5);
    ASSERT_GE(shot.switches.size(), 2u) << "w " << w;
    std::vector<double> errors;
    nbm::HarmonicBalanceResult hb;
    for (int H : Hs) {
      hb = balance(flow, shot.u0, shot.v0, H);
      errors.push_back(state_distance(hb.orbit, shot, w));
      std::cout << "bilinear w " << w << " H " << H << ": state error " << errors.back()
                << ", truncation " << hb.truncation << ", periodicity residual "
                << hb.orbit.periodicity_residual << "\n";
      EXPECT_LE(hb.residual, 1e-12);
      EXPECT_EQ(hb.orbit.switches.size(), shot.switches.size()) << "w " << w << " H " << H;
    }
    const double rate = fitted_rate(Hs, errors);
    std::cout << "bilinear w " << w << ": state error ~ H^-" << rate << "\n";
    EXPECT_GT(rate, 2.5) << "w " << w;
    EXPECT_LT(errors.back(), 1e-5) << "w " << w;
    // The exact flow's periodicity residual from the series' state (the
    // truncation seen without shooting) is of the size of the error.
    EXPECT_LT(hb.orbit.periodicity_residual, 10 * errors.back()) << "w " << w;
    EXPECT_GT(hb.orbit.periodicity_residual, 0.01 * errors.back()) << "w " << w;
    // Floquet: the exact flow's monodromy at the series' state, against
    // shooting's at the orbit.
    EXPECT_EQ(hb.orbit.stable, shot.stable);
    ASSERT_EQ(hb.orbit.multipliers.size(), shot.multipliers.size());
    for (std::size_t j = 0; j < shot.multipliers.size(); ++j)
      EXPECT_LT(std::abs(hb.orbit.multipliers[j] - shot.multipliers[j]), 1e-4) << "w " << w;
  }
}

// The saddle between the small and the large orbit at w = 1.3: harmonic
// balance needs no stability and finds it too; the exact flow from its state
// flags it unstable, like shooting.
TEST(ForcedHarmonicBalance, FindsTheUnstableOrbitShootingFlagsUnstable) {
  Bilinear b;
  b.w = 1.3;
  const auto field = b.oscillator().field();
  const nbm::ExactFlow flow(field, b.damping(), b.load());
  const auto saddle = shoot(flow, Vector::Constant(1, 0.9 * std::cos(3.0)),
                            Vector::Constant(1, -0.9 * b.w * std::sin(3.0)));
  ASSERT_FALSE(saddle.stable);
  const auto hb = balance(flow, saddle.u0, saddle.v0, 80);
  EXPECT_LT(state_distance(hb.orbit, saddle, b.w), 1e-4);
  EXPECT_FALSE(hb.orbit.stable);
  EXPECT_NEAR(std::abs(hb.orbit.multipliers[0]), std::abs(saddle.multipliers[0]), 1e-3);
}

// Stiffness-proportional damping makes the damping force b_K K_S u' jump at
// the switches (K_S changes), and a subharmonic basis (m = 2) holds the
// harmonic orbit on its even harmonics: both still converge to shooting.
TEST(ForcedHarmonicBalance, StiffnessDampingAndSubharmonicBasis) {
  Bilinear b;
  b.w = 1.2;
  const auto field = b.oscillator().field();
  nbm::Damping damping = b.damping();
  damping.b_K = 0.02;
  const nbm::ExactFlow flow(field, damping, b.load());
  const auto shot = shoot(flow, Vector::Constant(1, 0.3), Vector::Zero(1), 5);
  ASSERT_GE(shot.switches.size(), 2u);
  const auto h40 = balance(flow, shot.u0, shot.v0, 40);
  const auto h80 = balance(flow, shot.u0, shot.v0, 80);
  const double e40 = state_distance(h40.orbit, shot, b.w), e80 = state_distance(h80.orbit, shot, b.w);
  std::cout << "bilinear with b_K: state error " << e40 << " (H = 40), " << e80 << " (H = 80)\n";
  EXPECT_LT(e80, e40);
  EXPECT_LT(e80, 1e-3);
  // m = 2, H = 160: the same orbit (period 2 T), odd harmonics zero.
  const auto sub = balance(flow, shot.u0, shot.v0, 160, 2);
  EXPECT_DOUBLE_EQ(sub.orbit.period, 2 * shot.period);
  EXPECT_LT((sub.orbit.u0 - h80.orbit.u0).norm(), 1e-10 * h80.orbit.u0.norm());
  EXPECT_LT(sub.coefficients.col(1).norm(), 1e-10 * h80.orbit.u0.norm());
}

// Harmonic balance is one method of either kind of periodic problem, so
// the adaptive number of harmonics serves forced orbits too: H doubles from
// 10 until the truncation estimate is below the tolerance, each Newton
// solve starting from the last one's series; the result is the direct
// solve's at the final H, and closer to shooting than the first H's.
TEST(ForcedHarmonicBalance, AdaptiveHarmonicsDoubleUntilTheTruncationIsSmall) {
  Bilinear b;
  b.w = 1.2;
  const auto field = b.oscillator().field();
  const nbm::ExactFlow flow(field, b.damping(), b.load());
  const auto shot = shoot(flow, Vector::Constant(1, 0.3), Vector::Zero(1), 5);
  for (double tolerance : {1e-3, 1e-4}) {
    nbm::HarmonicBalanceOptions o;
    o.adaptive = true;
    o.truncation_tolerance = tolerance;
    const auto adaptive = balance(flow, shot.u0, shot.v0, 10, 1, o);
    const auto first = balance(flow, shot.u0, shot.v0, 10);
    const auto direct = balance(flow, shot.u0, shot.v0, adaptive.harmonics);
    std::cout << "adaptive forced harmonic balance, tolerance " << tolerance << ": H = "
              << adaptive.harmonics << " after " << adaptive.harmonics_tried.size()
              << " solves, truncation " << adaptive.truncation << "\n";
    ASSERT_GE(adaptive.harmonics_tried.size(), 2u) << "H = 10 should not be enough";
    for (std::size_t k = 0; k < adaptive.harmonics_tried.size(); ++k)
      EXPECT_EQ(adaptive.harmonics_tried[k], 10 << k);
    EXPECT_LE(adaptive.truncation, tolerance);
    EXPECT_GT(first.truncation, tolerance);
    EXPECT_LT((adaptive.orbit.u0 - direct.orbit.u0).norm(), 1e-10 * direct.orbit.u0.norm());
    EXPECT_LT(state_distance(adaptive.orbit, shot, b.w), state_distance(first.orbit, shot, b.w));
  }
}

TEST(ForcedHarmonicBalance, ExactAndSampledIntegrationAgree) {
  Bilinear b;
  const auto field = b.oscillator().field();
  const nbm::ExactFlow flow(field, b.damping(), b.load());
  const auto exact = balance(flow, Vector::Constant(1, 0.3), Vector::Zero(1), 10);
  nbm::HarmonicBalanceOptions aft;
  aft.integration = nbm::HarmonicBalanceOptions::Integration::aft;
  double previous = 1;
  for (int samples : {128, 512, 2048}) {
    aft.aft_samples = samples;
    const auto sampled =
        balance(flow, Vector::Constant(1, 0.3), Vector::Zero(1), 10, 1, aft);
    const double gap = (sampled.coefficients - exact.coefficients).norm() /
                       exact.coefficients.norm();
    EXPECT_LT(gap, previous) << samples;
    previous = gap;
  }
  std::cout << "AFT at 2048 samples against exact integration: " << previous << "\n";
  EXPECT_LT(previous, 1e-4);  // measured 1.3e-6: the switching times to ~1 / samples
}

TEST(ForcedHarmonicBalance, BadOptionsAreNamedErrors) {
  Bilinear b;
  const auto field = b.oscillator().field();
  const nbm::ExactFlow unforced(field);
  const Vector z = Vector::Zero(1);
  EXPECT_THROW(balance(unforced, z, z, 5), nbm::InputError);
  const nbm::ExactFlow flow(field, b.damping(), b.load());
  auto message = [&](int H, int m, const nbm::HarmonicBalanceOptions& o,
                     const Vector& u = Vector::Zero(1)) {
    try {
      balance(flow, u, Vector::Zero(1), H, m, o);
    } catch (const nbm::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(1, 2, {}).find("harmonics H = 1, expected H >= the subharmonic"),
            std::string::npos);
  EXPECT_NE(message(5, 0, {}).find("subharmonic order m must be >= 1"), std::string::npos);
  nbm::HarmonicBalanceOptions o;
  o.transient_periods = -1;
  EXPECT_NE(message(5, 1, o).find("transient_periods"), std::string::npos);
  o = {};
  o.integration = nbm::HarmonicBalanceOptions::Integration::aft;
  o.aft_samples = -1;
  EXPECT_NE(message(5, 1, o).find("aft_samples"), std::string::npos);
  o = {};
  o.max_iterations = 0;
  EXPECT_NE(message(5, 1, o).find("max_iterations"), std::string::npos);
  EXPECT_NE(message(5, 1, {}, Vector::Zero(2)).find("initial state of size 2"), std::string::npos);
  EXPECT_NE(message(5, 1, {}, Vector::Constant(1, NAN)).find("non-finite"), std::string::npos);
  // The excitation fixes the period and the time origin: no series even in
  // time, no amplitude condition, no other period.
  o = {};
  o.cosine_only = true;
  EXPECT_NE(message(5, 1, o).find("cosine_only is an autonomous orbit's"), std::string::npos);
  o = {};
  o.amplitude = 0.2;
  EXPECT_NE(message(5, 1, o).find("the amplitude condition is an autonomous orbit's"),
            std::string::npos);
  const nbm::PeriodicProblem forced(flow, 1);
  try {
    nbm::harmonic_balance(forced, z, z, 0.9 * forced.period(), {});
    ADD_FAILURE() << "a period that is not the excitation's was accepted";
  } catch (const nbm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("forced harmonic balance: the period"),
              std::string::npos);
  }
}

}  // namespace
