// Shooting on the exact flow against closed-form periods (benchmarks.md §E).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "oscillators.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Vector;
using nbm_test::ImpactOscillator;

TEST(ImpactOscillatorPeriod, ClosedFormReproducesTheReferenceValues) {
  ImpactOscillator o;
  EXPECT_NEAR(o.period(3), 5.6962557937, 1e-10);
  o.kc = 10;
  EXPECT_NEAR(o.period(3), 4.7044517102, 1e-10);
  o.kc = 1e4;
  EXPECT_NEAR(o.period(3), 3.8526101250, 1e-10);
  o.kc = 1, o.mB = 0.5;
  EXPECT_NEAR(o.period(3), 6.4813232912, 1e-10);
}

struct OscillatorCase {
  double kc, mB, A;
};

// Readable, stable test names and printed values (gtest would otherwise print
// the raw bytes of the parameter): "kc10_mB0p5_A3".
std::string case_name(const OscillatorCase& c) {
  using nbm_test::name_word;
  return "kc" + name_word(c.kc) + "_mB" + name_word(c.mB) + "_A" + name_word(c.A);
}
void PrintTo(const OscillatorCase& c, std::ostream* os) { *os << case_name(c); }

class ShootingOnOscillator : public ::testing::TestWithParam<OscillatorCase> {};

TEST_P(ShootingOnOscillator, FindsTheExactPeriod) {
  const auto [kc, mB, A] = GetParam();
  ImpactOscillator osc;
  osc.kc = kc, osc.mB = mB;
  const auto field = osc.field();
  const double exact = osc.period(A);
  for (bool half : {false, true}) {
    nbm::ShootingOptions opt;
    opt.half_period = half;
    opt.amplitude = -A;
    // A rough guess: period 15% off, amplitude 10% off, a small velocity.
    const auto orbit = nbm::shoot(field, Vector::Constant(1, -1.1 * A),
                                  Vector::Constant(1, half ? 0 : 0.1), 1.15 * exact, opt);
    EXPECT_NEAR(orbit.period, exact, 1e-10 * exact) << "half " << half;
    EXPECT_LE(orbit.periodicity_residual, 1e-10);
    EXPECT_NEAR(orbit.u0(0), -A, 1e-12 * A);
    EXPECT_EQ(orbit.switches.size(), A > osc.g ? 2u : 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    ClosedForms, ShootingOnOscillator,
    ::testing::Values(OscillatorCase{1, 0, 3}, OscillatorCase{10, 0, 3}, OscillatorCase{1e4, 0, 3},
                      OscillatorCase{1, 0.5, 3}, OscillatorCase{3, 0.2, 1.5},
                      OscillatorCase{1, 0, 0.8}),
    [](const ::testing::TestParamInfo<OscillatorCase>& info) { return case_name(info.param); });

}  // namespace
