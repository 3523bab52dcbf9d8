// Dense Cholesky factors of the contact blocks (the Schur complements of the
// constrained solves, the LCP's dense principal blocks), computed in place:
// no copy of the matrix beside its factor (1.1 GB each at 1e4 contact
// nodes). Large ones by LAPACK's dpotrf, the LAPACK of the BLAS CHOLMOD
// loads (OpenBLAS, with its threads; scripts/install-deps.sh): on a
// 2000 x 2000 SPD matrix on this project's 2-core machine 36 ms, 1.3 times
// faster than Eigen's blocked LLT through the same BLAS; small ones by
// Eigen's, which does not pay for LAPACK's call (dense_cholesky.cpp).
#pragma once

#include <cstddef>

#include "base/types.hpp"

namespace nbm {

class DenseCholesky {
 public:
  DenseCholesky() = default;
  /// Factors A = L L^T, reading A's lower triangle, in A's storage.
  explicit DenseCholesky(Matrix&& A);

  /// False if A was not (numerically) positive definite.
  bool positive_definite() const { return positive_definite_; }
  Index size() const { return L_.rows(); }
  auto matrixL() const { return L_.triangularView<Eigen::Lower>(); }
  auto matrixU() const { return L_.transpose().triangularView<Eigen::Upper>(); }
  /// x <- A^-1 x (one or several columns); no allocation.
  template <class Rhs>
  void solve_in_place(Rhs&& x) const {
    matrixL().solveInPlace(x);
    matrixU().solveInPlace(x);
  }
  std::size_t bytes() const { return static_cast<std::size_t>(L_.size()) * sizeof(double); }

 private:
  Matrix L_;  // lower triangle: the factor; upper: what A held there
  bool positive_definite_ = false;
};

}  // namespace nbm
