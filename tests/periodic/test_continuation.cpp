// Pseudo-arclength continuation (continuation.hpp) on the impact oscillator
// of benchmarks.md §E, whose family of orbits is known in closed form: the
// period is constant below grazing (so the period cannot parametrise the
// family there) and falls beyond it, with a kink at grazing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "oscillators.hpp"
#include "periodic/continuation.hpp"

namespace {

using nbm::Vector;
using nbm_test::ImpactOscillator;

struct FamilyCase {
  double kc, mB;
  bool half;
};

// Readable, stable test names and printed values (gtest would otherwise print
// the raw bytes of the parameter): "kc10_mB0p5_full".
std::string case_name(const FamilyCase& c) {
  using nbm_test::name_word;
  return "kc" + name_word(c.kc) + "_mB" + name_word(c.mB) + (c.half ? "_half" : "_full");
}
void PrintTo(const FamilyCase& c, std::ostream* os) { *os << case_name(c); }

class ContinuationOnOscillator : public ::testing::TestWithParam<FamilyCase> {};

TEST_P(ContinuationOnOscillator, FollowsTheClosedFormFamilyThroughGrazing) {
  const auto [kc, mB, half] = GetParam();
  ImpactOscillator osc;
  osc.kc = kc, osc.mB = mB;
  const auto field = osc.field();
  // Two orbits below grazing (amplitude A = -u0 < g), by the displacement
  // condition, then continuation up to A = 4 g.
  nbm::ShootingOptions o;
  o.half_period = half;
  std::vector<nbm::PeriodicOrbit> family;
  for (double A : {0.5, 0.55}) {
    o.amplitude = -A * osc.g;
    family.push_back(nbm::shoot(field, Vector::Constant(1, -A * osc.g), Vector::Zero(1),
                                osc.period(A * osc.g), o));
  }
  nbm::ContinuationOptions c;
  c.length = osc.g, c.time = osc.period(0), c.velocity = osc.g / c.time;
  c.step = 0.1;
  int steps = 0;
  while (-family.back().u0(0) < 4 * osc.g) {
    ASSERT_LT(++steps, 200) << "the family did not reach 4 g";
    const auto& last = family.back();
    const auto next = nbm::continuation_step(field, family[family.size() - 2], last, o, c);
    const double A = -next.u0(0);
    EXPECT_NEAR(next.period, osc.period(A), 1e-10 * next.period) << "A = " << A;
    EXPECT_LE(std::abs(next.v0(0)), 1e-12 * osc.g / c.time);
    EXPECT_LE(next.periodicity_residual, 1e-10);
    EXPECT_EQ(next.switches.size(), A > osc.g ? 2u : 0u);
    // On the hyperplane orthogonal to the secant, one step beyond the last
    // orbit (scaled unknowns; v0 = 0 along this family).
    const auto& before = family[family.size() - 2];
    const Eigen::Vector2d secant =
        Eigen::Vector2d((last.u0(0) - before.u0(0)) / c.length, (last.period - before.period) / c.time)
            .normalized();
    const Eigen::Vector2d advance((next.u0(0) - last.u0(0)) / c.length,
                                  (next.period - last.period) / c.time);
    EXPECT_NEAR(secant.dot(advance), c.step, 1e-9);
    EXPECT_LE(advance.norm(), 1.5 * c.step);
    EXPECT_GT(A, -last.u0(0));  // the family is followed forwards
    family.push_back(next);
  }
  EXPECT_LT(family.back().period, 0.99 * osc.period(0));
}

INSTANTIATE_TEST_SUITE_P(ClosedForms, ContinuationOnOscillator,
                         ::testing::Values(FamilyCase{1, 0, false}, FamilyCase{10, 0, true},
                                           FamilyCase{10, 0.5, false}, FamilyCase{100, 0.2, true}),
                         [](const ::testing::TestParamInfo<FamilyCase>& info) {
                           return case_name(info.param);
                         });

TEST(Continuation, RejectsBadSteps) {
  const auto field = ImpactOscillator{}.field();
  nbm::PeriodicOrbit a;
  a.u0 = Vector::Ones(1), a.v0 = Vector::Zero(1), a.period = 4;
  nbm::ShootingOptions o;
  nbm::ContinuationOptions c;
  EXPECT_THROW(nbm::continuation_step(field, a, a, o, c), nbm::InputError);  // no direction
  nbm::PeriodicOrbit b = a;
  b.period = 4.1;
  c.step = 0;
  EXPECT_THROW(nbm::continuation_step(field, a, b, o, c), nbm::InputError);
  c.step = 0.1;
  b.u0 = Vector::Ones(2);
  EXPECT_THROW(nbm::continuation_step(field, a, b, o, c), nbm::InputError);
}

}  // namespace
