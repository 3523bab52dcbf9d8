// Inverses of symmetric positive definite matrices, factored once and
// applied many times: the only place the core touches a sparse factorization.
#pragma once

#include <memory>

#include "types.hpp"

namespace nbm {

class SpdInverse {
 public:
  virtual ~SpdInverse() = default;
  /// Size of the matrix.
  virtual Index size() const = 0;
  /// x <- X^{-1} x, column by column.
  virtual void solve_in_place(Matrix& x) const = 0;
  virtual void solve_in_place(Vector& x) const = 0;
  /// The dense Gram matrix B^T X^{-1} B for a sparse B with few columns.
  virtual Matrix gram(const SparseMatrix& B) const = 0;
};

/// Sparse Cholesky (CHOLMOD, supernodal). Throws NumericalError naming `what`
/// if the matrix is not positive definite. Solves reuse workspaces of the
/// inverse (no heap allocation after the first solve of a given width), so
/// one inverse serves one thread at a time.
std::unique_ptr<SpdInverse> make_cholesky_inverse(const SparseMatrix& X, const std::string& what);

/// Inverse of a positive diagonal matrix (a lumped mass). Throws InputError
/// naming `what` if an entry is not positive.
std::unique_ptr<SpdInverse> make_diagonal_inverse(const Vector& d, const std::string& what);

}  // namespace nbm
