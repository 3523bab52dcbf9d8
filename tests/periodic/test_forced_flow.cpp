// The exact flow with Rayleigh damping and a harmonic load (method.md §9):
// the region flow and its transition matrix against a matrix exponential of
// the same linear system (under-, critically and over-damped modes, rigid
// modes), the monodromy through switches against finite differences, and a
// switching search that does not miss grazing crossings.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "base/errors.hpp"
#include "forced_models.hpp"
#include "oscillators.hpp"
#include "periodic/exact_flow.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::ForcedChain;
using nbm_test::internal;

struct FlowCase {
  const char* name;
  double ground, a_M, b_K;
};

// Single-region flow (gap out of reach) against the matrix exponential.
void expect_region_flow_matches_exponential(const FlowCase& c, Index n) {
  ForcedChain chain;
  chain.n = n;
  chain.ground = c.ground;
  Vector F0(n), Fc1(n), Fs1(n), Fc2(n), Fs2(n);
  for (Index i = 0; i < n; ++i) {
    F0(i) = -0.3 + 0.1 * i;
    Fc1(i) = 0.7 - 0.2 * i, Fs1(i) = 0.1 * i;
    Fc2(i) = 0.05 * (i + 1), Fs2(i) = -0.3;
  }
  const auto field = chain.field(internal(F0));
  nbm::Damping damping;
  damping.a_M = c.a_M, damping.b_K = c.b_K;
  nbm::HarmonicLoad load;
  load.omega = 1.3;
  load.cos = {internal(Fc1), internal(Fc2)};
  load.sin = {internal(Fs1), internal(Fs2)};
  const nbm::ExactFlow flow(field, damping, load);

  const Matrix M = chain.M().topLeftCorner(n, n), K = chain.reduced_K();
  const Matrix C = c.a_M * M + c.b_K * K;
  Vector u0(n), v0(n);
  for (Index i = 0; i < n; ++i) u0(i) = 0.2 - 0.15 * i, v0(i) = 0.4 * std::cos(i);
  for (double t0 : {0.0, 0.7}) {
    for (double t : {0.3, 2.0, 9.0}) {
      Matrix X_ref;
      const Vector ref = nbm_test::reference_flow(M, C, K, F0, {Fc1, Fc2}, {Fs1, Fs2}, load.omega,
                                                  u0, v0, t0, t, &X_ref);
      const auto r = flow.integrate(u0, v0, t, true, {}, t0);
      ASSERT_TRUE(r.switches.empty());
      Vector x(2 * n);
      x << r.u, r.v;
      EXPECT_LT((x - ref).norm(), 1e-11 * std::max(1.0, ref.norm()))
          << c.name << " t0 " << t0 << " t " << t << "\n"
          << x.transpose() << "\n"
          << ref.transpose();
      EXPECT_LT((r.monodromy - X_ref).norm(), 1e-11 * std::max(1.0, X_ref.norm()))
          << c.name << " t0 " << t0 << " t " << t;
      // u'' at the end: the equation of motion, from the reference.
      const double W = load.omega;
      const Vector F = F0 + Fc1 * std::cos(W * (t0 + t)) + Fs1 * std::sin(W * (t0 + t)) +
                       Fc2 * std::cos(2 * W * (t0 + t)) + Fs2 * std::sin(2 * W * (t0 + t));
      const Vector a_ref = M.inverse() * (F - C * ref.tail(n) - K * ref.head(n));
      EXPECT_LT((r.a - a_ref).norm(), 1e-10 * std::max(1.0, a_ref.norm())) << c.name;
    }
  }
}

TEST(ForcedFlow, RegionFlowMatchesTheMatrixExponentialOfTheDampedForcedSystem) {
  for (const FlowCase& c : {FlowCase{"undamped", 1, 0, 0}, FlowCase{"light", 1, 0.05, 0.02},
                            FlowCase{"heavy_stiffness", 1, 0.1, 1.5},
                            FlowCase{"free_chain_undamped", 0, 0, 0},
                            FlowCase{"free_chain_damped", 0, 0.3, 0.1}})
    expect_region_flow_matches_exponential(c, 3);
}

// One interior dof with the contact open: q'' + a_M q' + q = F, w = 1, so
// a_M = 2 is exactly critical; a_M = 6 over-damped; a free mass (ground 0)
// is a rigid mode with and without damping.
TEST(ForcedFlow, OneDofUnderCriticalOverDampedAndRigidMatchTheExponential) {
  for (const FlowCase& c :
       {FlowCase{"under", 1, 0.3, 0}, FlowCase{"critical", 1, 2, 0}, FlowCase{"over", 1, 6, 0},
        FlowCase{"rigid", 0, 0, 0}, FlowCase{"rigid_damped", 0, 0.8, 0},
        FlowCase{"rigid_tiny_damping", 0, 1e-9, 0}}) {
    // ground 1 and kc 2 in series with a free contact dof: reduced stiffness 1.
    expect_region_flow_matches_exponential(c, 1);
  }
}

TEST(ForcedFlow, UndampedResonanceAndBadExcitationAreNamedErrors) {
  ForcedChain chain;
  chain.n = 1;
  const auto field = chain.field(Vector::Zero(2));
  nbm::HarmonicLoad load;
  load.omega = 1;  // the reduced frequency of the 1-dof chain
  load.cos = {internal(Vector::Ones(1))};
  const nbm::ExactFlow flow(field, nbm::Damping{}, load);
  EXPECT_THROW(flow.integrate(Vector::Zero(1), Vector::Zero(1), 1, false), nbm::NumericalError);

  nbm::Damping negative;
  negative.a_M = -1;
  EXPECT_THROW(nbm::ExactFlow(field, negative, load), nbm::InputError);
  nbm::HarmonicLoad wrong_size = load;
  wrong_size.sin = {Vector::Ones(3)};
  EXPECT_THROW(nbm::ExactFlow(field, nbm::Damping{}, wrong_size), nbm::InputError);
  nbm::HarmonicLoad no_frequency = load;
  no_frequency.omega = 0;
  EXPECT_THROW(nbm::ExactFlow(field, nbm::Damping{}, no_frequency), nbm::InputError);
}

// Monodromy through switches against central differences of the flow map,
// with damping (a stiffness-proportional part makes the acceleration jump at
// the switches even with a massless boundary) and a harmonic load.
void expect_forced_monodromy_matches_differences(double mB, double a_M, double b_K) {
  nbm_test::ImpactOscillator osc;
  osc.mB = mB;
  osc.kc = 10;
  const auto field = osc.field();
  nbm::Damping damping;
  damping.a_M = a_M, damping.b_K = b_K;
  nbm::HarmonicLoad load;
  load.omega = 0.9;
  load.cos = {Eigen::Vector2d(1.2, 0)};
  load.sin = {Eigen::Vector2d(0.4, 0)};
  nbm_test::expect_monodromy_matches_differences(
      nbm::ExactFlow(field, damping, load),
      "mB " + std::to_string(mB) + " b_K " + std::to_string(b_K));
}

TEST(ForcedFlow, MonodromyThroughSwitchesMatchesFiniteDifferences) {
  expect_forced_monodromy_matches_differences(0, 0.1, 0);
  expect_forced_monodromy_matches_differences(0, 0.05, 0.02);
  expect_forced_monodromy_matches_differences(0.5, 0.1, 0.02);
}

// A 1-dof free response u = V e^{-alpha t} S(t) (u0 = 0, v0 = V, reduced
// stiffness 1, c = a_M) has a single highest maximum at t1; a gap just
// below it is hit near t1, a gap just above it never.
void expect_first_peak_graze(double a_M) {
  const double alpha = 0.5 * a_M, d2 = 1 - alpha * alpha, V = 1;
  double t1, peak;
  if (d2 > 0) {
    const double d = std::sqrt(d2);
    t1 = std::atan2(d, alpha) / d;
    peak = V * std::exp(-alpha * t1) * std::sin(d * t1) / d;
  } else if (d2 == 0) {
    t1 = 1 / alpha;
    peak = V * t1 * std::exp(-1.0);
  } else {
    const double k = std::sqrt(-d2);
    t1 = std::atanh(k / alpha) / k;
    peak = V * std::exp(-alpha * t1) * std::sinh(k * t1) / k;
  }
  for (double rel : {-1e-9, 1e-9}) {
    ForcedChain chain;
    chain.n = 1;
    chain.gap = peak * (1 + rel);
    const auto field = chain.field(Vector::Zero(2));
    nbm::Damping damping;
    damping.a_M = a_M;
    const nbm::ExactFlow flow(field, damping, nbm::HarmonicLoad{});
    const auto r = flow.integrate(Vector::Zero(1), Vector::Constant(1, V), 40, false);
    if (rel > 0) {
      EXPECT_TRUE(r.switches.empty()) << "a_M " << a_M;
    } else {
      ASSERT_FALSE(r.switches.empty()) << "a_M " << a_M;
      // The dip is 1e-9 deep: the root is within sqrt(2e-9 peak / |u''|) of t1.
      EXPECT_NEAR(r.switches.front().t, t1, 1e-3) << "a_M " << a_M;
    }
  }
}

TEST(ForcedSwitching, GrazingPeakOfADampedFreeResponseIsFoundAndANearMissIsNot) {
  for (double a_M : {0.0, 0.1, 1.0, 2.0, 3.0}) expect_first_peak_graze(a_M);
}

// The steady forced response u = Re(Q e^{i w t}) of q'' + a_M q' + q = F cos w t
// (started on it: no free response) touching a gap 1e-9 below its amplitude
// at the predicted time, and none 1e-9 above.
TEST(ForcedSwitching, GrazingSteadyForcedResponseIsFoundAtItsPredictedTime) {
  const double a_M = 0.2, w = 0.7, F = 0.5;
  const std::complex<double> Q = F / std::complex<double>(1 - w * w, a_M * w);
  const double X = std::abs(Q);
  for (double rel : {-1e-9, 1e-9}) {
    ForcedChain chain;
    chain.n = 1;
    chain.gap = X * (1 + rel);
    const auto field = chain.field(Vector::Zero(2));
    nbm::Damping damping;
    damping.a_M = a_M;
    nbm::HarmonicLoad load;
    load.omega = w;
    load.cos = {internal(Vector::Constant(1, F))};
    const nbm::ExactFlow flow(field, damping, load);
    const Vector u0 = Vector::Constant(1, Q.real());
    const Vector v0 = Vector::Constant(1, (std::complex<double>(0, w) * Q).real());
    const auto r = flow.integrate(u0, v0, 10 * 2 * M_PI / w, false);
    if (rel > 0) {
      EXPECT_TRUE(r.switches.empty());
      continue;
    }
    ASSERT_FALSE(r.switches.empty());
    // First t > 0 with w t + arg Q = -acos(gap / X) (mod 2 pi).
    double t = (-std::acos(chain.gap / X) - std::arg(Q)) / w;
    while (t < 0) t += 2 * M_PI / w;
    EXPECT_NEAR(r.switches.front().t, t, 1e-9);
  }
}

// Random damped forced 3-dof chains: the gap is set just below the largest
// contact displacement seen on a fine grid, so that the contact grazes; the
// search must report a crossing no later than the grid's first negative gap.
TEST(ForcedSwitching, NeverMissesACrossingThatAFineGridSees) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1), P(0, 1);
  int grazes = 0;
  for (int trial = 0; trial < 40; ++trial) {
    ForcedChain chain;
    chain.n = 3;
    Vector F0(3), Fc(3), Fs(3), u0(3), v0(3);
    for (Index i = 0; i < 3; ++i) F0(i) = 0.2 * U(rng), Fc(i) = U(rng), Fs(i) = U(rng),
                                   u0(i) = U(rng), v0(i) = U(rng);
    nbm::Damping damping;
    damping.a_M = 0.3 * P(rng), damping.b_K = 0.3 * P(rng);
    nbm::HarmonicLoad load;
    load.omega = 0.3 + 2 * P(rng);
    load.cos = {internal(Fc)};
    load.sin = {internal(Fs)};
    const double T = 20;
    // Contact displacement u_C = u_O[n-1] (massless, open) on a fine grid.
    const int samples = 200000;
    std::vector<double> times(samples + 1);
    for (int k = 0; k <= samples; ++k) times[k] = T * k / samples;
    double top = -1e300;
    int top_k = 0;
    {
      const auto free_field = chain.field(internal(F0));
      const nbm::ExactFlow flow(free_field, damping, load);
      const auto r = flow.integrate(u0, v0, T, false, times);
      for (int k = 1; k <= samples; ++k)
        if (r.samples(2, k) > top) top = r.samples(2, k), top_k = k;
    }
    if (top <= u0(2) + 1e-6) continue;  // the largest value at the start: no graze
    chain.gap = top - 1e-7 * std::abs(top);
    const auto field = chain.field(internal(F0));
    const nbm::ExactFlow flow(field, damping, load);
    const auto r = flow.integrate(u0, v0, T, false);
    ASSERT_FALSE(r.switches.empty()) << "trial " << trial;
    EXPECT_LE(r.switches.front().t, times[top_k] + 1e-12) << "trial " << trial;
    ++grazes;
  }
  EXPECT_GE(grazes, 20);
}

}  // namespace
