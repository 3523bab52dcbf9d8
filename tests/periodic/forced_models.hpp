// Damped, forced models for the tests of the forced exact flow and forced
// orbits, with references computed independently of the exact flow: the
// reduced matrices by the Schur complement of method.md §3 (massless contact
// dof, open), a dense matrix exponential of the augmented first-order system,
// and the frequency response of the full model.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "periodic/exact_flow.hpp"
#include "periodic/reduced_field.hpp"
#include "rk4.hpp"

namespace nbm_test {

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;

/// A chain of `n` unit-like masses (interior dofs 0..n-1, dof 0 tied to the
/// ground), the last one joined by a spring kc to a massless contact dof n
/// (obstacle at u_n <= gap). With ground = 0 the chain is free (a rigid mode).
struct ForcedChain {
  Index n = 3;
  double ground = 1, kc = 2, gap = 1e6;

  Matrix M() const {
    Matrix m = Matrix::Zero(n + 1, n + 1);
    for (Index i = 0; i < n; ++i) m(i, i) = 1 + 0.25 * i;
    return m;
  }
  Matrix K() const {
    Matrix k = Matrix::Zero(n + 1, n + 1);
    k(0, 0) = ground;
    auto spring = [&](Index i, Index j, double s) {
      k(i, i) += s, k(j, j) += s, k(i, j) -= s, k(j, i) -= s;
    };
    for (Index i = 0; i + 1 < n; ++i) spring(i, i + 1, 1.5 + 0.5 * i);
    spring(n - 1, n, kc);
    return k;
  }
  nbm::ReducedField field(const Vector& F0) const {
    return nbm::ReducedField(M(), K(), F0, {n}, Vector::Constant(1, gap));
  }
  /// Reduced stiffness with the contact open: K_OO - K_OC K_CC^-1 K_CO.
  Matrix reduced_K() const {
    const Matrix k = K();
    return k.topLeftCorner(n, n) - k.topRightCorner(n, 1) * k.bottomLeftCorner(1, n) / k(n, n);
  }
  /// Brute-force reference with the gap in reach, by RK4 (rk4.hpp): the
  /// massless contact dof follows the last mass while open and stops at the
  /// gap, so the contact adds the bilinear force kc [u_{n-1} - gap]_+ to the
  /// open model, M u'' + a_M M u' + K_r u = Fc cos(w t) (interior dofs).
  /// x = (u, v) at t = 0, over `periods` periods 2 pi / w.
  Vector integrate(double a_M, const Vector& Fc, double w, const Vector& x, int periods,
                   int steps = 40000) const {
    return integrate_damped(a_M * M().topLeftCorner(n, n), Fc, w, x, periods, steps);
  }
  /// The same with any interior damping matrix Cr (n x n).
  Vector integrate_damped(const Matrix& Cr, const Vector& Fc, double w, const Vector& x,
                          int periods, int steps = 40000) const {
    const Matrix Mr = M().topLeftCorner(n, n), Minv = Mr.inverse(), Kr = reduced_K();
    auto field = [&](double t, const Vector& y) {
      Vector force = Fc * std::cos(w * t) - Kr * y.head(n) - Cr * y.tail(n);
      force(n - 1) -= kc * std::max(y(n - 1) - gap, 0.0);
      Vector dy(2 * n);
      dy << y.tail(n), Minv * force;
      return dy;
    };
    return rk4_periods(field, x, 2 * M_PI / w, periods, steps);
  }
};

/// exp(A) by scaling and squaring of a Taylor series (dense, small A).
inline Matrix expm(const Matrix& A) {
  int s = 0;
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  while (norm / std::ldexp(1.0, s) > 0.25) ++s;
  const Matrix B = A / std::ldexp(1.0, s);
  Matrix E = Matrix::Identity(A.rows(), A.cols()), term = E;
  for (int k = 1; k <= 24; ++k) {
    term = term * B / k;
    E += term;
  }
  for (int k = 0; k < s; ++k) E = E * E;
  return E;
}

/// The reference flow of M u'' + C u' + K u = F0 + sum_k (Fc_k cos k w t +
/// Fs_k sin k w t) (all n x n, interior dofs) from (u0, v0) at time t0 over
/// t: the matrix exponential of the first-order system augmented with the
/// states 1, cos(k w t), sin(k w t). Returns (u, v) and, in `transition`,
/// d(u, v)(t0 + t) / d(u0, v0).
inline Vector reference_flow(const Matrix& M, const Matrix& C, const Matrix& K, const Vector& F0,
                             const std::vector<Vector>& Fc, const std::vector<Vector>& Fs,
                             double w, const Vector& u0, const Vector& v0, double t0, double t,
                             Matrix* transition = nullptr) {
  const Index n = M.rows(), H = static_cast<Index>(Fc.size()), m = 2 * n + 1 + 2 * H;
  const Matrix Minv = M.inverse();
  Matrix A = Matrix::Zero(m, m);
  A.block(0, n, n, n) = Matrix::Identity(n, n);
  A.block(n, 0, n, n) = -Minv * K;
  A.block(n, n, n, n) = -Minv * C;
  A.block(n, 2 * n, n, 1) = Minv * F0;
  Vector z(m);
  z << u0, v0, 1, Vector::Zero(2 * H);
  for (Index k = 0; k < H; ++k) {
    const double W = (k + 1) * w;
    const Index c = 2 * n + 1 + 2 * k, s = c + 1;
    A.block(n, c, n, 1) = Minv * Fc[k];
    A.block(n, s, n, 1) = Minv * Fs[k];
    A(c, s) = -W;  // cos' = -W sin
    A(s, c) = W;   // sin' = W cos
    z(c) = std::cos(W * t0), z(s) = std::sin(W * t0);
  }
  const Matrix E = expm(A * t);
  if (transition) *transition = E.topLeftCorner(2 * n, 2 * n);
  return (E * z).head(2 * n);
}

/// The monodromy of `flow` over [t0, t0 + T] from (u0, v0) by central
/// differences of the flow map (step eps in every state component): the
/// reference of the monodromy through switches.
inline Matrix monodromy_by_differences(const nbm::ExactFlow& flow, const Vector& u0,
                                       const Vector& v0, double T, double t0,
                                       double eps = 1e-6) {
  const Index n = u0.size();
  Matrix fd(2 * n, 2 * n);
  for (Index j = 0; j < 2 * n; ++j) {
    Vector up = u0, vp = v0, um = u0, vm = v0;
    (j < n ? up(j) : vp(j - n)) += eps;
    (j < n ? um(j) : vm(j - n)) -= eps;
    const auto p = flow.integrate(up, vp, T, false, {}, t0);
    const auto m = flow.integrate(um, vm, T, false, {}, t0);
    fd.col(j) << (p.u - m.u) / (2 * eps), (p.v - m.v) / (2 * eps);
  }
  return fd;
}

/// The monodromy of the impact oscillators' flow (one interior dof) from
/// (u, v) = (-2.5, 0.7) at t0 = 0.4 over 13 time units, through at least four
/// switches, against monodromy_by_differences.
inline void expect_monodromy_matches_differences(const nbm::ExactFlow& flow,
                                                 const std::string& what) {
  const Vector u0 = Vector::Constant(1, -2.5), v0 = Vector::Constant(1, 0.7);
  const double T = 13, t0 = 0.4;
  const auto r = flow.integrate(u0, v0, T, true, {}, t0);
  ASSERT_GE(r.switches.size(), 4u) << what;
  const Matrix fd = monodromy_by_differences(flow, u0, v0, T, t0);
  EXPECT_LT((r.monodromy - fd).norm(), 1e-7 * fd.norm()) << what << "\n"
                                                          << r.monodromy << "\n"
                                                          << fd;
}

/// The internal load vector (size n + 1, zero on the contact dof) of
/// interior values.
inline Vector internal(const Vector& interior) {
  Vector x = Vector::Zero(interior.size() + 1);
  x.head(interior.size()) = interior;
  return x;
}

}  // namespace nbm_test
