// Continuation of forced periodic orbits (method.md §9, "Continuation of
// forced orbits"): the linear limit against the frequency response of the
// full damped model, in frequency and in amplitude; the forced bilinear
// oscillator's fold pair, unstable branch and grazing against closed-form
// and brute-force references; a period doubling confirmed by the period-2
// orbit of branch switching; step control and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "bilinear_oscillator.hpp"
#include "errors.hpp"
#include "forced_continuation.hpp"
#include "forced_models.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::Bilinear;
using nbm_test::ForcedChain;
using nbm_test::internal;
using Complex = std::complex<double>;

// The chain of the forced-orbit linear-limit test, gap out of reach, with
// its load: F0 + Fc1 cos wt + Fs1 sin wt + Fc2 cos 2wt (interior dofs).
struct LinearChain {
  ForcedChain chain;
  Vector F0, Fc1, Fs1, Fc2;
  nbm::Damping damping;
  LinearChain() {
    chain.n = 4;
    const Index n = chain.n;
    F0.resize(n), Fc1.resize(n), Fs1.resize(n), Fc2.resize(n);
    for (Index i = 0; i < n; ++i)
      F0(i) = 0.1 * (i - 1), Fc1(i) = 1 - 0.3 * i, Fs1(i) = 0.2 * i,
      Fc2(i) = 0.1 * std::sin(i + 1.0);
    damping.a_M = 0.05, damping.b_K = 0.01;
  }
  nbm::HarmonicLoad load(double w) const {
    nbm::HarmonicLoad l;
    l.omega = w;
    l.cos = {internal(Fc1), internal(Fc2)};
    l.sin = {internal(Fs1)};
    return l;
  }
  /// The steady response of the full damped model M u'' + C u' + K u = F(t)
  /// at t = 0 (massless contact dof: its row is the nodal boundary
  /// relation), harmonics times `scale`: u = K^-1 F0 + scale sum_k Re(U_k),
  /// Z_k U_k = Fc_k - i Fs_k, Z_k = K - (k w)^2 M + i k w C. Interior (u, v).
  std::pair<Vector, Vector> response(double w, double scale = 1) const {
    const Index n = chain.n;
    const Matrix M = chain.M(), K = chain.K(), C = damping.a_M * M + damping.b_K * K;
    Vector u = K.ldlt().solve(internal(F0)), v = Vector::Zero(n + 1);
    const std::vector<Eigen::VectorXcd> Fhat = {
        internal(Fc1).cast<Complex>() - Complex(0, 1) * internal(Fs1).cast<Complex>(),
        internal(Fc2).cast<Complex>()};
    for (int k = 0; k < 2; ++k) {
      const double W = (k + 1) * w;
      const Eigen::MatrixXcd Z =
          K.cast<Complex>() - W * W * M.cast<Complex>() + Complex(0, W) * C.cast<Complex>();
      const Eigen::VectorXcd U = scale * Z.partialPivLu().solve(Fhat[k]);
      u += U.real();
      v += (Complex(0, W) * U).real();
    }
    return {u.head(n), v.head(n)};
  }
};

TEST(ForcedContinuation, LinearLimitFrequencyCurveIsTheDampedFrequencyResponse) {
  const LinearChain lc;
  const auto field = lc.chain.field(internal(lc.F0));
  nbm::ForcedContinuationOptions o;
  o.parameter_min = 0.3, o.parameter_max = 2.5;
  o.step = 0.05, o.max_step = 0.1;
  const Index n = lc.chain.n;
  const auto curve = nbm::continue_forced(field, lc.damping, lc.load(0.4), Vector::Zero(n),
                                          Vector::Zero(n), o);
  EXPECT_EQ(curve.stop, nbm::ForcedStop::parameter_bound) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 20u) << curve.stop_reason;
  EXPECT_NEAR(curve.points.back().parameter, 2.5, 1e-12);
  for (std::size_t i = 0; i < curve.points.size(); ++i) {
    const auto& pt = curve.points[i];
    const auto [u, v] = lc.response(pt.omega);
    EXPECT_LT((pt.orbit.u0 - u).norm(), 1e-10 * u.norm()) << "point " << i << " w " << pt.omega;
    EXPECT_LT((pt.orbit.v0 - v).norm(), 1e-10 * std::max(v.norm(), u.norm() * pt.omega))
        << "point " << i << " w " << pt.omega;
    EXPECT_EQ(pt.switches, 0);
    EXPECT_TRUE(pt.orbit.stable);
    if (i > 0) {
      EXPECT_GT(pt.parameter, curve.points[i - 1].parameter);
    }
  }
  EXPECT_TRUE(curve.events.empty()) << curve.events.front().description;
}

TEST(ForcedContinuation, AmplitudeCurveOfTheLinearLimitIsLinearInTheScale) {
  const LinearChain lc;
  const auto field = lc.chain.field(internal(lc.F0));
  nbm::ForcedContinuationOptions o;
  o.parameter = nbm::ForcedParameter::amplitude;
  o.parameter_min = 0, o.parameter_max = 4;
  o.direction = -1;  // down to 0, then stop on the bound
  const Index n = lc.chain.n;
  const double w = 1.1;
  const auto curve = nbm::continue_forced(field, lc.damping, lc.load(w), Vector::Zero(n),
                                          Vector::Zero(n), o);
  EXPECT_EQ(curve.stop, nbm::ForcedStop::parameter_bound) << curve.stop_reason;
  EXPECT_NEAR(curve.points.back().parameter, 0, 1e-12);
  ASSERT_GE(curve.points.size(), 3u);
  for (const auto& pt : curve.points) {
    EXPECT_EQ(pt.omega, w);
    EXPECT_EQ(pt.scale, pt.parameter);
    const auto [u, v] = lc.response(w, pt.scale);
    const auto [u1, v1] = lc.response(w);
    EXPECT_LT((pt.orbit.u0 - u).norm(), 1e-10 * u1.norm()) << "scale " << pt.scale;
    EXPECT_LT((pt.orbit.v0 - v).norm(), 1e-10 * std::max(v1.norm(), u1.norm() * w))
        << "scale " << pt.scale;
  }
  EXPECT_TRUE(curve.events.empty());
}

// Grazing of the bilinear oscillator from the contact-free side: the linear
// response's amplitude F / |k - w^2 + i a_M w| reaches the gap g.
double grazing_frequency(const Bilinear& b, double lo, double hi) {
  auto excess = [&](double w) {
    return b.F / std::abs(Complex(b.k - w * w, b.a_M * w)) - b.g;
  };
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) * excess(lo) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The hardening bilinear oscillator of test_forced_orbits.cpp (three orbits
// at w = 1.3), swept through its resonance: the upper branch grazes, turns at
// a fold, comes back unstable to a second fold and rejoins the contact-free
// branch, which grazes again on the way.
TEST(ForcedContinuation, BilinearSweepFindsTwoFoldsWithTheUnstableBranchBetween) {
  Bilinear b;
  b.w = 0.5;
  const auto field = b.oscillator().field();
  nbm::ForcedContinuationOptions o;
  o.parameter_min = 0.5, o.parameter_max = 1.8;
  o.step = 0.05, o.max_step = 0.1;
  const auto curve =
      nbm::continue_forced(field, b.damping(), b.load(), Vector::Zero(1), Vector::Zero(1), o);
  EXPECT_EQ(curve.stop, nbm::ForcedStop::parameter_bound) << curve.stop_reason;
  std::vector<nbm::ForcedEvent> folds, grazings;
  for (const auto& e : curve.events) {
    if (e.kind == nbm::ForcedEventKind::fold) folds.push_back(e);
    if (e.kind == nbm::ForcedEventKind::grazing) grazings.push_back(e);
    EXPECT_TRUE(e.kind == nbm::ForcedEventKind::fold || e.kind == nbm::ForcedEventKind::grazing)
        << e.description;
    EXPECT_TRUE(e.bisected) << e.description;
  }
  ASSERT_EQ(folds.size(), 2u) << curve.stop_reason;
  const auto& P = curve.points;
  for (std::size_t f = 0; f < 2; ++f) {
    const auto& e = folds[f];
    // The frequency turns: a maximum (first fold) or a minimum (second) of
    // omega along the curve, against its neighbours on both sides.
    const double sign = f == 0 ? 1 : -1;
    for (Index j = std::max<Index>(0, e.point - 2);
         j <= std::min<Index>(P.size() - 1, e.point + 3); ++j)
      EXPECT_GE(sign * (e.parameter - P[j].parameter), 0) << e.description << " point " << j;
    EXPECT_LT(P[e.point].tangent_parameter * P[e.point + 1].tangent_parameter, 0);
    EXPECT_LT(std::abs(e.multiplier - 1.0), 1e-3) << e.description;
    EXPECT_EQ(e.multiplier.imag(), 0);
  }
  EXPECT_GT(folds[0].parameter, 1.3);
  EXPECT_LT(folds[1].parameter, 1.3);
  for (Index j = 0; j < static_cast<Index>(P.size()); ++j) {
    const bool between = j > folds[0].point && j <= folds[1].point;
    EXPECT_EQ(P[j].orbit.stable, !between) << "point " << j << " w " << P[j].omega;
  }
  // Grazing twice: on the way up (contact appears) and back on the lower
  // branch (contact vanishes), each where the contact-free amplitude is g.
  ASSERT_EQ(grazings.size(), 2u);
  EXPECT_NEAR(grazings[0].parameter, grazing_frequency(b, 0.5, 1.0), 1e-7);
  EXPECT_NEAR(grazings[1].parameter, grazing_frequency(b, 1.05, 1.8), 1e-7);
  EXPECT_EQ(P[grazings[0].point].switches, 0);
  EXPECT_GT(P[grazings[0].point + 1].switches, 0);

  // Stable points against brute-force RK4 to steady state, started 1e-3
  // away: the first point, the upper branch at the first fold's last point,
  // and the last point.
  for (Index j : {Index(0), folds[0].point, static_cast<Index>(P.size()) - 1}) {
    Bilinear bj = b;
    bj.w = P[j].omega;
    const Eigen::Vector2d x(P[j].orbit.u0(0), P[j].orbit.v0(0));
    const Eigen::Vector2d steady = bj.steady_state(x + Eigen::Vector2d(1e-3, -1e-3));
    EXPECT_NEAR(x(0), steady(0), 2e-8) << "w " << bj.w;
    EXPECT_NEAR(x(1), steady(1), 2e-8) << "w " << bj.w;
  }
}

}  // namespace
