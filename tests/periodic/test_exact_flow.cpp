// The exact flow of the reduced NBM equations: switching-time search, modal
// solution, energy, and the monodromy matrix against finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "oscillators.hpp"
#include "periodic/exact_flow.hpp"
#include "periodic/trig_sum.hpp"

namespace {

using nbm::Matrix;
using nbm::Vector;
using nbm_test::ImpactOscillator;

nbm::TrigSum single_cosine(double c, double a, double nu) {
  nbm::TrigSum h;
  h.c = Vector::Constant(1, c);
  h.p = h.q = Vector::Zero(1);
  h.a = Matrix::Constant(1, 1, a);
  h.b = Matrix::Zero(1, 1);
  h.nu = Vector::Constant(1, nu);
  return h;
}

TEST(SwitchingSearch, FindsTheFirstTransversalRootToRoundOff) {
  // h = cos(3 t) - 0.5: first root pi / 9.
  const auto c = nbm::first_crossing(single_cosine(-0.5, 1, 3), 0, 10);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->t, M_PI / 9, 1e-15);
  // From just after the first root the function is negative: an error.
  EXPECT_THROW(nbm::first_crossing(single_cosine(-0.5, 1, 3), 0.5, 10), nbm::NumericalError);
  // Next crossing after the positive lobe that starts at 5 pi / 9.
  const auto d = nbm::first_crossing(single_cosine(-0.5, 1, 3), 5 * M_PI / 9 + 1e-3, 10);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->t, 7 * M_PI / 9, 1e-14);
}

TEST(SwitchingSearch, TangentialContactIsNotACrossing) {
  // h = 1 - cos(t) touches zero at 2 pi without changing sign.
  EXPECT_FALSE(nbm::first_crossing(single_cosine(1, -1, 1), 0.1, 10));
  // A dip below zero of depth 1e-9 is found.
  const auto c = nbm::first_crossing(single_cosine(1 - 1e-9, -1, 1), 0.1, 10);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->t, 2 * M_PI - std::acos(1 - 1e-9), 1e-12);
}

TEST(ExactFlow, BelowGrazingTheMotionIsTheLinearOneWithItsPeriod) {
  ImpactOscillator osc;
  osc.mB = 0.3;
  const auto field = osc.field();
  const nbm::ExactFlow flow(field);
  const double T = 2 * M_PI / std::sqrt(osc.k / (osc.m + osc.mB));
  const auto r = flow.integrate(Vector::Constant(1, -0.9), Vector::Zero(1), T, true);
  EXPECT_TRUE(r.switches.empty());
  EXPECT_NEAR(r.u(0), -0.9, 1e-14);
  EXPECT_NEAR(r.v(0), 0, 1e-14);
  EXPECT_NEAR((r.monodromy - Matrix::Identity(2, 2)).norm(), 0, 1e-13);
}

TEST(ExactFlow, MasslessBoundaryConservesEnergyThroughSwitches) {
  for (double kc : {1.0, 10.0, 1e4}) {
    ImpactOscillator osc;
    osc.kc = kc;
    const auto field = osc.field();
    const nbm::ExactFlow flow(field);
    Vector u = Vector::Constant(1, -3), v = Vector::Zero(1);
    const double E0 = field.energies(u, v)(3);
    const auto r = flow.integrate(u, v, 20, false);
    EXPECT_GE(r.switches.size(), 4u) << kc;
    EXPECT_NEAR(field.energies(r.u, r.v)(3), E0, 1e-12 * E0) << kc;
  }
}

// A sample at the end of the span is the end state, whatever the pieces'
// durations add up to: their sum may fall an ulp short of T (the last
// sample was then left unwritten: nbmOrbitState returned uninitialised
// memory at some times of a 3D blade's orbit). Spans through many switches,
// each sampled at its end and halfway.
TEST(ExactFlow, ASampleAtTheEndOfTheSpanIsTheEndState) {
  ImpactOscillator osc;
  osc.kc = 10;
  const auto field = osc.field();
  const nbm::ExactFlow flow(field);
  const Vector u = Vector::Constant(1, -3), v = Vector::Zero(1);
  int switching = 0;
  for (int k = 1; k <= 3000; ++k) {
    const double T = 0.0371 * k;
    const auto r = flow.integrate(u, v, T, false, {0.5 * T, T});
    const auto half = flow.integrate(u, v, 0.5 * T, false);
    ASSERT_EQ(r.samples.cols(), 2);
    EXPECT_EQ(r.samples(0, 1), r.u(0)) << T;
    EXPECT_EQ(r.samples(1, 1), r.v(0)) << T;
    EXPECT_NEAR(r.samples(0, 0), half.u(0), 1e-12) << T;
    switching += r.switches.size() > 2;
  }
  EXPECT_GT(switching, 200);
  EXPECT_THROW(flow.integrate(u, v, 1, false, {0.5, 1.5}), nbm::InputError);
  EXPECT_THROW(flow.integrate(u, v, 1, false, {0.5, 0.2}), nbm::InputError);
}

// Monodromy of the exact flow against central differences of the flow map,
// through two contact phases. With mass on the contact dof (m_B > 0) the
// acceleration jumps at the switches and only the saltation terms make the
// two agree: removing them changes the monodromy by O(1).
void expect_monodromy_matches_differences(const ImpactOscillator& osc, double T) {
  const auto field = osc.field();
  const nbm::ExactFlow flow(field);
  const Vector u0 = Vector::Constant(1, -2.5), v0 = Vector::Constant(1, 0.7);
  const auto r = flow.integrate(u0, v0, T, true);
  ASSERT_GE(r.switches.size(), 4u);
  Matrix fd(2, 2);
  const double eps = 1e-6;
  for (int j = 0; j < 2; ++j) {
    Vector up = u0, vp = v0, um = u0, vm = v0;
    (j == 0 ? up : vp)(0) += eps;
    (j == 0 ? um : vm)(0) -= eps;
    const auto p = flow.integrate(up, vp, T, false), m = flow.integrate(um, vm, T, false);
    fd(0, j) = (p.u(0) - m.u(0)) / (2 * eps);
    fd(1, j) = (p.v(0) - m.v(0)) / (2 * eps);
  }
  EXPECT_LT((r.monodromy - fd).norm(), 1e-7 * fd.norm()) << "mB " << osc.mB << "\n"
                                                          << r.monodromy << "\n"
                                                          << fd;
  // The monodromy of a Hamiltonian-like reversible flow has determinant 1.
  EXPECT_NEAR(r.monodromy.determinant(), 1, 1e-9);
}

TEST(ExactFlow, MonodromyMatchesFiniteDifferencesWithMassOnTheBoundary) {
  ImpactOscillator osc;
  osc.mB = 0.5;
  expect_monodromy_matches_differences(osc, 13);
}

TEST(ExactFlow, MonodromyMatchesFiniteDifferencesForTheMasslessBoundary) {
  ImpactOscillator osc;
  osc.kc = 10;
  expect_monodromy_matches_differences(osc, 13);
}

}  // namespace
