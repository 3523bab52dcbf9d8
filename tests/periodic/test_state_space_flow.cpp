// The exact flow with an assembled damping matrix that does not decouple on
// the modes (state_space_flow.hpp, method.md §9): the region flow and its
// transition matrix against a matrix exponential, the flow through switches
// against the modal flow when the matrix is Rayleigh, the monodromy against
// finite differences, a forced orbit against brute-force time integration to
// steady state, and the named errors.
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "forced_models.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/shooting.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_test::ForcedChain;
using nbm_test::internal;

// A damping matrix on the interior dofs of a chain of n masses (zero on the
// contact dof n), not proportional to M or K: a dashpot to the ground on dof
// 0 and one between dofs 1 and 2.
Matrix interior_damping(Index n, double ground, double between) {
  Matrix C = Matrix::Zero(n, n);
  C(0, 0) = ground;
  if (n > 2) C(1, 1) += between, C(2, 2) += between, C(1, 2) -= between, C(2, 1) -= between;
  return C;
}

nbm::Damping with_matrix(const Matrix& C_interior, double a_M = 0, double b_K = 0) {
  const Index n = C_interior.rows();
  Matrix C = Matrix::Zero(n + 1, n + 1);
  C.topLeftCorner(n, n) = C_interior;
  nbm::Damping d;
  d.a_M = a_M, d.b_K = b_K;
  d.C_user = C.sparseView();
  return d;
}

TEST(StateSpaceFlow, MatchesTheExponentialOfTheSystemWithANonProportionalDampingMatrix) {
  for (const double scale : {0.05, 0.6}) {
    ForcedChain chain;
    chain.n = 3;
    const Index n = chain.n;
    Vector F0(n), Fc(n), Fs(n);
    for (Index i = 0; i < n; ++i) F0(i) = -0.3 + 0.1 * i, Fc(i) = 0.7 - 0.2 * i, Fs(i) = 0.1 * i;
    const auto field = chain.field(internal(F0));
    const Matrix Cm = interior_damping(n, scale, 0.5 * scale);
    const nbm::Damping damping = with_matrix(Cm, 0.02, 0.01);
    nbm::HarmonicLoad load;
    load.omega = 1.3;
    load.cos = {internal(Fc)};
    load.sin = {internal(Fs)};
    const nbm::ExactFlow flow(field, damping, load);

    const Matrix M = chain.M().topLeftCorner(n, n), K = chain.reduced_K();
    const Matrix C = 0.02 * M + 0.01 * K + Cm;
    Vector u0(n), v0(n);
    for (Index i = 0; i < n; ++i) u0(i) = 0.2 - 0.15 * i, v0(i) = 0.4 * std::cos(i);
    for (double t0 : {0.0, 0.7}) {
      for (double t : {0.3, 2.0, 9.0}) {
        Matrix X_ref;
        const Vector ref =
            nbm_test::reference_flow(M, C, K, F0, {Fc}, {Fs}, load.omega, u0, v0, t0, t, &X_ref);
        const auto r = flow.integrate(u0, v0, t, true, {}, t0);
        ASSERT_TRUE(r.switches.empty());
        Vector x(2 * n);
        x << r.u, r.v;
        EXPECT_LT((x - ref).norm(), 1e-11 * std::max(1.0, ref.norm()))
            << "scale " << scale << " t0 " << t0 << " t " << t;
        EXPECT_LT((r.monodromy - X_ref).norm(), 1e-11 * std::max(1.0, X_ref.norm()))
            << "scale " << scale << " t0 " << t0 << " t " << t;
        const double W = load.omega * (t0 + t);
        const Vector F = F0 + Fc * std::cos(W) + Fs * std::sin(W);
        const Vector a_ref = M.inverse() * (F - C * ref.tail(n) - K * ref.head(n));
        EXPECT_LT((r.a - a_ref).norm(), 1e-10 * std::max(1.0, a_ref.norm())) << "scale " << scale;
      }
    }
  }
}

// A damping matrix equal to a_M M (massless contact dof: zero there) must give
// the modal flow of the Rayleigh coefficient a_M, switches included: two
// independent computations of the same flow.
TEST(StateSpaceFlow, ARayleighMatrixGivesTheModalFlowThroughSwitches) {
  ForcedChain chain;
  chain.n = 3;
  chain.gap = 0.4;
  const Index n = chain.n;
  Vector Fc(n);
  for (Index i = 0; i < n; ++i) Fc(i) = 0.9 - 0.2 * i;
  const auto field = chain.field(Vector::Zero(n + 1));
  nbm::HarmonicLoad load;
  load.omega = 0.8;
  load.cos = {internal(Fc)};
  const double a_M = 0.07;
  nbm::Damping rayleigh;
  rayleigh.a_M = a_M;
  const nbm::ExactFlow modal(field, rayleigh, load);
  const nbm::ExactFlow state_space(field, with_matrix(a_M * chain.M().topLeftCorner(n, n)), load);
  const Vector u0 = Vector::Zero(n), v0 = Vector::Constant(n, 0.3);
  const auto a = modal.integrate(u0, v0, 30, true);
  const auto b = state_space.integrate(u0, v0, 30, true);
  ASSERT_GE(a.switches.size(), 4u);
  ASSERT_EQ(a.switches.size(), b.switches.size());
  for (std::size_t k = 0; k < a.switches.size(); ++k)
    EXPECT_NEAR(a.switches[k].t, b.switches[k].t, 1e-10) << "switch " << k;
  EXPECT_LT((a.u - b.u).norm(), 1e-10 * a.u.norm());
  EXPECT_LT((a.v - b.v).norm(), 1e-10 * a.v.norm());
  EXPECT_LT((a.monodromy - b.monodromy).norm(), 1e-9 * a.monodromy.norm());
}

TEST(StateSpaceFlow, MonodromyThroughSwitchesMatchesFiniteDifferences) {
  ForcedChain chain;
  chain.n = 3;
  chain.gap = 0.4;
  const Index n = chain.n;
  const auto field = chain.field(Vector::Zero(n + 1));
  nbm::HarmonicLoad load;
  load.omega = 0.8;
  load.cos = {internal(Vector::Constant(n, 0.6))};
  load.sin = {internal(Vector::LinSpaced(n, 0.1, 0.3))};
  const nbm::ExactFlow flow(field, with_matrix(interior_damping(n, 0.15, 0.2), 0, 0.01), load);
  const Vector u0 = Vector::Zero(n), v0 = Vector::Constant(n, 0.3);
  const double T = 17, t0 = 0.3;
  const auto r = flow.integrate(u0, v0, T, true, {}, t0);
  ASSERT_GE(r.switches.size(), 4u);
  const Matrix fd = nbm_test::monodromy_by_differences(flow, u0, v0, T, t0);
  EXPECT_LT((r.monodromy - fd).norm(), 1e-6 * fd.norm()) << r.monodromy << "\n\n" << fd;
}

// The forced orbit with contact under a non-proportional damping matrix
// against RK4 to steady state (ForcedChain::integrate_damped: the massless
// contact dof as a bilinear spring). At w = 0.9 the time integration does not
// settle on a period-1 orbit: the one shooting finds there must be unstable.
TEST(StateSpaceFlow, ForcedOrbitWithContactIsTheSteadyStateOfBruteForceIntegration) {
  ForcedChain chain;
  chain.n = 3;
  chain.gap = 0.5;
  const Index n = chain.n;
  const Matrix Cm = interior_damping(n, 0.2, 0.1);
  const Vector Fc = Vector::LinSpaced(n, 0.3, 0.9);
  const auto field = chain.field(Vector::Zero(n + 1));
  for (double w : {0.4, 0.7, 0.9}) {
    nbm::HarmonicLoad load;
    load.omega = w;
    load.cos = {internal(Fc)};
    const nbm::ExactFlow flow(field, with_matrix(Cm), load);
    // 150 periods from rest (coarse steps), then shooting from there.
    const Vector x = chain.integrate_damped(Cm, Fc, w, Vector::Zero(2 * n), 150, 8000);
    const nbm::PeriodicProblem forced(flow, 1);
    const auto orbit = nbm::shoot(forced, x.head(n), x.tail(n), forced.period(), {});
    ASSERT_FALSE(orbit.switches.empty()) << "w " << w << ": the orbit should touch the wall";
    Vector x0(2 * n);
    x0 << orbit.u0, orbit.v0;
    const Vector x1 = chain.integrate_damped(Cm, Fc, w, x0, 1);
    EXPECT_LT((x1 - x0).norm(), 1e-8 * x0.norm()) << "w " << w << ": RK4 over one period";
    const bool settled = (chain.integrate_damped(Cm, Fc, w, x, 1, 8000) - x).norm() < 1e-6;
    EXPECT_EQ(orbit.stable, settled) << "w " << w;
    if (settled) {
      EXPECT_LT((x - x0).norm(), 1e-6 * x0.norm()) << "w " << w;
    }
  }
}

TEST(StateSpaceFlow, BadDampingMatricesAreNamedErrors) {
  ForcedChain chain;
  chain.n = 1;
  const auto field = chain.field(Vector::Zero(2));
  nbm::HarmonicLoad load;
  load.omega = 0.5;
  load.cos = {internal(Vector::Ones(1))};
  nbm::Damping on_contact;
  on_contact.C_user = Matrix::Identity(2, 2).sparseView();
  EXPECT_THROW(nbm::ExactFlow(field, on_contact, load), nbm::InputError);
  nbm::Damping wrong_size;
  wrong_size.C_user = Matrix::Identity(3, 3).sparseView();
  EXPECT_THROW(nbm::ExactFlow(field, wrong_size, load), nbm::InputError);
  Matrix nan = Matrix::Zero(2, 2);
  nan(0, 0) = NAN;
  nbm::Damping non_finite;
  non_finite.C_user = nan.sparseView();
  EXPECT_THROW(nbm::ExactFlow(field, non_finite, load), nbm::InputError);

  // Reduced stiffness 1 and unit mass: C = 2 is exactly critical (a defective
  // first-order system), C = -0.1 a growing mode.
  for (double c : {2.0, -0.1}) {
    const nbm::ExactFlow flow(field, with_matrix(Matrix::Constant(1, 1, c)), load);
    EXPECT_THROW(flow.integrate(Vector::Zero(1), Vector::Zero(1), 1, false), nbm::NumericalError)
        << "c " << c;
  }
  // Moving gaps need the moving switching offsets of the modal flow.
  nbm::HarmonicLoad moving = load;
  moving.gap_cos = {Vector::Constant(1, 0.1)};
  EXPECT_THROW(nbm::ExactFlow(field, with_matrix(Matrix::Constant(1, 1, 0.3)), moving),
               nbm::InputError);
  // Harmonic balance carries Rayleigh damping only: a named error, not a
  // silently undamped orbit.
  const nbm::ExactFlow damped(field, with_matrix(Matrix::Constant(1, 1, 0.3)), load);
  const nbm::PeriodicProblem damped_problem(damped, 1);
  EXPECT_THROW(nbm::harmonic_balance(damped_problem, Vector::Zero(1), Vector::Zero(1),
                                     damped_problem.period(), {}),
               nbm::InputError);
  ForcedChain free_chain = chain;
  free_chain.ground = 0;
  const auto free_field = free_chain.field(Vector::Zero(2));
  const nbm::ExactFlow rigid(free_field, with_matrix(Matrix::Constant(1, 1, 0.3)), load);
  EXPECT_THROW(rigid.integrate(Vector::Zero(1), Vector::Zero(1), 1, false), nbm::NumericalError);
}

}  // namespace
