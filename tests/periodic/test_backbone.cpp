// Backbones from grazing (backbone.hpp, method.md §6): the grazing orbit
// against the linear mode of a dense eigenproblem computed here, the
// homogeneity of the backbone in the gap, the bilinear oscillator's backbone
// against its closed-form period, and input errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>


#include "bars.hpp"
#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "oscillators.hpp"  // name_word
#include "periodic/backbone.hpp"
#include "periodic/user_backbone.hpp"
#include "periodic/user_orbit.hpp"

namespace {

using nbm::Matrix;
using nbm::Vector;

// A chain of six dofs tied to the ground by springs of different stiffness,
// with a bar-like (tridiagonal) consistent mass; contact dofs 2 and 5 (the
// obstacle at u <= gap), a constant load F.
struct Chain {
  Matrix M = Matrix::Zero(6, 6), K = Matrix::Zero(6, 6);
  Vector F = Vector::Zero(6);
  std::vector<nbm::Index> contact{2, 5};
  Vector gaps = Eigen::Vector2d(0.02, 0.03);
  Chain() {
    const double k[6] = {3, 1.5, 2, 1, 2.5, 1.2}, m[6] = {1, 0.8, 0.3, 1.2, 0.9, 0.4};
    for (int i = 0; i < 6; ++i) {
      // spring k[i] between dof i - 1 (the ground for i = 0) and dof i,
      // element mass m[i] / 6 [2 1; 1 2] on the same pair.
      K(i, i) += k[i];
      M(i, i) += m[i] / 3;
      if (i > 0) {
        K(i - 1, i - 1) += k[i], K(i - 1, i) -= k[i], K(i, i - 1) -= k[i];
        M(i - 1, i - 1) += m[i] / 3, M(i - 1, i) += m[i] / 6, M(i, i - 1) += m[i] / 6;
      }
    }
  }
  nbm::ReducedField field() const { return nbm::ReducedField(M, K, F, contact, gaps); }
};

// The open (linear) system of the chain, computed here from M and K: the
// contact dofs slaved by their own rows of K u = F (no reaction), P = [I; A].
struct OpenSystem {
  Vector omega, static_u, static_gaps;
  Matrix modes, A;  // M_S-normalised modes; u_C = A u_O + e
  explicit OpenSystem(const Chain& c) {
    const std::vector<nbm::Index> O{0, 1, 3, 4}, C = c.contact;
    A = -Matrix(c.K(C, C)).ldlt().solve(Matrix(c.K(C, O)));
    Matrix P(6, 4);  // full vector = P u_O (+ the load's part on C)
    P.setZero();
    for (int i = 0; i < 4; ++i) P(O[i], i) = 1;
    for (int r = 0; r < 2; ++r) P.row(C[r]) = A.row(r);
    const Matrix MS = P.transpose() * c.M * P, KS = P.transpose() * c.K * P;
    const nbm::SymmetricEigen eig = nbm::generalized_symmetric_eigen(KS, MS);
    omega = eig.values.cwiseSqrt();
    modes = eig.vectors;
    // The static state with open contacts: K x = F on every dof.
    const Vector x = c.K.ldlt().solve(c.F);
    static_u = x(O);
    static_gaps = c.gaps - x(C);
  }
};

TEST(Backbone, StartsAtTheLinearModeAtGrazing) {
  for (double load : {0.0, 0.004, -0.01}) {  // open at rest: |load| < 0.0068
    Chain chain;
    chain.F(3) = load, chain.F(5) = 0.5 * load;  // a load on a contact dof too
    const OpenSystem lin(chain);
    const auto field = chain.field();
    for (nbm::Index j = 0; j < 4; ++j) {
      SCOPED_TRACE("load " + std::to_string(load) + ", mode " + std::to_string(j));
      const Vector phi = lin.modes.col(j), normal = lin.A * phi;
      double a = 1e300;
      for (int k = 0; k < 2; ++k) a = std::min(a, lin.static_gaps(k) / std::abs(normal(k)));
      nbm::BackboneOptions o;
      o.points = 1;
      const nbm::Backbone b = nbm::backbone(field, j, o);
      ASSERT_EQ(b.points.size(), 1u);
      const nbm::BackbonePoint& p = b.points[0];
      const double T = 2 * M_PI / lin.omega(j);
      EXPECT_NEAR(p.orbit.period, T, 1e-10 * T);
      EXPECT_NEAR(b.grazing.amplitude, a, 1e-10 * a);
      EXPECT_NEAR(p.energy, 0.5 * a * a * lin.omega(j) * lin.omega(j), 1e-9 * p.energy);
      EXPECT_NEAR(p.amplitude, a * phi.cwiseAbs().maxCoeff(), 1e-10 * p.amplitude);
      EXPECT_LE((b.grazing.static_state - lin.static_u).norm(),
                1e-12 + 1e-10 * lin.static_u.norm());
      // u0 = u_s -+ a phi, at rest; no contact, but a gap of exactly 0 at T/2.
      const Vector d = p.orbit.u0 - lin.static_u;
      EXPECT_LE(std::min((d - a * phi).norm(), (d + a * phi).norm()), 1e-10 * a);
      EXPECT_EQ(p.orbit.v0.norm(), 0.0);
      EXPECT_EQ(p.orbit.switches.size(), 0u);
      EXPECT_EQ(p.orbit.contact_time, 0.0);
      EXPECT_LE(p.orbit.periodicity_residual, 1e-10);
      nbm::ExactFlow flow(field);
      std::vector<double> times;
      for (int i = 0; i <= 400; ++i) times.push_back(T * i / 400);
      const nbm::FlowResult r = flow.integrate(p.orbit.u0, p.orbit.v0, T, false, times);
      double smallest = 1e300;
      for (nbm::Index i = 0; i < r.samples.cols(); ++i) {
        const Vector u = r.samples.col(i).head(4);
        const Vector gap = lin.static_gaps - lin.A * (u - lin.static_u);
        smallest = std::min(smallest, gap.minCoeff());
      }
      EXPECT_NEAR(smallest, 0, 1e-12 * chain.gaps.maxCoeff());
      // The linear orbit's multipliers: exp(+-i omega_k T), on the unit circle.
      EXPECT_TRUE(p.orbit.stable);
      for (const auto& mu : p.orbit.multipliers) EXPECT_NEAR(std::abs(mu), 1, 1e-8);
      EXPECT_NE(p.events.find("grazing"), std::string::npos);
    }
  }
}

// (11 points: mode 0's 12th lies at a fold in frequency, where the step
// control of the two runs parts at round-off on some BLAS kernels: OpenBLAS
// single-threaded with OPENBLAS_CORETYPE=Haswell flags the fold for 2 g and
// not for g.)
TEST(Backbone, IsHomogeneousInTheGap) {
  Chain one, two;
  two.gaps *= 2;
  nbm::BackboneOptions o;
  o.points = 11;
  o.step = 0.1;
  for (nbm::Index j : {0, 1}) {
    SCOPED_TRACE("mode " + std::to_string(j));
    const nbm::Backbone b1 = nbm::backbone(one.field(), j, o);
    const nbm::Backbone b2 = nbm::backbone(two.field(), j, o);
    ASSERT_EQ(b1.points.size(), 11u) << b1.stop_reason;
    ASSERT_EQ(b2.points.size(), 11u) << b2.stop_reason;
    for (std::size_t k = 0; k < b1.points.size(); ++k) {
      const auto &p = b1.points[k], &q = b2.points[k];
      EXPECT_NEAR(q.orbit.period, p.orbit.period, 1e-8 * p.orbit.period) << "point " << k;
      EXPECT_NEAR(q.amplitude, 2 * p.amplitude, 1e-8 * q.amplitude) << "point " << k;
      EXPECT_NEAR(q.energy, 4 * p.energy, 1e-8 * q.energy) << "point " << k;
      EXPECT_LE((q.orbit.u0 - 2 * p.orbit.u0).norm(), 1e-8 * q.orbit.u0.norm()) << "point " << k;
      EXPECT_NEAR(q.orbit.contact_time, p.orbit.contact_time, 1e-8 * p.orbit.period);
      EXPECT_EQ(q.orbit.switches.size(), p.orbit.switches.size());
      EXPECT_EQ(q.events, p.events);
    }
    // Beyond grazing the family leaves the linear one: contact, and a
    // higher frequency (the obstacle stiffens the system).
    EXPECT_GT(b1.points.back().orbit.contact_time, 0);
    EXPECT_LT(b1.points.back().orbit.period, b1.points[0].orbit.period);
  }
}

// The frequency branch is homogeneous in the gap as the arclength one is:
// doubling every gap doubles every orbit at the same frequencies, tongue
// events included (the chain's mode 0 meets some: their ratios name the
// open modes near integer multiples of the skipped frequency).
TEST(Backbone, TheFrequencyBranchIsHomogeneousInTheGap) {
  Chain one, two;
  two.gaps *= 2;
  nbm::BackboneOptions o;
  o.points = 30;
  o.branch = nbm::BackboneOptions::Branch::frequency;
  o.frequency_step = 0.02;
  const nbm::Backbone b1 = nbm::backbone(one.field(), 0, o);
  const nbm::Backbone b2 = nbm::backbone(two.field(), 0, o);
  ASSERT_GT(b1.points.size(), 3u) << b1.stop_reason;
  ASSERT_EQ(b2.points.size(), b1.points.size()) << b2.stop_reason;
  EXPECT_EQ(b2.stop_reason.substr(0, 10), b1.stop_reason.substr(0, 10));
  for (std::size_t k = 0; k < b1.points.size(); ++k) {
    const auto &p = b1.points[k], &q = b2.points[k];
    EXPECT_NEAR(q.orbit.period, p.orbit.period, 1e-8 * p.orbit.period) << "point " << k;
    EXPECT_NEAR(q.energy, 4 * p.energy, 1e-7 * q.energy) << "point " << k;
    EXPECT_EQ(q.events, p.events) << "point " << k;
    if (k >= 1) {
      EXPECT_GT(p.orbit.contact_time, 0) << "point " << k;
    }
  }
  std::printf("chain, frequency branch: %zu orbits to %.4f x the linear frequency; %s\n",
              b1.points.size(), b1.points[0].orbit.period / b1.points.back().orbit.period,
              b1.stop_reason.c_str());
  for (const auto& p : b1.points)
    if (p.events.find("tongue") != std::string::npos) std::printf("  %s\n", p.events.c_str());
}

// The clamped bar with its wall (the case of issue 26 whose arclength
// backbone stops at grazing or climbs a tongue at once): the frequency
// branch leaves grazing and holds, with the massless boundary, every orbit
// periodic and in contact. Printed for both mass treatments (method.md §6,
// "The primary branch", quotes these lines).
TEST(Backbone, TheFrequencyBranchLeavesGrazingOnTheBar) {
  for (bool massless : {true, false}) {
    nbm_test::GapBar bar;
    bar.N = 40;
    bar.g = 0.05;
    bar.massless = massless;
    nbm::BackboneOptions o;
    o.points = 120;
    o.branch = nbm::BackboneOptions::Branch::frequency;
    o.frequency_step = 5e-4;
    const nbm::Backbone b = nbm::backbone(bar.field(), 0, o);
    const auto& last = b.points.back();
    int tongues = 0;
    for (const auto& p : b.points) tongues += p.events.find("tongue") != std::string::npos;
    std::printf("bar N = 40, %s: %zu orbits to %.4f x the linear frequency at %.2f x the grazing "
                "energy, %d with tongue events; %s\n",
                massless ? "massless" : "consistent", b.points.size(),
                b.points[0].orbit.period / last.orbit.period, last.energy / b.points[0].energy,
                tongues, b.stop_reason.c_str());
    // The continuum family (benchmarks.md §C) at that frequency ratio:
    // omega / omega_1 = 4 / (4 - tau), E / E_g = 8 / (pi^2 (1 - tau)^2).
    const double ratio = b.points[0].orbit.period / last.orbit.period, tau = 4 * (1 - 1 / ratio);
    std::printf("  the continuum family at that ratio: %.2f x the grazing energy\n",
                8 / (M_PI * M_PI * (1 - tau) * (1 - tau)));
    if (!massless) continue;
    ASSERT_EQ(b.points.size(), 120u) << b.stop_reason;
    EXPECT_GT(b.points[0].orbit.period / last.orbit.period, 1.03);
    for (std::size_t k = 1; k < b.points.size(); ++k) {
      EXPECT_LE(b.points[k].orbit.periodicity_residual, 1e-9) << k;
      EXPECT_GT(b.points[k].orbit.contact_time, 0) << k;
    }
  }
}

// The chain's first backbone turns: events flagged where the data of the
// orbits say (frequency or energy turning, switches or stability changing),
// and it ends, through a 6:1 internal resonance, on an orbit without contact:
// mode 2's linear orbit, whose period is 6 times mode 2's.
TEST(Backbone, FlagsEventsWhereTheOrbitsChangeAndStopsOffContact) {
  const Chain chain;
  const OpenSystem lin(chain);
  nbm::BackboneOptions o;
  o.points = 60;
  o.step = 0.1;
  const nbm::Backbone b = nbm::backbone(chain.field(), 0, o);
  ASSERT_GE(b.points.size(), 3u);
  int folds = 0, changes = 0;
  for (std::size_t k = 0; k < b.points.size(); ++k) {
    const auto& p = b.points[k].orbit;
    std::string expected = k == 0 ? "grazing" : "";
    auto add = [&](const char* e) { expected += (expected.empty() ? "" : " ") + std::string(e); };
    if (k > 0) {
      const auto& q = b.points[k - 1].orbit;
      if (p.switches.size() != q.switches.size()) add("grazing");
      if (k + 1 < b.points.size()) {
        const auto& r = b.points[k + 1];
        // period up then down (or down then up) = frequency turning
        if ((p.period - q.period) * (r.orbit.period - p.period) < 0) add("fold-frequency"), ++folds;
        const double e0 = b.points[k - 1].energy, e1 = b.points[k].energy, e2 = r.energy;
        if ((e1 - e0) * (e2 - e1) < 0) add("fold-energy"), ++folds;
      }
      if (p.stable != q.stable) add("stability"), ++changes;
    }
    EXPECT_EQ(b.points[k].events, expected) << "orbit " << k;
  }
  EXPECT_GE(folds, 2);
  EXPECT_GE(changes, 2);
  const auto& last = b.points.back().orbit;
  EXPECT_NE(b.stop_reason.find("an orbit without contact"), std::string::npos) << b.stop_reason;
  EXPECT_EQ(last.switches.size(), 0u);
  EXPECT_EQ(last.contact_time, 0.0);
  const double T2 = 2 * M_PI / lin.omega(2);
  EXPECT_NEAR(last.period, 6 * T2, 1e-8 * last.period);
}

// The bilinear oscillator: mass m on a spring k (interior dof), joined by a
// spring k_c to a contact dof that stops at the gap g, under a constant load
// P on the mass. The contact dof is massless (m_B = 0) or carries m_B (the
// paper's NBM: it moves with the mass while open, stops dead on contact).
// Open, the mass oscillates about u_s = P / k with w1 = sqrt(k / (m + m_B)); in
// contact (u > g) it feels k + k_c: w2 = sqrt((k + k_c) / m) about
// z = (P + k_c g) / (k + k_c). From rest at u_s - A (t = 0, the free turning
// point), u = u_s - A cos(w1 t) reaches g at w1 t1 = pi - acos(g' / A),
// g' = g - u_s, with speed V = w1 sqrt(A^2 - g'^2); then u - z =
// (g - z) cos(w2 s) + (V / w2) sin(w2 s) returns to g after
// s2 = (2 / w2) atan(V / (w2 (g - z))), and the free half mirrors the first:
//   T(A) = 2 (pi - acos(g' / A)) / w1 + (2 / w2) atan(V / (w2 (g - z))).
// As g' / A -> 0 (a gap at 0): T -> pi / w1 + pi / w2, the frequency
// 2 w1 w2 / (w1 + w2) whatever the amplitude. With m_B > 0 the two terms in
// sqrt(A - g') no longer cancel: T(A) - T(g') ~ sqrt(A - g'), the backbone
// leaves grazing with a vertical tangent (m_B = 0: ~ (A - g')^(3/2)).
struct Bilinear {
  double m = 1, mB = 0, k = 1, kc, g = 0.1, P = 0;
  double w1() const { return std::sqrt(k / (m + mB)); }
  double w2() const { return std::sqrt((k + kc) / m); }
  double period(double A) const {
    const double us = P / k, gp = g - us, z = (P + kc * g) / (k + kc);
    const double V = w1() * std::sqrt(A * A - gp * gp);
    return 2 * (M_PI - std::acos(gp / A)) / w1() + (2 / w2()) * std::atan(V / (w2() * (g - z)));
  }
  /// The two dofs (mass, contact dof) as a field.
  nbm::ReducedField field() const {
    Eigen::Matrix2d M, K;
    M << m, 0, 0, mB;
    K << k + kc, -kc, -kc, kc;
    return nbm::ReducedField(M, K, Eigen::Vector2d(P, 0), {1}, Vector::Constant(1, g));
  }
};

struct BilinearCase {
  double kc, P;
  bool half;
  double mB = 0;
};
std::string case_name(const BilinearCase& c) {
  using nbm_test::name_word;
  return "kc" + name_word(c.kc) + "_P" + name_word(c.P) + "_mB" + name_word(c.mB) +
         (c.half ? "_half" : "_full");
}
void PrintTo(const BilinearCase& c, std::ostream* os) { *os << case_name(c); }

class BilinearBackbone : public ::testing::TestWithParam<BilinearCase> {};

TEST_P(BilinearBackbone, FollowsTheClosedFormPeriod) {
  const auto [kc, P, half, mB] = GetParam();
  Bilinear exact;
  exact.kc = kc, exact.P = P, exact.mB = mB;
  const nbm::ReducedField field = exact.field();
  nbm::BackboneOptions o;
  o.points = 40;
  o.step = 0.2;
  o.half_period = half;
  const nbm::Backbone b = nbm::backbone(field, 0, o);
  ASSERT_EQ(b.points.size(), 40u) << b.stop_reason;
  const double gp = exact.g - P / exact.k;
  EXPECT_NEAR(b.points[0].amplitude, gp, 1e-12 * gp);
  EXPECT_NEAR(b.points[0].orbit.period, 2 * M_PI / exact.w1(), 1e-12);
  double previous_A = 0;
  for (std::size_t i = 1; i < b.points.size(); ++i) {
    const auto& p = b.points[i];
    const double A = p.amplitude;
    EXPECT_GT(A, previous_A);  // the backbone is followed away from grazing
    previous_A = A;
    EXPECT_NEAR(p.orbit.period, exact.period(A), 1e-10 * p.orbit.period) << "A = " << A;
    EXPECT_EQ(p.orbit.switches.size(), 2u);
    EXPECT_TRUE(p.orbit.stable);
    EXPECT_NEAR(p.orbit.u0(0), P / exact.k - A, 1e-12 * A);  // t = 0: the free turning point
    // Energy: the spring's at the turning point, about the static state.
    EXPECT_NEAR(p.energy, 0.5 * exact.k * A * A, 1e-10 * p.energy);
    EXPECT_EQ(p.events.find("fold"), std::string::npos);
  }
  // Far beyond grazing the frequency nears the gap-0 value 2 w1 w2 / (w1 + w2).
  const double w0 = 2 * exact.w1() * exact.w2() / (exact.w1() + exact.w2());
  EXPECT_GT(b.points.back().amplitude, 20 * gp);
  const double w_last = 2 * M_PI / b.points.back().orbit.period;
  EXPECT_GT(w_last, exact.w1());
  EXPECT_LT(w_last, w0);
  EXPECT_LT(w0 - w_last, 0.1 * (w0 - exact.w1()));
}

INSTANTIATE_TEST_SUITE_P(ClosedForm, BilinearBackbone,
                         ::testing::Values(BilinearCase{1, 0, true}, BilinearCase{10, 0, false},
                                           BilinearCase{100, 0.05, true},
                                           BilinearCase{3, -0.2, false},
                                           BilinearCase{10, 0, true, 0.5}),
                         [](const ::testing::TestParamInfo<BilinearCase>& info) {
                           return case_name(info.param);
                         });

// The frequency branch (BackboneOptions::Branch::frequency) on the same
// oscillators: after the first orbit past grazing, orbits at frequencies
// raised by exactly frequency_step each (no tongue on two dofs: no skip),
// each on the closed-form period-amplitude curve, up to `max_omega`.
TEST_P(BilinearBackbone, TheFrequencyBranchFollowsTheClosedFormPeriod) {
  const auto [kc, P, half, mB] = GetParam();
  Bilinear exact;
  exact.kc = kc, exact.P = P, exact.mB = mB;
  const nbm::ReducedField field = exact.field();
  const double w0 = 2 * exact.w1() * exact.w2() / (exact.w1() + exact.w2());
  nbm::BackboneOptions o;
  o.points = 400;
  o.step = 0.2;
  o.half_period = half;
  o.branch = nbm::BackboneOptions::Branch::frequency;
  o.frequency_step = 0.01;
  o.max_omega = exact.w1() + 0.5 * (w0 - exact.w1());
  const nbm::Backbone b = nbm::backbone(field, 0, o);
  EXPECT_NE(b.stop_reason.find("frequency: the next orbit's omega"), std::string::npos)
      << b.stop_reason;
  ASSERT_GT(b.points.size(), 5u);
  for (std::size_t i = 1; i < b.points.size(); ++i) {
    const auto& p = b.points[i];
    EXPECT_NEAR(p.orbit.period, exact.period(p.amplitude), 1e-10 * p.orbit.period) << i;
    EXPECT_NEAR(p.energy, 0.5 * exact.k * p.amplitude * p.amplitude, 1e-10 * p.energy) << i;
    EXPECT_EQ(p.events.find("tongue"), std::string::npos) << i;
    if (i >= 2) {
      const double ratio = b.points[i - 1].orbit.period / p.orbit.period;
      EXPECT_NEAR(ratio, 1 + o.frequency_step, 1e-12) << i;
      EXPECT_GT(p.amplitude, b.points[i - 1].amplitude) << i;
    }
  }
  const double w_last = 2 * M_PI / b.points.back().orbit.period;
  EXPECT_LE(w_last, o.max_omega);
  EXPECT_GT(w_last * (1 + o.frequency_step), o.max_omega) << b.stop_reason;
}

TEST(Backbone, TheBilinearLimitAtGapZero) {
  // The closed form of the test itself: at a vanishing gap, 2 w1 w2 / (w1 + w2).
  Bilinear b;
  b.kc = 10, b.g = 1e-12;
  EXPECT_NEAR(2 * M_PI / b.period(1), 2 * b.w1() * b.w2() / (b.w1() + b.w2()), 1e-10);
}

// Bad input: each names the argument.
void expect_input_error(const std::function<void()>& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no InputError (expected \"" << words << "\")";
  } catch (const nbm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Backbone, RejectsBadInput) {
  const Chain chain;
  const auto field = chain.field();
  const nbm::BackboneOptions o;
  expect_input_error([&] { nbm::backbone(field, 4, o); }, "mode: 4 out of range [0, 4)");
  expect_input_error([&] { nbm::backbone(field, -1, o); }, "mode: -1 out of range");
  for (double g : {0.0, -0.01}) {
    Chain c = chain;
    c.gaps(1) = g;
    expect_input_error([&] { nbm::backbone(c.field(), 0, o); }, "gaps: contact 1 has gap");
  }
  Chain none = chain;
  none.contact.clear();
  none.gaps.resize(0);
  expect_input_error([&] { nbm::backbone(none.field(), 0, o); },
                     "contacts: the model has no contact");
  Chain pushed = chain;
  pushed.F(5) = 1;  // pushes the contact dofs beyond their gaps at rest
  expect_input_error([&] { nbm::backbone(pushed.field(), 0, o); },
                     "F: the static state under the load closes contact");
  // Two decoupled oscillators, the contact on the second: the first's mode
  // never moves the contact.
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity(), K = Eigen::Matrix3d::Zero();
  M(2, 2) = 0;
  K << 1, 0, 0, 0, 5, -1, 0, -1, 1;
  const nbm::ReducedField decoupled(M, K, Vector::Zero(3), {2}, Vector::Constant(1, 0.1));
  expect_input_error([&] { nbm::backbone(decoupled, 0, o); }, "mode: 0 does not move any contact");
  // A free mass: rigid-body mode 0.
  Eigen::Matrix2d M2, K2;
  M2 << 1, 0, 0, 0;
  K2 << 1, -1, -1, 1;
  const nbm::ReducedField free_body(M2, K2, Vector::Zero(2), {1}, Vector::Constant(1, 0.1));
  expect_input_error([&] { nbm::backbone(free_body, 0, o); }, "mode: 0 is a rigid-body mode");
  // Options.
  auto with = [&](auto change, const std::string& words) {
    nbm::BackboneOptions b;
    change(b);
    expect_input_error([&] { nbm::backbone(field, 0, b); }, words);
  };
  with([](nbm::BackboneOptions& b) { b.points = 0; }, "points: expected >= 1");
  with([](nbm::BackboneOptions& b) { b.step = 0; }, "step: expected a finite step > 0");
  with([](nbm::BackboneOptions& b) { b.step = NAN; }, "step: expected a finite step > 0");
  with([](nbm::BackboneOptions& b) { b.max_energy = -1; }, "energy: expected a limit > 0");
  with([](nbm::BackboneOptions& b) { b.max_iterations = 0; }, "iterations: expected >= 1");
  using Branch = nbm::BackboneOptions::Branch;
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.frequency_step = 0; },
       "frequencyStep: expected a finite relative step > 0, got 0");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.frequency_step = INFINITY; },
       "frequencyStep: expected a finite relative step > 0");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.energy_jump = -0.1; },
       "energyJump: expected a finite relative bound > 0, got -0.1");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.energy_jump = NAN; },
       "energyJump: expected a finite relative bound > 0");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.max_skips = -1; },
       "skips: expected >= 0, got -1");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.max_omega = 0; },
       "to: expected a frequency > 0, got 0");
  with([](nbm::BackboneOptions& b) { b.branch = Branch::frequency, b.max_omega = NAN; },
       "to: expected a frequency > 0");
}

// The fixed-gap bar of benchmarks.md §C (paper NBM) with N elements and no
// load, for the front end on user dofs (user_backbone.hpp).
struct UnloadedBar {
  nbm_test::GapBar bar;
  std::unique_ptr<nbm::ContactProblem> problem;
  std::vector<double> F;
  explicit UnloadedBar(int N) {
    bar.N = N;
    problem = bar.problem();
    F.assign(N + 1, 0.0);
  }
};

// Mode 0 (the bar's first longitudinal mode).
TEST(UserBackbone, ReportsEveryPointOnTheBar) {
  UnloadedBar b(10);
  const auto& bar = b.bar;
  const auto& problem = b.problem;
  auto& F = b.F;
  nbm::BackboneOptions o;
  o.points = 6;
  const nbm::BackboneReport r = nbm::backbone(*problem, F, 0, o);
  ASSERT_EQ(r.points.size(), 6u) << r.stop_reason;
  EXPECT_EQ(r.grazing_contact, 0);
  EXPECT_NEAR(r.points[0].omega, r.linear_omega, 1e-12 * r.linear_omega);
  EXPECT_NE(r.stop_reason.find("points: 6 orbits"), std::string::npos);
  EXPECT_NE(r.summary.find("backbone of mode 0"), std::string::npos);
  for (const auto& p : r.points) {
    EXPECT_NEAR(p.omega * p.period, 2 * M_PI, 1e-12);
    EXPECT_LE(p.periodicity_residual, 1e-10);
    EXPECT_EQ(p.multipliers_re.size(), 2u * (bar.N - 1));
    EXPECT_GE(p.max_multiplier, 1 - 1e-8);
  }
  EXPECT_GT(r.points.back().switches, 0);
  EXPECT_GT(r.points.back().omega, r.points[0].omega);
  // Every orbit by index: point k's monitors, and a state that the exact
  // flow brings back after one period.
  ASSERT_EQ(r.orbits->size(), r.points.size());
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const nbm::OrbitReport o = r.orbits->report(k);
    EXPECT_EQ(o.period, r.points[k].period);
    EXPECT_EQ(o.switches, r.points[k].switches);
    EXPECT_EQ(o.probe, r.probe);
    EXPECT_NEAR(o.amplitude, r.points[k].probe_amplitude, 1e-14 * o.amplitude);
    std::vector<std::vector<double>> us, vs;
    nbm::orbit_states(o, {o.period}, us, vs);
    for (std::size_t i = 0; i < o.u0.size(); ++i) EXPECT_NEAR(us[0][i], o.u0[i], 1e-9 * bar.g);
  }
  expect_input_error([&] { r.orbits->report(r.points.size()); }, "point: 6 out of range [0, 6)");
  // The energy limit stops the backbone at the first orbit beyond it.
  o.max_energy = 0.5 * (r.points[2].energy + r.points[3].energy);
  const nbm::BackboneReport s = nbm::backbone(*problem, F, 0, o);
  EXPECT_EQ(s.points.size(), 4u);
  EXPECT_NE(s.stop_reason.find("energy"), std::string::npos);
  // The load's size is checked, and the reduced basis's size.
  o.modes = -1;
  expect_input_error([&] { nbm::backbone(*problem, F, 0, o); }, "modes: -1; expected >= 0");
  o.modes = 10;
  expect_input_error([&] { nbm::backbone(*problem, F, 0, o); }, "modes: 10; expected 1 .. 9");
  o.modes = 0;
  F.pop_back();
  expect_input_error([&] { nbm::backbone(*problem, F, 0, o); }, "F: size 10, expected 11");
}

// The backbone on the reduced basis, checked on the full model: each
// reduced orbit, expanded to the user's dofs, is the guess of the full
// model's orbit of the same energy (shooting, condition "energy"). With every
// fixed-interface mode the reduced orbits are the full model's (states to
// 1e-9, reduction residuals at round-off); with 6 of 15 they lie within a
// few percent of them, and the reported residual says so. (The two
// backbones' points differ: the arclength steps are measured in their own
// unknowns.)
TEST(UserBackbone, OnTheReducedBasisFollowsTheFullModels) {
  const UnloadedBar b(16);
  const auto& problem = b.problem;
  const auto& F = b.F;
  nbm::BackboneOptions o;
  o.points = 5;
  for (int modes : {15, 6}) {
    o.modes = modes;
    const nbm::BackboneReport red = nbm::backbone(*problem, F, 0, o);
    ASSERT_EQ(red.points.size(), 5u) << modes << ": " << red.stop_reason;
    EXPECT_NE(red.summary.find("reduced basis: " + std::to_string(modes)), std::string::npos);
    for (std::size_t k = 0; k < red.points.size(); ++k) {
      const nbm::OrbitReport r = red.orbits->report(k);
      nbm::OrbitOptions full;
      full.condition = "energy";
      full.amplitude = r.energies[3];
      full.half_period = true;
      full.probe = r.probe;
      const nbm::OrbitReport f = nbm::periodic_orbit(*problem, F, r.u0, r.v0, r.period, full);
      double d = 0, size = 0;
      for (std::size_t i = 0; i < f.u0.size(); ++i)
        d = std::max(d, std::abs(f.u0[i] - r.u0[i])), size = std::max(size, std::abs(f.u0[i]));
      std::printf("backbone, %2d modes, orbit %zu: period %.10f, energy %.6e; the full model's "
                  "orbit of that energy differs by %.1e of its size; reduction residual %.1e\n",
                  modes, k, r.period, red.points[k].energy, d / size, r.reduction_residual);
      EXPECT_LT(d, (modes == 15 ? 1e-9 : 0.05) * size) << modes << " " << k;
      EXPECT_LT(r.reduction_residual, modes == 15 ? 1e-12 : 0.05) << modes << " " << k;
      if (modes == 6) {
        EXPECT_GT(r.reduction_residual, 1e-5) << k;
      }
    }
  }
}

}  // namespace
