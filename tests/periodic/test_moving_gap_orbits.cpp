// Forced orbits against periodically moving obstacles and time-varying loads
// on the contact dofs (method.md §8, §9 "Moving obstacles"): the gaps
// g(t) = g0 + sum_k gc_k cos(k w t) + gs_k sin(k w t) move the offset e(t) of
// the nodal boundary relation. Expectations independent of the exact flow:
// brute-force RK4 of a bilinear oscillator against a moving stop, the
// equivalences of method.md §8 (a load on an open massless contact dof is a
// moving gap plus an interior load; a translating wall is a body load on a
// free body), the linear frequency response of a chain held on a moving
// wall, and central differences of the flow map for the monodromy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "base/errors.hpp"
#include "bilinear_oscillator.hpp"
#include "forced_models.hpp"
#include "periodic/forced_continuation.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::Bilinear;
using nbm_test::ForcedChain;
using nbm_test::internal;
using Complex = std::complex<double>;

// The bilinear oscillator of bilinear_oscillator.hpp against a stop that
// moves, g(t) = g + gc cos(w t) + gs sin(w t): when closed the massless
// contact dof sits on the stop, so
//     u'' = F cos(w t) - a_M u' - k u - kc [u - g(t)]_+.
struct MovingStop {
  Bilinear b;
  double gc = 0, gs = 0;

  double gap(double t) const { return b.g + gc * std::cos(b.w * t) + gs * std::sin(b.w * t); }
  nbm::HarmonicLoad load() const {
    nbm::HarmonicLoad l = b.load();
    l.gap_cos = {Vector::Constant(1, gc)};
    l.gap_sin = {Vector::Constant(1, gs)};
    return l;
  }
  Eigen::Vector2d steady_state() const {
    auto field = [this](double t, const Eigen::Vector2d& x) -> Eigen::Vector2d {
      return {x(1), b.F * std::cos(b.w * t) - b.a_M * x(1) - b.k * x(0) -
                        b.kc * std::max(x(0) - gap(t), 0.0)};
    };
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    for (int p = 0; p < 2000; ++p) {
      const Eigen::Vector2d next = nbm_test::rk4_periods(field, x, 2 * M_PI / b.w, 1, 40000);
      if ((next - x).norm() < 1e-13) return next;
      x = next;
    }
    ADD_FAILURE() << "no steady state in 2000 periods";
    return x;
  }
};

nbm::PeriodicOrbit shoot(const nbm::ExactFlow& flow, const Vector& u0, const Vector& v0,
                         int transient_periods = 0) {
  nbm::ShootingOptions o;
  o.transient_periods = transient_periods;
  const nbm::PeriodicProblem forced(flow, 1);
  return nbm::shoot(forced, u0, v0, forced.period(), o);
}

TEST(MovingGapOrbit, OscillatorAgainstAMovingStopMatchesBruteForceTimeIntegration) {
  struct Case {
    double F, g, gc, gs, w;
  };
  // A forced mass hitting a moving stop, and a mass at rest driven by the
  // stop alone (F = 0: the stop's lowest point, g - |G|, is below the rest
  // position 0).
  for (const Case& c : {Case{0.3, 0.5, 0.1, 0.1, 1.0}, Case{0.3, 0.5, -0.15, 0.2, 1.2},
                        Case{0, 0.1, 0.3, 0, 0.8}, Case{0, 0.1, 0.2, 0.25, 1.3}}) {
    MovingStop s;
    s.b.F = c.F, s.b.g = c.g, s.b.w = c.w, s.gc = c.gc, s.gs = c.gs;
    const auto field = s.b.oscillator().field();
    const nbm::ExactFlow flow(field, s.b.damping(), s.load());
    const auto orbit = shoot(flow, Vector::Zero(1), Vector::Zero(1), 10);
    ASSERT_GE(orbit.switches.size(), 2u) << "the orbit must touch the stop, w " << c.w;
    EXPECT_LT(orbit.periodicity_residual, 1e-11);
    EXPECT_LT(orbit.complementarity_residual, 1e-12);
    EXPECT_TRUE(orbit.stable);
    const Eigen::Vector2d x = s.steady_state();
    // RK4 at 40000 steps per period; the kink of [u - g(t)]_+ costs order
    // (as in test_forced_orbits.cpp).
    EXPECT_NEAR(orbit.u0(0), x(0), 2e-8) << "F " << c.F << " w " << c.w;
    EXPECT_NEAR(orbit.v0(0), x(1), 2e-8) << "F " << c.F << " w " << c.w;
    // Massless boundary and a_M only: det X = exp(-a_M T) (Liouville), the
    // saltation at the switches being the identity.
    EXPECT_NEAR(orbit.monodromy.determinant(), std::exp(-s.b.a_M * orbit.period), 1e-11);
  }
}

// Monodromy through switches of a moving gap against central differences
// of the flow map. A stiffness-proportional damping makes the acceleration
// jump at the switches (b_K K_OC e'(t) acts only while closed), and the
// switching function's own rate d'(t) enters the saltation's denominator;
// mass on the contact dof (m_B > 0) adds P^T M [0; e''] with a load on it.
void expect_moving_monodromy_matches_differences(double mB, double a_M, double b_K) {
  nbm_test::ImpactOscillator osc;
  osc.mB = mB;
  osc.kc = 10;
  osc.g = 0.8;
  const auto field = osc.field();
  nbm::Damping damping;
  damping.a_M = a_M, damping.b_K = b_K;
  nbm::HarmonicLoad load;
  load.omega = 0.9;
  load.cos = {Eigen::Vector2d(1.2, 0.3)};
  load.sin = {Eigen::Vector2d(0.4, -0.5)};
  load.gap_cos = {Vector::Constant(1, 0.3), Vector::Constant(1, 0.05)};
  load.gap_sin = {Vector::Constant(1, -0.2)};
  nbm_test::expect_monodromy_matches_differences(
      nbm::ExactFlow(field, damping, load),
      "mB " + std::to_string(mB) + " b_K " + std::to_string(b_K));
}

TEST(MovingGapOrbit, MonodromyThroughSwitchesMatchesFiniteDifferences) {
  expect_moving_monodromy_matches_differences(0, 0.1, 0);
  expect_moving_monodromy_matches_differences(0, 0.05, 0.02);
  expect_moving_monodromy_matches_differences(0.5, 0.1, 0.02);
}

// A load Fc(t) on the massless contact dof of the chain (joined to the last
// mass only, by kc) acts, while open, on the last mass (u_c = u_last +
// Fc / kc) and, while closed, on the obstacle alone. With mass-proportional
// damping that is a gap g - Fc(t) / kc plus the interior load Fc(t) on the
// last mass: closed, kc (u_last - g + Fc / kc) - Fc = kc (u_last - g); open,
// the same force; and the switching functions agree (gap: g - u_last -
// Fc / kc; reaction: Fc - kc (g - u_last)).
TEST(MovingGapOrbit, ALoadOnTheContactDofIsAMovingGapPlusAnInteriorLoad) {
  ForcedChain chain;
  chain.n = 3;
  chain.gap = 0.4;
  const Index n = chain.n;
  Vector F0 = Vector::Zero(n + 1);
  F0(n - 1) = 0.1;
  const auto field = chain.field(F0);
  nbm::Damping damping;
  damping.a_M = 0.08;
  const double w = 0.7, Fcc = 0.6, Fcs = -0.25, H2 = 0.1;
  Vector Fc1 = Vector::Zero(n + 1), Fs1 = Vector::Zero(n + 1), Fc2 = Vector::Zero(n + 1);
  Fc1(0) = 0.2;  // an interior harmonic as well
  nbm::HarmonicLoad on_contact;
  on_contact.omega = w;
  on_contact.cos = {Fc1, Fc2};
  on_contact.sin = {Fs1};
  on_contact.cos[0](n) = Fcc, on_contact.sin[0](n) = Fcs, on_contact.cos[1](n) = H2;
  nbm::HarmonicLoad moving = on_contact;
  for (auto* list : {&moving.cos, &moving.sin})
    for (Vector& x : *list) x(n - 1) += x(n), x(n) = 0;
  moving.gap_cos = {Vector::Constant(1, -Fcc / chain.kc), Vector::Constant(1, -H2 / chain.kc)};
  moving.gap_sin = {Vector::Constant(1, -Fcs / chain.kc)};
  const nbm::ExactFlow a(field, damping, on_contact), b(field, damping, moving);
  const auto oa = shoot(a, Vector::Zero(n), Vector::Zero(n), 20);
  ASSERT_GE(oa.switches.size(), 2u) << "the orbit must reach the obstacle";
  const auto ob = shoot(b, oa.u0, oa.v0);
  EXPECT_LT((oa.u0 - ob.u0).norm(), 1e-11 * oa.u0.norm());
  EXPECT_LT((oa.v0 - ob.v0).norm(), 1e-11 * oa.v0.norm());
  ASSERT_EQ(oa.switches.size(), ob.switches.size());
  for (std::size_t k = 0; k < oa.switches.size(); ++k)
    EXPECT_NEAR(oa.switches[k].t, ob.switches[k].t, 1e-10);
  EXPECT_LT((oa.monodromy - ob.monodromy).norm(), 1e-9 * oa.monodromy.norm());
}

// method.md §8, the translating plane: a free chain (ground = 0) pushed
// towards a wall that moves by w(t) = Wc cos(w t) + Ws sin(w t) along its
// normal. In the wall's frame, u = u~ + w(t) t_n (t_n = 1 on every dof) with
// K t_n = 0, the wall is fixed and the body carries the extra load
// -w''(t) M t_n = w^2 w(t) M t_n (M t_n: zero on the massless contact dof).
// Stiffness-proportional damping is frame-independent (K t_n = 0): the two
// orbits are the same motion.
TEST(MovingGapOrbit, ATranslatingWallIsABodyLoadOnAFreeBody) {
  ForcedChain chain;
  chain.n = 3;
  chain.ground = 0;
  chain.gap = 0.05;
  const Index n = chain.n;
  const Matrix M = chain.M();
  const Vector ones = Vector::Ones(n + 1), Mt = M * ones;
  const Vector F0 = 0.4 * Mt;  // a body force towards the wall
  const auto field = chain.field(F0);
  nbm::Damping damping;
  damping.b_K = 0.1;
  const double w = 1.5, Wc = 0.45, Ws = 0.15;
  nbm::HarmonicLoad wall;
  wall.omega = w;
  wall.cos = {Vector::Zero(n + 1)};
  wall.gap_cos = {Vector::Constant(1, Wc)};
  wall.gap_sin = {Vector::Constant(1, Ws)};
  nbm::HarmonicLoad body;
  body.omega = w;
  body.cos = {w * w * Wc * Mt};
  body.sin = {w * w * Ws * Mt};
  const nbm::ExactFlow moving(field, damping, wall), fixed(field, damping, body);

  // The flows first: from a state in the wall's frame and its image.
  const Vector ut0 = Vector::LinSpaced(n, -0.1, 0.02), vt0 = Vector::LinSpaced(n, 0.3, -0.2);
  const double T = 20;
  const auto rf = fixed.integrate(ut0, vt0, T, true);
  const Vector shift0 = Vector::Constant(n, Wc), rate0 = Vector::Constant(n, Ws * w);
  const auto rm = moving.integrate(ut0 + shift0, vt0 + rate0, T, true);
  ASSERT_GE(rf.switches.size(), 4u) << "the body must bounce on the wall";
  ASSERT_EQ(rf.switches.size(), rm.switches.size());
  for (std::size_t k = 0; k < rf.switches.size(); ++k)
    EXPECT_NEAR(rf.switches[k].t, rm.switches[k].t, 1e-10);
  const double wT = Wc * std::cos(w * T) + Ws * std::sin(w * T);
  const double wdT = w * (Ws * std::cos(w * T) - Wc * std::sin(w * T));
  EXPECT_LT((rm.u - rf.u - Vector::Constant(n, wT)).norm(), 1e-11 * rf.u.norm());
  EXPECT_LT((rm.v - rf.v - Vector::Constant(n, wdT)).norm(), 1e-11 * rf.v.norm());
  EXPECT_LT((rm.monodromy - rf.monodromy).norm(), 1e-9 * rf.monodromy.norm());

  // Then the orbits: the stable one on the moving wall (reached by the
  // exact flow from rest) and the one on the fixed wall from its image.
  const auto om = shoot(moving, Vector::Zero(n), Vector::Zero(n), 50);
  ASSERT_GE(om.switches.size(), 2u);
  ASSERT_TRUE(om.stable);
  const auto of = shoot(fixed, om.u0 - shift0, om.v0 - rate0);
  EXPECT_LT((om.u0 - shift0 - of.u0).norm(), 1e-11 * om.u0.norm());
  EXPECT_LT((om.v0 - rate0 - of.v0).norm(), 1e-11 * om.v0.norm());
  ASSERT_EQ(of.multipliers.size(), om.multipliers.size());
  for (std::size_t k = 0; k < om.multipliers.size(); ++k)
    EXPECT_LT(std::abs(of.multipliers[k] - om.multipliers[k]), 1e-9);
}

// Held on the wall (a load pressing the chain against it that the wall's
// motion never overcomes), the contact stays closed: the motion is the
// linear steady response of the chain with its last dof driven by the wall,
//     (K_OO - W^2 M_OO + i W C_OO) U = -(K_OC + i W C_OC) G,
// C = a_M M + b_K K (M_OC = 0), on top of the static K_OO^-1 (F_O - K_OC g0).
struct HeldChain {
  ForcedChain chain;
  Vector F0;
  nbm::Damping damping;
  HeldChain() {
    chain.n = 3;
    chain.gap = 0.1;
    F0 = Vector::Zero(chain.n + 1);
    F0(chain.n - 1) = 2;  // the reaction at rest: 2 - (static) > 0 by far
    damping.a_M = 0.03, damping.b_K = 0.02;
  }
  /// The gap harmonics G_k = gc_k - i gs_k of the tests.
  nbm::HarmonicLoad load(double w) const {
    nbm::HarmonicLoad l;
    l.omega = w;
    l.gap_cos = {Vector::Constant(1, 0.01), Vector::Constant(1, 0.004)};
    l.gap_sin = {Vector::Constant(1, -0.006)};
    return l;
  }
  /// The static state and the driven response (u, v at t = 0) to load(w),
  /// solved densely on the interior dofs.
  void reference(double w, Vector& u_static, Vector& u, Vector& v) const {
    const Index n = chain.n;
    const Matrix M = chain.M(), K = chain.K();
    const Matrix C = damping.a_M * M + damping.b_K * K;
    const Matrix Moo = M.topLeftCorner(n, n), Koo = K.topLeftCorner(n, n);
    const Matrix Coo = C.topLeftCorner(n, n);
    const Vector Koc = K.topRightCorner(n, 1), Coc = C.topRightCorner(n, 1);
    const std::vector<Complex> G = {Complex(0.01, 0.006), Complex(0.004, 0)};
    u_static = Koo.ldlt().solve(F0.head(n) - Koc * chain.gap);
    u = Vector::Zero(n), v = Vector::Zero(n);
    for (int k = 0; k < 2; ++k) {
      const double W = (k + 1) * w;
      const Eigen::MatrixXcd Z = Koo.cast<Complex>() - W * W * Moo.cast<Complex>() +
                                 Complex(0, W) * Coo.cast<Complex>();
      const Eigen::VectorXcd rhs =
          -(Koc.cast<Complex>() + Complex(0, W) * Coc.cast<Complex>()) * G[k];
      const Eigen::VectorXcd U = Z.partialPivLu().solve(rhs);
      u += U.real();
      v += (Complex(0, W) * U).real();
    }
  }
};

TEST(MovingGapOrbit, OnAMovingWallTheLinearLimitIsTheDrivenFrequencyResponse) {
  const HeldChain held;
  const Index n = held.chain.n;
  const auto field = held.chain.field(held.F0);
  for (double w : {0.5, 1.7}) {
    Vector u_static, u, v;
    held.reference(w, u_static, u, v);
    u += u_static;
    const nbm::ExactFlow flow(field, held.damping, held.load(w));
    const auto orbit = shoot(flow, Vector::Zero(n), Vector::Zero(n));
    EXPECT_TRUE(orbit.switches.empty());
    EXPECT_LE(orbit.iterations, 2) << "the flow is affine: Newton converges in one step";
    EXPECT_LT((orbit.u0 - u).norm(), 1e-10 * u.norm()) << "w " << w;
    EXPECT_LT((orbit.v0 - v).norm(), 1e-10 * std::max(v.norm(), w * u.norm())) << "w " << w;
  }
}

// The amplitude parameter of the continuation scales the gap harmonics too:
// along the amplitude curve of the held chain every point is the static
// state plus s times the driven response.
TEST(MovingGapOrbit, TheAmplitudeCurveScalesTheGapMotion) {
  const HeldChain held;
  const Index n = held.chain.n;
  const auto field = held.chain.field(held.F0);
  const double w = 1.1;
  Vector u_static, u, v;
  held.reference(w, u_static, u, v);
  nbm::ForcedContinuationOptions o;
  o.parameter = nbm::ForcedParameter::amplitude;
  o.parameter_min = 0.5, o.parameter_max = 3;
  o.max_points = 12;
  const auto curve =
      nbm::continue_forced(field, held.damping, held.load(w), Vector::Zero(n), Vector::Zero(n), o);
  ASSERT_GE(curve.points.size(), 3u);
  for (const auto& p : curve.points) {
    EXPECT_TRUE(p.orbit.switches.empty());
    EXPECT_LT((p.orbit.u0 - u_static - p.scale * u).norm(), 1e-9 * u_static.norm())
        << "scale " << p.scale;
    EXPECT_LT((p.orbit.v0 - p.scale * v).norm(), 1e-9 * w * u_static.norm()) << "scale " << p.scale;
  }
  EXPECT_GT(curve.points.back().scale, 1.5);
}

// Out of reach, the gap's motion changes nothing: the open region's offset
// does not depend on the gaps.
TEST(MovingGapOrbit, AGapOutOfReachLeavesTheLinearLimit) {
  ForcedChain chain;
  chain.n = 2;
  chain.gap = 10;
  const auto field = chain.field(internal(Vector::Constant(2, 0.1)));
  nbm::Damping damping;
  damping.a_M = 0.05;
  nbm::HarmonicLoad fixed;
  fixed.omega = 1.1;
  fixed.cos = {internal(Vector::Constant(2, 0.3))};
  nbm::HarmonicLoad moving = fixed;
  moving.gap_cos = {Vector::Constant(1, 2)};
  moving.gap_sin = {Vector::Constant(1, -1)};
  const auto a = shoot(nbm::ExactFlow(field, damping, fixed), Vector::Zero(2), Vector::Zero(2));
  const auto b = shoot(nbm::ExactFlow(field, damping, moving), Vector::Zero(2), Vector::Zero(2));
  EXPECT_TRUE(b.switches.empty());
  EXPECT_LT((a.u0 - b.u0).norm(), 1e-14 * a.u0.norm());
  EXPECT_LT((a.v0 - b.v0).norm(), 1e-14 * a.v0.norm());
}

TEST(MovingGapOrbit, BadGapHarmonicsAreNamedErrors) {
  Bilinear b;
  const auto field = b.oscillator().field();
  auto message = [&](const nbm::HarmonicLoad& load) -> std::string {
    try {
      nbm::ExactFlow(field, nbm::Damping{}, load);
    } catch (const nbm::InputError& e) {
      return e.what();
    }
    return "no error";
  };
  nbm::HarmonicLoad size = b.load();
  size.gap_cos = {Vector::Zero(1), Vector::Ones(2)};
  EXPECT_NE(message(size).find("gap harmonic cos[1] has 2 entries, expected 1"), std::string::npos)
      << message(size);
  nbm::HarmonicLoad nan = b.load();
  nan.gap_sin = {Vector::Constant(1, NAN)};
  EXPECT_NE(message(nan).find("gap harmonic sin[0] has non-finite entries"), std::string::npos)
      << message(nan);
  nbm::HarmonicLoad infinite = b.load();
  infinite.cos = {Eigen::Vector2d(0, INFINITY)};
  EXPECT_NE(message(infinite).find("load harmonic cos[0] has non-finite entries"),
            std::string::npos)
      << message(infinite);
  nbm::HarmonicLoad gaps_only;
  gaps_only.gap_cos = {Vector::Ones(1)};
  EXPECT_NE(message(gaps_only).find("omega must be finite and > 0"), std::string::npos)
      << message(gaps_only);
}

}  // namespace
