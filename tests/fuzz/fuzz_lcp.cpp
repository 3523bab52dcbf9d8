// libFuzzer target: the exact LCP solver (nbm::LcpSolver::solve) on random
// symmetric positive definite matrices of size 1..12 built from the fuzz
// bytes (overall scales 1e-12..1e12, condition numbers up to about 1e16 and
// beyond) and random q (scales 1e-12..1e12, exact zeros, degenerate rows), a
// random warm start, and sometimes corrupted input (NaN, inf, non-symmetric,
// wrong sizes).
//
// Properties:
//  * corrupted input: nbm::InputError, nothing else;
//  * valid input: no InputError; nbm::NumericalError only if A is not safely
//    positive definite in floating point (cond2(A) > 1e8) or an extreme
//    value (1e300, denormal, DBL_MAX) was injected (the solution may overflow);
//  * a returned solution is structurally exact: sizes n, z >= 0, w >= 0,
//    z_i = 0 on the active set, w_i = 0 on the free set, all finite;
//  * its merit LcpSolver::residual(A, q, z) <= 100 n^2.5 eps max(1, cond2(A)).
//
// Why that tolerance is sound (backward error, not forward error): residual()
// measures the returned z itself, z scaled by |z|_inf and w = q + A z by
// max(|q|_inf, |A z|_inf). On the free set F, z_F solves A_FF z_F = -q_F by
// Cholesky, backward stable: |q_F + A_FF z_F| <= c n^2 eps |A| |z|; the sign
// clipping of z (|dz| <= 8 n eps |z|_inf) adds at most 8 n^2 eps |A| |z|. On
// the active set the solver accepted w_i >= -8 n eps (|q| + |A| |z|). Both are
// relative to w_scale >= |A z|_inf >= lambda_min |z|_2 / sqrt(n), and
// |A| <= lambda_max, hence a bound c' n^2.5 eps cond2(A). No forward error
// (which would bring cond^2) enters. cond2 is computed from the singular values of
// A; when A is not positive definite in floating point (its Cholesky
// factorization fails) the residual is not checked.
//
// Corpus: lcp-overflow (A = 8.7e-26 I, q = (-1e300, 0)) made solve() return
// z = inf as a "solution"; it now throws nbm::NumericalError (lcp.cpp).
#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "fuzz_common.hpp"
#include "linalg/lcp.hpp"

using nbm::Index;
using nbm::Matrix;
using nbm::Vector;
using nbm_fuzz::fail;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Matrix random_matrix(FuzzedDataProvider& fdp, Index rows, Index cols) {
  Matrix B(rows, cols);
  for (Index i = 0; i < rows; ++i)
    for (Index j = 0; j < cols; ++j)
      B(i, j) = fdp.ConsumeIntegralInRange<int>(0, 4) == 0 ? 0.0 : nbm_fuzz::uniform(fdp, -1, 1);
  return B;
}

// Random orthogonal matrix: Q of the QR factorisation of a random matrix
// (the identity if the bytes run out).
Matrix random_orthogonal(FuzzedDataProvider& fdp, Index n) {
  Matrix B = random_matrix(fdp, n, n) + 1e-3 * Matrix::Identity(n, n);
  return Eigen::HouseholderQR<Matrix>(B).householderQ() * Matrix::Identity(n, n);
}

Matrix random_spd(FuzzedDataProvider& fdp, Index n) {
  Matrix A;
  switch (fdp.ConsumeIntegralInRange<int>(0, 4)) {
    case 0: {  // Gram matrix plus a shift: B B' + delta I
      const Index m = fdp.ConsumeIntegralInRange<Index>(1, 2 * n);
      const Matrix B = random_matrix(fdp, n, m);
      A = B * B.transpose() + nbm_fuzz::pow10_in(fdp, -14, 1) * Matrix::Identity(n, n);
      break;
    }
    case 1: {  // badly scaled: D C D, C well conditioned, D over 12 decades
      const Matrix B = random_matrix(fdp, n, n);
      const Matrix C = B * B.transpose() / double(n) + Matrix::Identity(n, n);
      Vector d(n);
      for (Index i = 0; i < n; ++i) d(i) = nbm_fuzz::pow10_in(fdp, -6, 6);
      A = d.asDiagonal() * C * d.asDiagonal();
      break;
    }
    case 2: {  // prescribed spectrum, condition number up to 1e16
      const Matrix Q = random_orthogonal(fdp, n);
      const double decades = fdp.ConsumeFloatingPointInRange<double>(0, 16);
      Vector lambda(n);
      for (Index i = 0; i < n; ++i)
        lambda(i) = std::pow(10.0, -decades * nbm_fuzz::uniform(fdp, 0, 1));
      A = Q * lambda.asDiagonal() * Q.transpose();
      break;
    }
    case 3: {  // stiffness-like: a chain of springs, optionally grounded
      A = Matrix::Zero(n, n);
      for (Index i = 0; i + 1 < n; ++i) {
        const double k = nbm_fuzz::pow10_in(fdp, -4, 4);
        A(i, i) += k, A(i + 1, i + 1) += k, A(i, i + 1) -= k, A(i + 1, i) -= k;
      }
      for (Index i = 0; i < n; ++i)
        if (i == 0 || fdp.ConsumeBool()) A(i, i) += nbm_fuzz::pow10_in(fdp, -8, 2);
      break;
    }
    default: {  // nearly duplicated rows: v v' + eps I plus a little noise
      const Matrix v = random_matrix(fdp, n, 1) + Matrix::Ones(n, 1);
      const Matrix B = random_matrix(fdp, n, n);
      A = v * v.transpose() + nbm_fuzz::pow10_in(fdp, -12, -2) * (B * B.transpose()) +
          nbm_fuzz::pow10_in(fdp, -14, -4) * Matrix::Identity(n, n);
      break;
    }
  }
  A *= nbm_fuzz::pow10_in(fdp, -12, 12);
  // Exactly symmetric (the products above are only to round-off).
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < i; ++j) A(j, i) = A(i, j);
  return A;
}

// cond2 of a symmetric A, infinite unless A is positive definite in floating
// point (its Cholesky factorization succeeds): the ratio of its extreme
// singular values, its eigenvalues then. Not by SelfAdjointEigenSolver: its
// tridiagonalization calls BLAS dsymv (EIGEN_USE_BLAS), and OpenBLAS 0.3.21's
// dsymv_L kernel reads past the end of the small matrix it is given, which
// ASan's allocator once placed at the end of a mapped region (a SEGV in the
// CI run; corpus/fuzz_lcp/openblas-dsymv-overread). JacobiSVD uses plane
// rotations only.
double cond2(const Matrix& A) {
  if (Eigen::LLT<Matrix>(A).info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::JacobiSVD<Matrix> svd(A);
  const double smin = svd.singularValues().minCoeff(), smax = svd.singularValues().maxCoeff();
  if (!(smin > 0)) return std::numeric_limits<double>::infinity();
  return smax / smin;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider fdp(data, size);
  const Index n = fdp.ConsumeIntegralInRange<Index>(1, 12);
  Matrix A = random_spd(fdp, n);

  Vector q(n);
  const double q_scale = nbm_fuzz::pow10_in(fdp, -12, 12);
  const int q_mode = fdp.ConsumeIntegralInRange<int>(0, 3);
  for (Index i = 0; i < n; ++i) {
    const int kind = fdp.ConsumeIntegralInRange<int>(0, 7);
    q(i) = kind == 0 ? 0.0 : nbm_fuzz::uniform(fdp, -1, 1) * q_scale;
  }
  if (q_mode == 1) {  // degenerate: q = -A z* for a z* with zeros (w*_i = z*_i = 0)
    Vector zs(n);
    for (Index i = 0; i < n; ++i)
      zs(i) = fdp.ConsumeBool() ? 0.0 : nbm_fuzz::uniform(fdp, 0, 1) * q_scale;
    q = -(A * zs);
  } else if (q_mode == 2) {  // all positive (solution z = 0) or all negative
    const double sign = fdp.ConsumeBool() ? 1.0 : -1.0;
    q = sign * q.cwiseAbs();
  }

  std::vector<bool> guess;
  if (fdp.ConsumeBool()) {
    guess.resize(n);
    for (Index i = 0; i < n; ++i) guess[i] = fdp.ConsumeBool();
  }

  // Corruptions that the solver must reject with an InputError.
  const int corrupt = fdp.ConsumeIntegralInRange<int>(0, 15);
  const Index ci = fdp.ConsumeIntegralInRange<Index>(0, n - 1);
  const Index cj = fdp.ConsumeIntegralInRange<Index>(0, n - 1);
  bool corrupted = true;
  switch (corrupt) {
    case 0: {  // a finite extreme value keeps A symmetric: valid (maybe not SPD)
      const double x = nbm_fuzz::special(fdp);
      A(ci, cj) = x;
      if (std::isfinite(x)) A(cj, ci) = x;
      corrupted = !std::isfinite(x);
      break;
    }
    case 1:
      q(ci) = nbm_fuzz::special(fdp);
      corrupted = !std::isfinite(q(ci));
      break;
    case 2:
      if (ci != cj)
        A(ci, cj) += 1e-6 * std::max(std::abs(A(ci, cj)), A.cwiseAbs().maxCoeff());
      else
        corrupted = false;
      break;
    case 3:
      guess.assign(n + 1, true);
      break;
    case 4:
      q.conservativeResize(n + 1);
      q(n) = 1;
      break;
    case 5:
      A.conservativeResize(n, n + 1);
      A.col(n).setZero();
      break;
    default:
      corrupted = false;
  }
  // Finite extreme values are valid input (A stays symmetric, possibly not
  // positive definite in floating point: then cond2 is infinite below).
  const bool valid = !corrupted;
  const double cond = valid ? cond2(A) : 0.0;

  nbm_fuzz::on_fail() = [&] {
    std::fprintf(stderr, "n = %ld, cond2 = %g, corruption %d\nA =\n", (long)n, cond, corrupt);
    for (Index i = 0; i < A.rows(); ++i) {
      for (Index j = 0; j < A.cols(); ++j) std::fprintf(stderr, " %.17g", A(i, j));
      std::fputc('\n', stderr);
    }
    std::fputs("q =", stderr);
    for (Index i = 0; i < q.size(); ++i) std::fprintf(stderr, " %.17g", q(i));
    std::fputc('\n', stderr);
  };
  nbm::LcpResult r;
  bool solved = false;
  try {
    r = nbm::LcpSolver::solve(A, q, guess);
    solved = true;
  } catch (const nbm::InputError& e) {
    if (valid) fail("InputError on valid input (n = %ld, cond %g): %s", (long)n, cond, e.what());
  } catch (const nbm::NumericalError& e) {
    if (!valid) fail("NumericalError on corrupted input %d: %s", corrupt, e.what());
    // An extreme finite value (corruption 0, 1) may make the solution
    // overflow: a NumericalError is then the right answer.
    if (cond <= 1e8 && corrupt != 0 && corrupt != 1)
      fail("NumericalError on a well-conditioned SPD matrix (cond %g): %s", cond, e.what());
  } catch (const std::exception& e) {
    fail("unexpected exception %s: %s", typeid(e).name(), e.what());
  }
  if (!solved) return 0;
  if (!valid) fail("corrupted input %d accepted", corrupt);

  if (r.z.size() != n || r.w.size() != n || static_cast<Index>(r.active.size()) != n)
    fail("result sizes");
  if (r.pivots < 1) fail("pivots %d", r.pivots);
  for (Index i = 0; i < n; ++i) {
    if (!std::isfinite(r.z(i)) || !std::isfinite(r.w(i))) fail("non-finite result");
    if (r.z(i) < 0 || r.w(i) < 0) fail("negative z or w at %ld", (long)i);
    if (r.active[i] && r.z(i) != 0) fail("z_%ld = %g on the active set", (long)i, r.z(i));
    if (!r.active[i] && r.w(i) != 0) fail("w_%ld = %g on the free set", (long)i, r.w(i));
  }
  // The bound assumes no underflow or overflow: not checked after an extreme
  // value (DBL_MAX, denormals) was injected.
  if (corrupt == 0 || corrupt == 1) return 0;
  const double res = nbm::LcpSolver::residual(A, q, r.z);
  const double tol = 100 * std::pow(double(n), 2.5) * kEps * std::max(1.0, cond);
  if (!(res <= tol) && tol < 1)
    fail("residual %g > tolerance %g (n = %ld, cond %g, pivots %d)", res, tol, (long)n, cond,
         r.pivots);
  return 0;
}
