// Viscous damping in every time scheme (method.md §9), against independent
// expectations: the exact damped solution of the reduced linear system (a
// bar clamped at the top whose contact node never reaches the ground),
// computed here from a dense generalized eigendecomposition; the modal
// damping ratio zeta_j = a_M / (2 w_j) + b_K w_j / 2 read from the
// logarithmic decrement of a free decay; the energy balance E + D = E(0);
// the damped bouncing bar (dissipation, no penetration); bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "api/solver.hpp"
#include "base/errors.hpp"
#include "contact/contact_problem.hpp"
#include "linalg/dense_eigen.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Bar;
using nbm_test::expect_throw_with;
using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------ the problem

// The bar of test_problems.hpp (L = 1, E = 100, rho = 1, N = 8) clamped at
// x = L, with the ground contact at x = 0 out of reach (gap 1e3), no load:
// a linear system in which only the nodal boundary relation of the open
// contact node acts (method.md §3).
struct Clamped {
  Bar bar;
  nbm_test::Assembled a;
  nbm::SolverOptions options;
  Clamped(const std::string& scheme, double dt, double a_M, double b_K,
          const std::string& mass = "consistent") {
    bar.N = 8;
    a = assemble(bar);
    options.dt = dt;
    options.scheme = nbm_test::scheme_named(scheme);
    options.fixed = {bar.N};
    options.rayleigh_mass = a_M;
    options.rayleigh_stiffness = b_K;
    options.mass = nbm_test::mass_named(mass);
    if (mass == "redistributed") {
      const Mat X = nbm_test::node_positions(bar);
      for (int i = 0; i < X.rows(); ++i) options.positions.push_back(X(i, 0));
    }
  }
  nbm::Solver solver() const {
    return nbm::Solver(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K),
                       nbm_test::ground_contact(1e3), options);
  }
  /// u0(x) = 0.01 (L - x): the bar stretched, at rest.
  std::vector<double> u0() const {
    std::vector<double> u(bar.n_dofs());
    for (int i = 0; i < bar.n_dofs(); ++i) u[i] = 0.01 * (bar.L - i * bar.h());
    return u;
  }
};

// The reduced system of the open contact (method.md §4, §9) in the solver's
// internal coordinates: u = P q (q the interior dofs), P = [I; A] with
// A = -K_CC^-1 K_CO, and its modes K_r phi = w^2 M_r phi, phi' M_r phi = 1.
// With consistent mass the dynamics is M_r q'' + C_r q' + K_r q = 0; the
// mass is the scheme's (lumped for the explicit scheme, redistributed for
// the massless boundary: taken from the problem). With `full`, the contact
// dof is an ordinary unknown (Moreau-Jean): P = I.
struct Reduced {
  Mat P, M_r, K_r, Phi;
  Vec w;
  Reduced(const nbm::ContactProblem& p, const Mat& M, bool full) {
    const Mat K = Mat(p.K());
    const int n = static_cast<int>(K.rows());
    if (full) {
      P = Mat::Identity(n, n);
    } else {
      const int c = static_cast<int>(p.contact_index()[0]);
      P = Mat::Zero(n, n - 1);
      for (int i = 0, k = 0; i < n; ++i)
        if (i != c) P(i, k++) = 1.0;
      P.row(c) = -K.row(c) * P / K(c, c);
    }
    M_r = P.transpose() * M * P;
    K_r = P.transpose() * K * P;
    const nbm::SymmetricEigen eig = nbm::generalized_symmetric_eigen(K_r, M_r);
    Phi = eig.vectors;
    w = eig.values.cwiseSqrt();
  }
  /// The exact damped free motion (Rayleigh C_r = a_M M_r + b_K K_r is
  /// modal) from rest at u0 (full coordinates), at time t.
  Vec exact(const Vec& u0, double t, double a_M, double b_K) const {
    const Vec q0 = Phi.transpose() * M_r * (P.transpose() * P).ldlt().solve(P.transpose() * u0);
    Vec q(q0.size());
    for (int j = 0; j < q0.size(); ++j) {
      const double zeta = a_M / (2 * w(j)) + b_K * w(j) / 2;
      const double wd = w(j) * std::sqrt(1 - zeta * zeta);
      q(j) = std::exp(-zeta * w(j) * t) * q0(j) *
             (std::cos(wd * t) + zeta * w(j) / wd * std::sin(wd * t));
    }
    return P * Phi * q;
  }
};

Mat scheme_mass(const nbm::ContactProblem& p, const std::string& scheme) {
  if (scheme == "explicit") return Mat(p.lumped_mass().asDiagonal());
  return Mat(p.M());
}

// Runs to time T; returns the error of u (internal coordinates, max norm)
// against the exact damped solution.
double error_at(const std::string& scheme, const std::string& mass, double dt, double a_M,
                double b_K, double T) {
  const Clamped c(scheme, dt, a_M, b_K, mass);
  nbm::Solver s = c.solver();
  std::vector<double> u = c.u0(), v(u.size(), 0.0), F(u.size(), 0.0);
  s.initialize(u, v, F);
  const nbm::ContactProblem& p = s.model()->problem();
  const Vec u_start = p.to_internal(nbm_test::to_eigen(u));
  const Reduced r(p, scheme_mass(p, scheme), scheme == "moreau-jean");
  const int n = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < n; ++k) s.step(u, v, F);
  const Vec exact = r.exact(u_start, n * dt, a_M, b_K);
  return (p.to_internal(nbm_test::to_eigen(u)) - exact).cwiseAbs().maxCoeff();
}

struct SchemeCase {
  std::string scheme, mass;
  double a_M, b_K, dt;
};

// gtest prints a parameter's raw bytes unless told otherwise (test names).
void PrintTo(const SchemeCase& c, std::ostream* os) { *os << c.scheme << "/" << c.mass; }

// ------------------------------------- convergence to the damped solution

class DampedConvergence : public ::testing::TestWithParam<SchemeCase> {};

TEST_P(DampedConvergence, SecondOrderToTheExactDampedSolution) {
  const SchemeCase& c = GetParam();
  const double T = 1.0;  // about 2.5 periods of the first mode, zeta_1 about 3%
  const double e1 = error_at(c.scheme, c.mass, c.dt, c.a_M, c.b_K, T);
  const double e2 = error_at(c.scheme, c.mass, c.dt / 2, c.a_M, c.b_K, T);
  const double e3 = error_at(c.scheme, c.mass, c.dt / 4, c.a_M, c.b_K, T);
  const double order = std::log2(e2 / e3);
  std::printf("[ damping  ] %s/%s dt=%g: errors %.3e %.3e %.3e, order %.3f\n", c.scheme.c_str(),
              c.mass.c_str(), c.dt, e1, e2, e3, order);
  EXPECT_GT(std::log2(e1 / e2), 1.85);
  EXPECT_GT(order, 1.85);
  EXPECT_LT(order, 2.15);
  EXPECT_LT(e3, 1e-4 * 0.01);  // relative to the initial amplitude 0.01
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, DampedConvergence,
    ::testing::Values(SchemeCase{"newmark", "consistent", 0.5, 1e-3, 2e-3},
                      SchemeCase{"newmark", "redistributed", 0.5, 1e-3, 2e-3},
                      SchemeCase{"moreau-jean", "consistent", 0.5, 1e-3, 2e-3},
                      SchemeCase{"explicit", "consistent", 2.0, 0.0, 2e-3}),
    [](const ::testing::TestParamInfo<SchemeCase>& info) {
      return info.param.scheme == "moreau-jean"   ? std::string("MoreauJean")
             : info.param.mass == "redistributed" ? std::string("Massless")
             : info.param.scheme == "explicit"    ? std::string("Explicit")
                                                  : std::string("Newmark");
    });

// -------------------------------------------------- modal damping ratios

TEST(ModalDamping, LogDecrementOfAFreeModeGivesTheRayleighRatio) {
  const double a_M = 1.0, b_K = 2e-4;
  for (const int j : {0, 2}) {  // the first and third modes: zeta_j's two terms weigh differently
    Clamped probe("newmark", 1e-3, a_M, b_K);
    nbm::Solver s0 = probe.solver();
    const nbm::ContactProblem& p0 = s0.model()->problem();
    const Reduced r(p0, Mat(p0.M()), false);
    const double w = r.w(j), period = 2 * kPi / w;
    const double zeta = a_M / (2 * w) + b_K * w / 2;

    Clamped c("newmark", period / 400, a_M, b_K);
    nbm::Solver s = c.solver();
    const nbm::ContactProblem& p = s.model()->problem();
    const Vec mode = r.P * r.Phi.col(j) * (0.01 / (r.P * r.Phi.col(j)).cwiseAbs().maxCoeff());
    const Vec mode_user = p.to_user(mode);
    std::vector<double> u = nbm_test::to_std(mode_user), v(u.size(), 0.0), F(u.size(), 0.0);
    s.initialize(u, v, F);
    // The modal coordinate q_j = phi_j' M_r u_O, its successive maxima.
    std::vector<double> peaks;
    double q_prev2 = 0, q_prev = 0;
    const auto modal = [&] {
      const Vec ui = p.to_internal(nbm_test::to_eigen(u));
      const Vec q = (r.P.transpose() * r.P).ldlt().solve(r.P.transpose() * ui);
      return r.Phi.col(j).dot(r.M_r * q);
    };
    q_prev = modal();
    for (int k = 0; k < 400 * 6; ++k) {
      s.step(u, v, F);
      const double q = modal();
      if (k > 0 && q_prev > q_prev2 && q_prev >= q) peaks.push_back(q_prev);
      q_prev2 = q_prev;
      q_prev = q;
    }
    ASSERT_GE(peaks.size(), 4u);
    const double m = static_cast<double>(peaks.size() - 1);
    const double delta = std::log(peaks.front() / peaks.back()) / m;
    const double measured = delta / std::sqrt(4 * kPi * kPi + delta * delta);
    std::printf("[ damping  ] mode %d: w = %.4f, zeta exact %.6f, from log decrement %.6f\n",
                j + 1, w, zeta, measured);
    EXPECT_NEAR(measured, zeta, 2e-3 * zeta);
  }
}

// ------------------------------------------------------ energy balance

// E(t) + D(t) = E(0) on the linear problem: to round-off for the schemes
// that are the trapezoidal rule (average-acceleration Newmark, both mass
// treatments, and Moreau-Jean's theta = 1/2 step), with D by the midpoint
// rule (stepper.hpp); to O(dt^2) for central differences.
TEST(DampedEnergyBalance, EnergyPlusDissipationIsConstantWithoutContact) {
  for (const auto& [scheme, mass, a_M, b_K, tol] :
       {std::tuple{"newmark", "consistent", 0.5, 1e-3, 1e-12},
        {"newmark", "redistributed", 0.5, 1e-3, 1e-12},
        {"moreau-jean", "consistent", 0.5, 1e-3, 1e-12},
        {"explicit", "consistent", 2.0, 0.0, 1e-3}}) {
    SCOPED_TRACE(std::string(scheme) + "/" + mass);
    const Clamped c(scheme, 1e-3, a_M, b_K, mass);
    nbm::Solver s = c.solver();
    std::vector<double> u = c.u0(), v(u.size(), 0.0), F(u.size(), 0.0);
    s.initialize(u, v, F);
    const double E0 = s.energies()[3];
    double worst = 0;
    for (int k = 0; k < 1000; ++k) {
      s.step(u, v, F);
      const std::vector<double> e = s.energies();
      ASSERT_EQ(e.size(), 7u);
      worst = std::max(worst, std::abs(e[3] + e[5] - E0));
    }
    const std::vector<double> e = s.energies();
    std::printf("[ damping  ] %s/%s: D(1) = %.4f E(0), max |E + D - E(0)| = %.2e E(0)\n", scheme,
                mass, e[5] / E0, worst / E0);
    EXPECT_GT(e[5], 0.5 * E0);  // most of the energy is gone after 1 s
    EXPECT_LT(worst, tol * E0);
  }
}

// ------------------------------------------------ the damped bouncing bar

// The free bar of test_problems.hpp dropped from 0.05 onto the ground, with
// Rayleigh damping: the damping dissipates (D > 0, growing), the NBM schemes
// never penetrate and keep the nodal boundary relation (no force on an open
// contact, none pulling on a closed one), and E + D stays below E(0) (impacts only lose energy with
// these schemes); with the massless boundary the balance closes to the time
// discretisation's accuracy.
TEST(DampedBouncingBar, DissipatesWithoutPenetration) {
  Bar bar;
  const auto a = assemble(bar);
  const double mgh = a.mass * bar.g * 0.05;
  for (const auto& [scheme, mass, a_M, b_K, closure] :
       {std::tuple{"newmark", "consistent", 0.2, 1e-3, -1.0},
        {"newmark", "redistributed", 0.2, 1e-3, 0.02},
        {"explicit", "consistent", 0.2, 0.0, -1.0},
        {"moreau-jean", "consistent", 0.2, 1e-3, -1.0}}) {
    SCOPED_TRACE(std::string(scheme) + "/" + mass);
    nbm::SolverOptions o;
    o.dt = scheme == std::string("explicit") ? 5e-4 : 1e-3;
    o.scheme = nbm_test::scheme_named(scheme);
    o.mass = nbm_test::mass_named(mass);
    o.rayleigh_mass = a_M;
    o.rayleigh_stiffness = b_K;
    if (o.mass == nbm::MassTreatment::kRedistributed)
      for (int i = 0; i < bar.n_dofs(); ++i) o.positions.push_back(i * bar.h());
    nbm::Solver s(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), o);
    std::vector<double> u(bar.n_dofs(), 0.05), v(u.size(), 0.0), F = nbm_test::to_std(a.F);
    s.initialize(u, v, F);
    const double E0 = s.energies()[3];
    double min_gap = INFINITY, worst_excess = 0, worst_closure = 0, D_prev = 0, worst_lambda = 0;
    int closed = 0;
    const int n = static_cast<int>(std::lround(1.0 / o.dt));
    for (int k = 0; k < n; ++k) {
      s.step(u, v, F);
      const std::vector<double> e = s.energies();
      ASSERT_GE(e[5], D_prev);  // D never decreases
      D_prev = e[5];
      worst_excess = std::max(worst_excess, e[3] + e[5] - E0);
      worst_closure = std::max(worst_closure, std::abs(e[3] + e[5] - E0));
      min_gap = std::min(min_gap, s.gaps()[0]);
      closed += s.active()[0];
      // The nodal boundary relation holds at every step (method.md §3, §9): an
      // open contact carries no force, a closed one pushes.
      const double lambda = s.reactions()[0];
      worst_lambda = std::max(worst_lambda, s.active()[0] ? -lambda : std::abs(lambda));
    }
    std::printf("[ damping  ] bouncing bar %s/%s: D = %.4f mgh, E + D - E0 in [-%.2e, %.2e] mgh, "
                "min gap %.2e, closed steps %d\n",
                scheme, mass, D_prev / mgh, worst_closure / mgh, worst_excess / mgh, min_gap,
                closed);
    EXPECT_GT(closed, 0);                 // it did bounce
    EXPECT_GT(D_prev, 1e-3 * mgh);        // and dissipated
    EXPECT_LT(worst_excess, 1e-2 * mgh);  // no energy created
    if (scheme != std::string("moreau-jean")) {
      EXPECT_GE(min_gap, -1e-14);
      EXPECT_LE(worst_lambda, 1e-9 * a.mass * bar.g);
    }
    if (closure > 0) {
      EXPECT_LT(worst_closure, closure * mgh);
    }
  }
}

// ----------------------------------------------------------- bad input

TEST(DampingInput, BadDampingIsANamedError) {
  Clamped base("newmark", 1e-3, 0, 0);
  const auto build = [&](const nbm::SolverOptions& o) {
    return [&, o] { nbm::Solver s(nbm_test::to_coo(base.a.M), nbm_test::to_coo(base.a.K),
                                  nbm_test::ground_contact(1e3), o); };
  };
  nbm::SolverOptions o = base.options;
  o.rayleigh_mass = -1;
  expect_throw_with<nbm::InputError>(build(o), {"damping a_M", ">= 0"});
  o = base.options;
  o.rayleigh_stiffness = NAN;
  expect_throw_with<nbm::InputError>(build(o), {"damping b_K", "finite"});
  o = base.options;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(Mat::Identity(3, 3).sparseView()));
  expect_throw_with<nbm::InputError>(build(o), {"damping matrix", "size 3x3", "expected 9x9"});
  Mat C = Mat::Identity(9, 9);
  C(1, 2) = 0.5;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(C.sparseView()));
  expect_throw_with<nbm::InputError>(build(o), {"damping matrix", "not symmetric"});
  C = Mat::Identity(9, 9);
  C(3, 3) = -1;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(C.sparseView()));
  expect_throw_with<nbm::InputError>(build(o), {"damping matrix", "negative diagonal"});
  C = Mat::Identity(9, 9);
  C(4, 4) = INFINITY;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(C.sparseView()));
  expect_throw_with<nbm::InputError>(build(o), {"damping matrix", "non-finite"});
  // The explicit scheme: mass-proportional damping only.
  o = base.options;
  o.scheme = nbm::TimeScheme::kExplicit;
  o.rayleigh_stiffness = 1e-3;
  expect_throw_with<nbm::InputError>(build(o), {"damping", "explicit", "M + dt/2 C"});
  // The massless boundary: no damping matrix on the contact dofs.
  Clamped massless("newmark", 1e-3, 0, 0, "redistributed");
  o = massless.options;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(Mat::Identity(9, 9).sparseView()));
  expect_throw_with<nbm::InputError>(build(o), {"damping matrix", "contact dof"});
  // An assembled matrix that leaves the contact dof out is accepted there.
  C = Mat::Identity(9, 9);
  C(0, 0) = 0;
  o.damping = nbm_test::to_coo(nbm_test::Sparse(C.sparseView()));
  EXPECT_NO_THROW(build(o)());
}

// An assembled matrix equal to a_M M + b_K K gives the run of the Rayleigh
// coefficients (the same C, reached by the other input path), to round-off.
TEST(DampingInput, AssembledMatrixEqualsTheRayleighCoefficients) {
  const Clamped ray("newmark", 1e-3, 0.5, 1e-3);
  Clamped mat("newmark", 1e-3, 0, 0);
  mat.options.damping = nbm_test::to_coo(nbm_test::Sparse(0.5 * mat.a.M + 1e-3 * mat.a.K));
  nbm::Solver s1 = ray.solver(), s2 = mat.solver();
  std::vector<double> u1 = ray.u0(), v1(u1.size(), 0.0), F(u1.size(), 0.0);
  std::vector<double> u2 = u1, v2 = v1;
  s1.initialize(u1, v1, F);
  s2.initialize(u2, v2, F);
  for (int k = 0; k < 500; ++k) {
    s1.step(u1, v1, F);
    s2.step(u2, v2, F);
  }
  EXPECT_LT((nbm_test::to_eigen(u1) - nbm_test::to_eigen(u2)).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(s1.energies()[5], s2.energies()[5], 1e-12 * s1.energies()[5]);
}

}  // namespace
