// Factors of the constraint Schur complements S = W[c, c] of ConstrainedSolver
// (method.md §4): W is symmetric positive definite (2 n x 2 n), and the set of
// columns c picks, for each of the n contact nodes, one of its two columns of
// W (stiffness row if open, unit row if closed).
//
// A fresh factor is the Cholesky factor of S (n^3/3 flops). When the contact
// front sweeps the contact set, a new set differs from its base (a set chosen
// by ConstrainedSolver::schur) at r << n nodes; a factor bordered on the
// base's costs about 2 n^2 r flops (two triangular solves with r right-hand
// sides) instead: with the base columns c0 and the changed nodes D,
// T = W[c0 + c(D), c0 + c(D)] is factored by bordering the base factor (T is
// a principal submatrix of W: positive definite, no downdate), and S is T
// with the rows and columns of c0(D) removed, which a solve imposes by an
// r x r capacitance system (z = 0 at c0(D), their equations dropped). A
// solve costs one triangular solve each way with the base factor, as a fresh
// one, plus O(n r). Measured: bench/why.md, "Many contact nodes".
#pragma once

#include <memory>
#include <vector>

#include "base/types.hpp"
#include "linalg/dense_cholesky.hpp"

namespace nbm {

class SchurFactor {
 public:
  /// The Cholesky factor of W[columns, columns]. Throws NumericalError if it
  /// is not positive definite.
  SchurFactor(const Matrix& W, std::vector<Index> columns);
  /// The factor of W[columns, columns] bordered on `base` (a fresh factor of
  /// the same W whose columns differ at few nodes, and at one at least: for
  /// the base's own columns, use the base). Throws NumericalError if a
  /// bordered block is not positive definite, std::logic_error if no column
  /// differs.
  SchurFactor(const Matrix& W, std::vector<Index> columns,
              std::shared_ptr<const SchurFactor> base);

  /// x <- S^{-1} x (size n); no allocation.
  void solve_in_place(Vector& x) const;

  bool fresh() const { return base_ == nullptr; }
  const std::vector<Index>& columns() const { return columns_; }
  /// Nodes whose column differs between the two sets.
  static Index changes(const std::vector<Index>& a, const std::vector<Index>& b);
  /// Bytes held (a bordered factor: its own arrays, not its base's).
  std::size_t bytes() const;

 private:
  std::vector<Index> columns_;
  DenseCholesky llt_;                       // fresh: of S; bordered: of T's new block
  std::shared_ptr<const SchurFactor> base_;  // bordered only
  std::vector<Index> changed_;              // D, the nodes whose column differs from base's
  Matrix X_;                                // L0^-1 W[c0, c(D)]  (n x r)
  Matrix V_;                                // L_T^-1 E_{c0(D)}   ((n + r) x r)
  DenseCholesky capacitance_;               // of V^T V = E^T T^-1 E (bordered)
  mutable Vector w_, t_;                    // workspaces of a solve
};

}  // namespace nbm
