// Cholesky factors of principal blocks A[F, F] of a symmetric positive
// definite matrix: the LCP's pivots (lcp.hpp, one per complementary basis
// tried) and the nodal boundary relation's open block K_In,In (method.md §3)
// factor one per new active set.
//
// When A is K_CC, it is sparse: a contact node couples only to its neighbours
// on the contact boundary (a band along a 2D edge, a grid on a 3D face). A
// dense factor of A[F, F] costs |F|^3 / 3 flops and 8 |F|^2 bytes per set,
// which made these factorizations most of a step that changes the active set
// with a thousand contact nodes (bench/why.md, "Many contact nodes"); a sparse
// one, in a fill-reducing (AMD) order, costs about its fill: O(|F|) along an
// edge. A dense A (beta dt^2 W_CC of the massless boundary) keeps a dense
// blocked Cholesky factor.
#pragma once

#include <optional>
#include <vector>

#include "base/types.hpp"
#include "linalg/dense_cholesky.hpp"

namespace nbm {

/// A matrix whose principal blocks are factored: sparse if at most
/// 1 / kSparseFraction of its entries are nonzero (then A[F, F] gets a sparse
/// factor and products with A cost its nonzeros), else dense. Only that one
/// form is kept (K_CC of 1e4 contact nodes on a face: 0.3 MB sparse, 1.1 GB
/// dense).
class PrincipalBlocks {
 public:
  /// A: symmetric (not checked here), in either storage.
  explicit PrincipalBlocks(Matrix A);
  explicit PrincipalBlocks(const SparseMatrix& A);

  bool sparse() const { return sparse_; }
  Index size() const { return sparse_ ? A_sparse_.rows() : A_.rows(); }
  /// max |A_ij| (0 for an empty matrix).
  double max_abs() const;
  /// y += A x, at the cost of A's nonzeros when it is sparse; no allocation.
  void add_product(const Vector& x, Vector& y) const;
  /// y += A[:, F] x_F, for an x that is zero outside F (the LCP's z off its
  /// free set): the cost of those columns only, so that a step with every
  /// contact open reads none of a dense A; no allocation.
  void add_columns_product(const std::vector<Index>& F, const Vector& x, Vector& y) const;

  static constexpr Index kSparseFraction = 8;

 private:
  friend class PrincipalBlockFactor;
  Matrix A_;               // unless sparse_
  SparseMatrix A_sparse_;  // when sparse_
  bool sparse_ = false;
};

/// The Cholesky factor of A[F, F] (F: ascending indices, possibly empty).
class PrincipalBlockFactor {
 public:
  PrincipalBlockFactor(const PrincipalBlocks& A, const std::vector<Index>& F);

  /// False if A[F, F] is not (numerically) positive definite.
  bool positive_definite() const { return positive_definite_; }
  /// x <- A[F, F]^-1 x (size |F|), for a positive definite block; no
  /// allocation.
  void solve_in_place(Eigen::Ref<Vector> x) const;
  /// Bytes held by the factor and its workspace (not the object itself).
  std::size_t bytes() const;

 private:
  bool positive_definite_ = true;
  // A[F, F] of a dense A (else L_ holds it, or F is empty).
  std::optional<DenseCholesky> dense_;
  // Of a sparse A: P A[F, F] P^T = L L^T.
  SparseMatrix L_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P_, P_inverse_;
  mutable Vector work_;
};

/// Bytes held by a principal block factor (ActiveSetCache's budget).
inline std::size_t factor_bytes(const PrincipalBlockFactor& f) { return sizeof(f) + f.bytes(); }

}  // namespace nbm
