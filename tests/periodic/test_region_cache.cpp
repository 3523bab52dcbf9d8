// The region cache of ReducedField is bounded by bytes: with a budget below
// one region (nothing cached) or of one region (constant eviction along a
// contact orbit), shooting and harmonic balance give bit-identical results
// and the cache stays within its budget.
#include <gtest/gtest.h>

#include "bars.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/shooting.hpp"

namespace {

using Index = Eigen::Index;
using nbm::Vector;

struct OrbitPair {
  nbm::PeriodicOrbit shot;
  nbm::HarmonicBalanceResult hb;
};

OrbitPair orbits(const nbm::ReducedField& field, const nbm_test::GapBar& bar) {
  const Index n = field.size();
  Vector u0(n);
  for (Index k = 0; k < n; ++k)
    u0(k) = nbm_test::continuum_rest_profile(bar, 0.3, bar.x_of_interior(static_cast<int>(k)));
  nbm::ShootingOptions s;
  s.half_period = true;
  s.probe = n - 1;
  OrbitPair r;
  r.shot = nbm::shoot(field, u0, Vector::Zero(n), 3.7, s);
  nbm::HarmonicBalanceOptions o;
  o.cosine_only = true;
  o.harmonics = 20;
  o.probe = n - 1;
  r.hb = nbm::harmonic_balance(field, u0, Vector::Zero(n), 1.01 * r.shot.period, o);
  return r;
}

TEST(RegionCache, DefaultBudgetIs256MiB) {
  nbm_test::GapBar bar;
  EXPECT_EQ(bar.field().region_cache_budget(), std::size_t{256} << 20);
}

TEST(RegionCache, ATinyBudgetGivesIdenticalOrbitsAndStaysWithinIt) {
  nbm_test::GapBar bar;
  bar.N = 10, bar.massless = true;
  const auto reference_field = bar.field();
  const OrbitPair reference = orbits(reference_field, bar);
  ASSERT_GE(reference_field.region_cache_size(), 2u);  // open and closed at least
  const std::size_t one =
      nbm::ReducedField::bytes_of(*reference_field.region(reference.shot.switches.at(0).after));
  for (const std::size_t budget : {std::size_t{1}, one, one + one / 2}) {
    auto field = bar.field();
    field.set_region_cache_budget(budget);
    const OrbitPair run = orbits(field, bar);
    EXPECT_LE(field.region_cache_bytes(), budget) << budget;
    EXPECT_LE(field.region_cache_size(), budget < one ? 0u : 1u) << budget;
    EXPECT_EQ(run.shot.period, reference.shot.period) << budget;
    EXPECT_EQ(run.shot.u0, reference.shot.u0) << budget;
    EXPECT_EQ(run.shot.iterations, reference.shot.iterations) << budget;
    EXPECT_EQ(run.shot.residual_history, reference.shot.residual_history) << budget;
    EXPECT_EQ(run.hb.coefficients, reference.hb.coefficients) << budget;
    EXPECT_EQ(run.hb.orbit.period, reference.hb.orbit.period) << budget;
    EXPECT_EQ(run.hb.orbit.residual_history, reference.hb.orbit.residual_history) << budget;
  }
  // Lowering the budget of a full cache evicts down to it.
  auto field = bar.field();
  orbits(field, bar);
  ASSERT_GT(field.region_cache_bytes(), one);
  field.set_region_cache_budget(one);
  EXPECT_LE(field.region_cache_bytes(), one);
  EXPECT_EQ(field.region_cache_size(), 1u);
}

}  // namespace
