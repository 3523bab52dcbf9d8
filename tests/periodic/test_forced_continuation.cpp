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

#include "base/errors.hpp"
#include "bilinear_oscillator.hpp"
#include "forced_models.hpp"
#include "periodic/forced_continuation.hpp"

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
// at w = 1.3), swept from w = 0.5 through its resonance: it grazes, goes
// through a period-doubling interval (the next test), climbs the upper
// branch to a fold, comes back unstable to a second fold, and leaves the
// contact at a second grazing onto the contact-free lower branch.
struct BilinearSweep {
  Bilinear b;
  nbm::ReducedField field = b.oscillator().field();
  nbm::ForcedContinuationOptions o;
  nbm::ForcedCurve curve;
  explicit BilinearSweep(bool locate_events = true) {
    b.w = 0.5;
    o.parameter_min = 0.5, o.parameter_max = 1.8;
    o.step = 0.05, o.max_step = 0.25, o.max_points = 400;
    o.locate_events = locate_events;
    curve = nbm::continue_forced(field, b.damping(), b.load(), Vector::Zero(1), Vector::Zero(1), o);
  }
  std::vector<nbm::ForcedEvent> events(nbm::ForcedEventKind kind) const {
    std::vector<nbm::ForcedEvent> out;
    for (const auto& e : curve.events)
      if (e.kind == kind) out.push_back(e);
    return out;
  }
};

TEST(ForcedContinuation, BilinearSweepFindsTwoFoldsWithTheUnstableBranchBetween) {
  const BilinearSweep sweep;
  const auto& curve = sweep.curve;
  const Bilinear& b = sweep.b;
  EXPECT_EQ(curve.stop, nbm::ForcedStop::parameter_bound) << curve.stop_reason;
  for (const auto& e : curve.events) {
    EXPECT_TRUE(e.bisected) << e.description;
    EXPECT_NE(e.kind, nbm::ForcedEventKind::neimark_sacker) << e.description;
  }
  const auto folds = sweep.events(nbm::ForcedEventKind::fold);
  const auto doublings = sweep.events(nbm::ForcedEventKind::period_doubling);
  const auto grazings = sweep.events(nbm::ForcedEventKind::grazing);
  ASSERT_EQ(folds.size(), 2u) << curve.stop_reason;
  ASSERT_EQ(doublings.size(), 2u);
  const auto& P = curve.points;
  for (std::size_t f = 0; f < 2; ++f) {
    const auto& e = folds[f];
    // The frequency turns: a maximum (first fold) or a minimum (second) of
    // omega along the curve, against its neighbours on both sides.
    const double sign = f == 0 ? 1 : -1;
    for (Index j = std::max<Index>(0, e.point - 3);
         j <= std::min<Index>(P.size() - 1, e.point + 4); ++j)
      EXPECT_GE(sign * (e.parameter - P[j].parameter), 0) << e.description << " point " << j;
    EXPECT_GT(sign * (P[e.point].parameter - P[e.point - 3].parameter), 0);
    EXPECT_GT(sign * (P[e.point + 1].parameter - P[e.point + 4].parameter), 0);
    EXPECT_LT(P[e.point].tangent_parameter * P[e.point + 1].tangent_parameter, 0);
    EXPECT_LT(std::abs(e.multiplier - 1.0), 1e-6) << e.description;  // measured 1e-10, 3e-8
    EXPECT_EQ(e.multiplier.imag(), 0);
  }
  EXPECT_GT(folds[0].parameter, 1.3);
  EXPECT_LT(folds[1].parameter, 1.3);
  // Unstable exactly between the folds and between the period doublings.
  for (Index j = 0; j < static_cast<Index>(P.size()); ++j) {
    const bool saddle = j > folds[0].point && j <= folds[1].point;
    const bool doubled = j > doublings[0].point && j <= doublings[1].point;
    EXPECT_EQ(P[j].orbit.stable, !saddle && !doubled) << "point " << j << " w " << P[j].omega;
  }
  // Grazing twice: on the way up (contact appears) and at the end of the
  // unstable branch (contact vanishes), each where the contact-free
  // amplitude F / |k - w^2 + i a_M w| is g.
  ASSERT_EQ(grazings.size(), 2u);
  // (Measured: 1.1e-10 and 1e-11; the bisection stops at 1e-8 in the
  // scaled arclength, P = 0.5.)
  EXPECT_NEAR(grazings[0].parameter, grazing_frequency(b, 0.5, 1.0), 1e-8);
  EXPECT_NEAR(grazings[1].parameter, grazing_frequency(b, 1.05, 1.8), 1e-8);
  EXPECT_EQ(P[grazings[0].point].switches, 0);
  EXPECT_GT(P[grazings[0].point + 1].switches, 0);
  EXPECT_GT(P[grazings[1].point].switches, 0);
  EXPECT_EQ(P[grazings[1].point + 1].switches, 0);
  EXPECT_GT(P[grazings[0].point].min_gap, 0);
  EXPECT_EQ(P[grazings[0].point + 1].min_gap, 0);

  // Stable points against brute-force RK4 to steady state, started 1e-3
  // away: the first point, the upper branch near w = 1.2 and the last point.
  Index upper = 0;
  for (Index j = 0; j < folds[0].point; ++j)
    if (std::abs(P[j].omega - 1.2) < std::abs(P[upper].omega - 1.2)) upper = j;
  for (Index j : {Index(0), upper, static_cast<Index>(P.size()) - 1}) {
    ASSERT_TRUE(P[j].orbit.stable);
    Bilinear bj = b;
    bj.w = P[j].omega;
    const Eigen::Vector2d x(P[j].orbit.u0(0), P[j].orbit.v0(0));
    const Eigen::Vector2d steady = bj.steady_state(x + Eigen::Vector2d(1e-3, -1e-3));
    EXPECT_NEAR(x(0), steady(0), 2e-8) << "w " << bj.w;
    EXPECT_NEAR(x(1), steady(1), 2e-8) << "w " << bj.w;
  }
}

// The same sweep crosses a period-doubling interval on the lower part of the
// contact branch: a real multiplier leaves the unit circle through -1 and
// comes back. Branch switching at the first one finds a period-2 orbit,
// confirmed by brute-force RK4: it comes back after two forcing periods, not
// after one.
TEST(ForcedContinuation, PeriodDoublingIsConfirmedByThePeriodTwoOrbit) {
  const BilinearSweep sweep;
  const auto doublings = sweep.events(nbm::ForcedEventKind::period_doubling);
  ASSERT_EQ(doublings.size(), 2u) << sweep.curve.stop_reason;
  const auto& P = sweep.curve.points;
  for (const auto& e : doublings) {
    EXPECT_TRUE(e.bisected);
    EXPECT_EQ(e.multiplier.imag(), 0);
    EXPECT_NEAR(e.multiplier.real(), -1, 1e-6) << e.description;  // measured 5e-9, 3e-10
    EXPECT_GT(P[e.point].switches, 0);
    // One side has a real multiplier below -1, the other none.
    auto below = [](const nbm::PeriodicOrbit& o) {
      return std::count_if(o.multipliers.begin(), o.multipliers.end(),
                           [](Complex mu) { return mu.imag() == 0 && mu.real() < -1; });
    };
    EXPECT_NE(below(P[e.point].orbit), below(P[e.point + 1].orbit));
  }
  const auto branch = nbm::switch_at_period_doubling(sweep.field, sweep.b.damping(), sweep.b.load(),
                                                     sweep.o, sweep.curve, doublings[0], 1e-2);
  EXPECT_NEAR(branch.parameter, doublings[0].parameter, 1e-2);
  EXPECT_GT(branch.separation, 1e-3);
  EXPECT_LT(branch.orbit.periodicity_residual, 1e-10);
  Bilinear b = sweep.b;
  b.w = branch.parameter;
  const Eigen::Vector2d x0(branch.orbit.u0(0), branch.orbit.v0(0));
  const Eigen::Vector2d once = b.integrate(x0, 1), twice = b.integrate(x0, 2);
  EXPECT_LT((twice - x0).norm(), 1e-7) << "a period-2 orbit of the RK4 flow";
  EXPECT_GT((once - x0).norm(), 1e-3) << "not the period-1 orbit";
  // The period-1 orbit it branched from is a fixed point of one period.
  const Eigen::Vector2d xs(doublings[0].orbit.u0(0), doublings[0].orbit.v0(0));
  Bilinear bs = sweep.b;
  bs.w = doublings[0].parameter;
  EXPECT_LT((bs.integrate(xs, 1) - xs).norm(), 1e-7);
  // The period-2 branch continues from there (m = 2, from that orbit at
  // that frequency), into the interval where the period-1 orbit is unstable.
  nbm::ForcedContinuationOptions o2 = sweep.o;
  o2.subharmonic = 2;
  o2.max_points = 4;
  const auto doubled = nbm::continue_forced(
      sweep.field, sweep.b.damping(),
      nbm::forced_load(sweep.b.load(), nbm::ForcedParameter::frequency, branch.parameter),
      branch.orbit.u0, branch.orbit.v0, o2);
  EXPECT_EQ(doubled.stop, nbm::ForcedStop::max_points) << doubled.stop_reason;
  for (const auto& pt : doubled.points) {
    EXPECT_NEAR(pt.orbit.period, 4 * M_PI / pt.omega, 1e-12);
    Bilinear bp = sweep.b;
    bp.w = pt.omega;
    const Eigen::Vector2d x(pt.orbit.u0(0), pt.orbit.v0(0));
    EXPECT_LT((bp.integrate(x, 2) - x).norm(), 1e-7) << "w " << pt.omega;
    EXPECT_GT((bp.integrate(x, 1) - x).norm(), 1e-3) << "w " << pt.omega;
  }
  EXPECT_GT(doubled.points.back().omega, doubled.points.front().omega);
  // Not a period doubling: a named error.
  const auto folds = sweep.events(nbm::ForcedEventKind::fold);
  ASSERT_FALSE(folds.empty());
  EXPECT_THROW(nbm::switch_at_period_doubling(sweep.field, sweep.b.damping(), sweep.b.load(),
                                              sweep.o, sweep.curve, folds[0]),
               nbm::InputError);
  EXPECT_THROW(nbm::switch_at_period_doubling(sweep.field, sweep.b.damping(), sweep.b.load(),
                                              sweep.o, sweep.curve, doublings[0], 0),
               nbm::InputError);
}

// Without location, the same events are flagged between the same points and
// placed by interpolation: each grazing's bracket contains the closed-form
// grazing frequency, and the interpolated folds lie within a tenth of their
// bracket's parameter span of the located ones.
TEST(ForcedContinuation, UnlocatedEventsAreInterpolatedInTheirBracket) {
  const BilinearSweep located, interpolated(false);
  ASSERT_EQ(interpolated.curve.events.size(), located.curve.events.size());
  const auto& P = interpolated.curve.points;
  for (std::size_t i = 0; i < interpolated.curve.events.size(); ++i) {
    const auto& e = interpolated.curve.events[i];
    EXPECT_FALSE(e.bisected);
    EXPECT_EQ(e.kind, located.curve.events[i].kind);
    const double lo = std::min(P[e.point].parameter, P[e.point + 1].parameter);
    const double hi = std::max(P[e.point].parameter, P[e.point + 1].parameter);
    if (e.kind == nbm::ForcedEventKind::fold) {
      // Measured: 1.1% and 0.2% of the span (the chord's value: 130% for
      // the first).
      EXPECT_NEAR(e.parameter, located.curve.events[i].parameter, 0.1 * (hi - lo))
          << e.description;
    } else {
      EXPECT_GE(e.parameter, lo) << e.description;
      EXPECT_LE(e.parameter, hi) << e.description;
    }
    if (e.kind == nbm::ForcedEventKind::grazing) {
      const bool first = e.parameter < 1;
      const double exact =
          grazing_frequency(interpolated.b, first ? 0.5 : 1.05, first ? 1.0 : 1.8);
      EXPECT_GE(exact, lo);
      EXPECT_LE(exact, hi);
    }
  }
}

// A two-mass chain with the gap in reach (kc = 2, gap 1, cos(w t) on the
// first mass, a_M = 0.02), swept from w = 0.2 through a superharmonic
// resonance of its first mode: a complex pair of multipliers leaves the unit
// circle (Neimark-Sacker). On its way the curve passes grazings where it
// bends sharply (the step control's max_turn keeps it from converging back
// onto the part already followed). The flag is confirmed by brute-force RK4: a small perturbation of
// the orbit grows past the event and decays before it, as the monodromy
// predicts (X^N delta), turning with the pair's angle.
TEST(ForcedContinuation, NeimarkSackerIsFlaggedWhereAComplexPairLeavesTheUnitCircle) {
  ForcedChain chain;
  chain.n = 2, chain.kc = 2, chain.gap = 1;
  const Index n = chain.n;
  const auto field = chain.field(Vector::Zero(n + 1));
  nbm::Damping damping;
  damping.a_M = 0.02;
  const Vector Fc = Vector::Unit(n, 0);
  nbm::HarmonicLoad load;
  load.omega = 0.2;
  load.cos = {internal(Fc)};
  nbm::ForcedContinuationOptions o;
  o.parameter_min = 0.2, o.parameter_max = 0.235;
  o.step = 0.05, o.max_step = 0.25;
  const auto curve =
      nbm::continue_forced(field, damping, load, Vector::Zero(n), Vector::Zero(n), o);
  ASSERT_EQ(curve.stop, nbm::ForcedStop::parameter_bound) << curve.stop_reason;
  const auto& P = curve.points;
  // The upper bound: with max_turn = pi (no turn control) the curve comes
  // back to w = 0.2 after the grazing at 0.2038 (measured).
  EXPECT_EQ(P.back().parameter, o.parameter_max);
  const nbm::ForcedEvent* ns = nullptr;
  for (const auto& e : curve.events)
    if (e.kind == nbm::ForcedEventKind::neimark_sacker && !ns) ns = &e;
  ASSERT_NE(ns, nullptr);
  EXPECT_TRUE(ns->bisected);
  EXPECT_NE(ns->multiplier.imag(), 0);
  EXPECT_NEAR(std::abs(ns->multiplier), 1, 1e-6) << ns->description;
  const auto& before = P[ns->point];
  EXPECT_TRUE(before.orbit.stable);
  // Past the event: the pair outside the unit circle a few points on.
  const auto& after = P[ns->point + 3];
  EXPECT_FALSE(after.orbit.stable);
  const Complex mu = after.orbit.multipliers[0];
  EXPECT_NE(mu.imag(), 0);
  EXPECT_GT(std::abs(mu), 1.02);

  for (const auto* pt : {&before, &after}) {
    Vector x(2 * n);
    x << pt->orbit.u0, pt->orbit.v0;
    const Vector delta = 1e-6 * Vector::Ones(2 * n);
    const int periods = 25;
    const Vector d = chain.integrate(damping.a_M, Fc, pt->omega, x + delta, periods, 40000) -
                     chain.integrate(damping.a_M, Fc, pt->omega, x, periods, 40000);
    Matrix XN = Matrix::Identity(2 * n, 2 * n);
    for (int p = 0; p < periods; ++p) XN = pt->orbit.monodromy * XN;
    const Vector predicted = XN * delta;
    // Measured: 7.8e-5 (before) and 8.7e-5 (after); the RK4 error at the
    // kinks of the contact force dominates (it varies with the step count).
    EXPECT_LT((d - predicted).norm(), 1e-3 * predicted.norm()) << "w " << pt->omega;
    if (pt == &after) {
      EXPECT_GT(d.norm(), 2 * delta.norm()) << "grows past the event";  // measured 5.6
    } else {
      EXPECT_LT(d.norm(), delta.norm()) << "decays before it";  // measured 0.77
    }
  }
}

// Step control: a corrected point always lies at least one step from the
// previous one (on the hyperplane at `step`), so max_jump = 1 rejects every
// point that needed any correction; the step halves down to min_step and
// the curve stops with the reason. max_points ends a curve too.
TEST(ForcedContinuation, StepControlStopsWithAReason) {
  Bilinear b;
  b.w = 1.0;
  const auto field = b.oscillator().field();
  nbm::ForcedContinuationOptions o;
  o.parameter_min = 0.5, o.parameter_max = 1.8;
  o.max_jump = 1;
  o.step = 0.04, o.min_step = 0.01;
  const auto stuck =
      nbm::continue_forced(field, b.damping(), b.load(), Vector::Zero(1), Vector::Zero(1), o);
  EXPECT_EQ(stuck.stop, nbm::ForcedStop::step_too_small);
  EXPECT_EQ(stuck.points.size(), 1u);
  EXPECT_NE(stuck.stop_reason.find("jumped"), std::string::npos) << stuck.stop_reason;
  EXPECT_NE(stuck.stop_reason.find("min_step"), std::string::npos) << stuck.stop_reason;

  o.max_jump = 2;
  o.max_points = 5;
  const auto short_curve =
      nbm::continue_forced(field, b.damping(), b.load(), Vector::Zero(1), Vector::Zero(1), o);
  EXPECT_EQ(short_curve.stop, nbm::ForcedStop::max_points);
  EXPECT_EQ(short_curve.points.size(), 5u);
  // Easy correctors grow the step (up to max_step): the arclength between
  // points increases along this smooth part.
  const auto& P = short_curve.points;
  EXPECT_GT(P[4].arclength - P[3].arclength, P[1].arclength - P[0].arclength);
}

TEST(ForcedContinuation, BadInputIsANamedError) {
  Bilinear b;
  const auto field = b.oscillator().field();
  const Vector z = Vector::Zero(1);
  nbm::ForcedContinuationOptions good;
  good.parameter_min = 0.5, good.parameter_max = 1.8;
  auto run = [&](const nbm::ForcedContinuationOptions& o, const nbm::HarmonicLoad& load,
                 const Vector& u0) {
    return nbm::continue_forced(field, b.damping(), load, u0, z, o);
  };
  auto bad = [&](auto edit) {
    nbm::ForcedContinuationOptions o = good;
    edit(o);
    EXPECT_THROW(run(o, b.load(), z), nbm::InputError);
  };
  using O = nbm::ForcedContinuationOptions;
  bad([](O& o) { o.parameter_min = NAN; });
  bad([](O& o) { o.parameter_max = INFINITY; });
  bad([](O& o) { o.parameter_min = 2, o.parameter_max = 1; });    // reversed
  bad([](O& o) { o.parameter_min = 0; });                         // frequency <= 0
  bad([](O& o) { o.parameter_min = 0.9, o.parameter_max = 1.8; }); // start 0.8 outside
  bad([](O& o) { o.direction = 0; });
  bad([](O& o) { o.step = 0; });
  bad([](O& o) { o.step = -0.1; });
  bad([](O& o) { o.min_step = 0; });
  bad([](O& o) { o.min_step = 0.1, o.step = 0.05; });
  bad([](O& o) { o.max_step = 0.01; });
  bad([](O& o) { o.max_step = INFINITY; });
  bad([](O& o) { o.growth = 0.5; });
  bad([](O& o) { o.easy_iterations = -1; });
  bad([](O& o) { o.max_jump = 0.5; });
  bad([](O& o) { o.max_turn = 0; });
  bad([](O& o) { o.max_turn = 4; });
  bad([](O& o) { o.max_points = 0; });
  bad([](O& o) { o.length = -1; });
  bad([](O& o) { o.parameter_scale = NAN; });
  bad([](O& o) { o.difference_step = 0; });
  bad([](O& o) { o.difference_step = 0.5; });
  bad([](O& o) { o.corrector_iterations = 0; });
  bad([](O& o) { o.shooting.tolerance = 0; });
  bad([](O& o) { o.subharmonic = 0; });
  bad([](O& o) { o.event_tolerance = 0; });
  bad([](O& o) { o.max_bisections = -1; });
  bad([](O& o) { o.parameter = nbm::ForcedParameter::amplitude, o.parameter_min = 1.5; });
  bad([](O& o) { o.parameter_max = 0.8; });  // starts on the bound it leaves through
  EXPECT_THROW(run(good, b.load(), Vector::Zero(2)), nbm::InputError);  // guess size
  nbm::HarmonicLoad unforced;
  unforced.omega = 1;
  EXPECT_THROW(run(good, unforced, z), nbm::InputError);  // no harmonics
  EXPECT_NO_THROW(run([&] {
    auto o = good;
    o.max_points = 2;
    return o;
  }(), b.load(), z));
}

}  // namespace
