// Harmonic balance against closed-form periods (benchmarks.md §E) and
// against shooting on the bar (benchmarks.md §C, F).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "bars.hpp"
#include "oscillators.hpp"
#include "periodic/harmonic_balance.hpp"

namespace {

using nbm::HarmonicBalanceOptions;
using nbm::Vector;
using nbm_test::ImpactOscillator;

double period_error(const ImpactOscillator& osc, const HarmonicBalanceOptions& opt,
                    double guess_factor, nbm::HarmonicBalanceResult* out = nullptr) {
  const auto field = osc.field();
  const double exact = osc.period(3);
  auto r = nbm::harmonic_balance(field, Vector::Constant(1, -3), Vector::Zero(1),
                                 guess_factor * exact, opt);
  if (out) *out = r;
  return std::abs(r.orbit.period - exact) / exact;
}

HarmonicBalanceOptions options(int H, bool cosine_only) {
  HarmonicBalanceOptions o;
  o.harmonics = H;
  o.cosine_only = cosine_only;
  o.amplitude = -3;
  return o;
}

TEST(HarmonicBalance, MasslessOscillatorToOneInTenToTheEightAtFortyHarmonics) {
  ImpactOscillator osc;  // k_c / k = 1
  for (bool cosine_only : {true, false}) {
    nbm::HarmonicBalanceResult r;
    const double error = period_error(osc, options(40, cosine_only), 1.1, &r);
    std::cout << "k_c/k = 1, H = 40, cosine only " << cosine_only << ": relative period error "
              << error << "\n";
    EXPECT_LE(error, 1e-8) << cosine_only;
    EXPECT_LE(r.residual, 1e-12);
    EXPECT_EQ(r.orbit.switches.size(), 2u);
    // The exact flow from the series' initial state is periodic to the
    // truncation error.
    EXPECT_LE(r.orbit.periodicity_residual, 1e-7);
  }
}

TEST(HarmonicBalance, MasslessOscillatorConvergesFasterThanHToTheMinusTwo) {
  ImpactOscillator osc;
  osc.kc = 10;
  const double e10 = period_error(osc, options(10, true), 1.02);
  const double e80 = period_error(osc, options(80, true), 1.02);
  std::cout << "k_c/k = 10: relative period error " << e10 << " (H = 10), " << e80 << " (H = 80)\n";
  EXPECT_GT(std::log(e10 / e80) / std::log(8.0), 2.0) << e10 << " " << e80;
}

TEST(HarmonicBalance, StiffContactSpringToOneInAMillionWithTheHarmonicsItNeeds) {
  // k_c / k = 1e4: the contact phase lasts 0.8% of the period. The basin of
  // Newton's method is narrow (a guess 1% off the period fails): the guess
  // is 0.1% off.
  ImpactOscillator osc;
  osc.kc = 1e4;
  HarmonicBalanceOptions o = options(80, true);
  o.adaptive = true;
  o.truncation_tolerance = 1e-3;
  nbm::HarmonicBalanceResult r;
  const double error = period_error(osc, o, 1.001, &r);
  std::cout << "k_c/k = 1e4, H = " << r.harmonics << ": relative period error " << error << "\n";
  EXPECT_LE(error, 1e-6);
  EXPECT_EQ(r.harmonics, 320);
  EXPECT_EQ(r.harmonics_tried, (std::vector<int>{80, 160, 320}));
  EXPECT_LE(r.truncation, 1e-3);
}

TEST(HarmonicBalance, MassJumpConvergesLikeOneOverH) {
  // With mass on the contact dof the acceleration jumps at switches: the
  // series converges like 1/H (benchmarks.md §F). Exact and AFT agree.
  ImpactOscillator osc;
  osc.mB = 0.5;
  std::vector<double> err;
  for (int H : {10, 20, 40, 80}) err.push_back(period_error(osc, options(H, true), 1.02));
  for (std::size_t k = 1; k < err.size(); ++k) {
    const double rate = std::log2(err[k - 1] / err[k]);
    EXPECT_GT(rate, 0.8) << k;
    EXPECT_LT(rate, 1.3) << k;
  }
  HarmonicBalanceOptions aft = options(40, true);
  aft.integration = HarmonicBalanceOptions::Integration::aft;
  double previous = 1;
  for (int samples : {256, 2048, 16384}) {
    aft.aft_samples = samples;
    nbm::HarmonicBalanceResult exact, sampled;
    period_error(osc, options(40, true), 1.02, &exact);
    period_error(osc, aft, 1.02, &sampled);
    const double gap = std::abs(sampled.orbit.period - exact.orbit.period) / exact.orbit.period;
    EXPECT_LT(gap, previous) << samples;
    previous = gap;
  }
  EXPECT_LT(previous, 1e-5);  // the sampling error decays like 1/samples
}

TEST(HarmonicBalance, AgreesWithShootingOnTheMasslessBar) {
  nbm_test::GapBar bar;
  bar.N = 10, bar.massless = true;
  const auto field = bar.field();
  const Eigen::Index n = field.size();
  Vector u0(n);
  for (Eigen::Index k = 0; k < n; ++k)
    u0(k) = nbm_test::continuum_rest_profile(bar, 0.3, bar.x_of_interior(static_cast<int>(k)));
  nbm::ShootingOptions s;
  s.half_period = true;
  s.probe = n - 1;
  const auto shot = nbm::shoot(field, u0, Vector::Zero(n), 3.7, s);
  HarmonicBalanceOptions o;
  o.cosine_only = true;
  o.harmonics = 80;
  o.probe = n - 1;
  o.amplitude = shot.u0(n - 1);
  const auto hb = nbm::harmonic_balance(field, u0, Vector::Zero(n), 1.01 * shot.period, o);
  EXPECT_NEAR(hb.orbit.period, shot.period, 1e-6 * shot.period);
  EXPECT_LE((hb.orbit.u0 - shot.u0).norm(), 1e-4 * shot.u0.norm());
  EXPECT_EQ(hb.orbit.switches.size(), shot.switches.size());
}

TEST(HarmonicBalance, RejectsBadOptions) {
  ImpactOscillator osc;
  const auto field = osc.field();
  HarmonicBalanceOptions o = options(0, true);
  EXPECT_THROW(nbm::harmonic_balance(field, Vector::Constant(1, -3), Vector::Zero(1), 6, o),
               std::invalid_argument);
  o = options(10, true);
  o.probe = 1;
  EXPECT_THROW(nbm::harmonic_balance(field, Vector::Constant(1, -3), Vector::Zero(1), 6, o),
               std::invalid_argument);
  o.probe = 0;
  EXPECT_THROW(nbm::harmonic_balance(field, Vector::Constant(1, -3), Vector::Zero(1), -1, o),
               std::invalid_argument);
  EXPECT_THROW(nbm::harmonic_balance(field, Vector::Constant(2, -3), Vector::Zero(2), 6, o),
               std::invalid_argument);
}

}  // namespace
