// Inverses of symmetric positive definite matrices, factored once and
// applied many times: the only place the core touches a sparse factorization.
#pragma once

#include <memory>

#include "base/types.hpp"
#include "linalg/gram.hpp"

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

/// X = P' L L' P (P a fill-reducing permutation): besides whole solves, the
/// two halves of one, so that a solve constrained by a few sparse rows costs
/// one substitution each way (ConstrainedSolver, method.md §4).
class CholeskyInverse : public SpdInverse {
 public:
  /// x <- L^{-1} P x.
  virtual void forward_in_place(Vector& x) const = 0;
  /// x <- P' L^{-T} x.
  virtual void backward_in_place(Vector& x) const = 0;
  /// Y = L^{-1} P B for a sparse B, sparse: a column of Y is nonzero only
  /// where the nonzeros of its column of B reach in the elimination tree
  /// (supernodal_forward.hpp). With `gram`, also *gram = Y^T Y =
  /// B^T X^{-1} B, formed as Y is.
  virtual SparseMatrix forward(const SparseMatrix& B, Matrix* gram) const = 0;
  SparseMatrix forward(const SparseMatrix& B) const { return forward(B, nullptr); }
  /// The entries forward(B) would have (with the zeros of the supernodal
  /// pattern), counted on the symbolic factor, and L's entries: what a
  /// product with Y costs next to a substitution.
  virtual double forward_entries(const SparseMatrix& B) const = 0;
  virtual double factor_entries() const = 0;
};

/// Sparse Cholesky (CHOLMOD, supernodal). Throws NumericalError naming `what`
/// if the matrix is not positive definite. Solves reuse workspaces of the
/// inverse (no heap allocation after the first solve of a given width), so
/// one inverse serves one thread at a time.
std::unique_ptr<CholeskyInverse> make_cholesky_inverse(const SparseMatrix& X,
                                                       const std::string& what);
/// The same, for solves constrained by the columns of `constraints` (B of
/// ConstrainedSolver, method.md §4): the fill-reducing ordering is the one of
/// CHOLMOD's choice and nested dissection whose constrained step costs less,
/// the two substitutions with L plus the products with Y = L^-1 P B (bench/why.md).
std::unique_ptr<CholeskyInverse> make_cholesky_inverse(const SparseMatrix& X,
                                                       const std::string& what,
                                                       const SparseMatrix& constraints);

/// CHOLMOD's fill-reducing ordering of the symmetric pattern of X (the best
/// of the orderings it tries, nested dissection among them): order[k] is the
/// k-th pivot. For MUMPS (mumps_inverse.cpp), whose own choice with a Schur
/// complement is the minimum degree alone.
std::vector<Index> fill_reducing_order(const SparseMatrix& X);

/// Inverse of a positive diagonal matrix D (a lumped mass).
class DiagonalInverse final : public SpdInverse {
 public:
  explicit DiagonalInverse(Vector inverse) : inverse_(std::move(inverse)) {}
  Index size() const override { return inverse_.size(); }
  void solve_in_place(Matrix& x) const override { x = inverse_.asDiagonal() * x; }
  void solve_in_place(Vector& x) const override { x = inverse_.cwiseProduct(x); }
  Matrix gram(const SparseMatrix& B) const override { return Matrix(sparse_gram(B)); }
  /// B^T D^{-1} B, sparse: a column of B couples only to the columns that
  /// share a row with it.
  SparseMatrix sparse_gram(const SparseMatrix& B) const;
  /// The diagonal of D^{-1}.
  const Vector& inverse() const { return inverse_; }

 private:
  Vector inverse_;
};

/// Throws InputError naming `what` if an entry of d is not positive.
std::unique_ptr<DiagonalInverse> make_diagonal_inverse(const Vector& d, const std::string& what);

}  // namespace nbm
