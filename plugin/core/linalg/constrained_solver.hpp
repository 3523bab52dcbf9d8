// Solves the constrained systems of the reduced equations (method.md §4)
//
//     X x = r + G^T mu,   G x = h,
//
// for any active set, with X (M + beta dt^2 K, or a mass matrix) factored once.
// The rows of G are columns of B = [K_{:,C}  E_C]; with W = B^T X^{-1} B
// computed once, the Schur complement G X^{-1} G^T of an active set is a
// principal submatrix of W: an active-set change costs a small dense
// factorization (cached per set), or less when the set differs from the last
// factored one at few nodes (schur_factor.hpp), never a new sparse one.
//
// With a Cholesky factor X = P' L L' P, Y = L^{-1} P B (sparse) is kept:
// G X^{-1} r = Y_G^T y with y = L^{-1} P r, and x = P' L^{-T} (y + Y_G mu),
// so a solve is one forward and one backward substitution, as an
// unconstrained one. With a diagonal X (a lumped mass), x is X^{-1} r
// corrected by X^{-1} G^T mu, and W is sparse (a contact node couples only to
// the contact nodes its neighbours touch): its principal blocks get sparse
// factors (principal_block.hpp), not dense ones.
#pragma once

#include <memory>
#include <optional>

#include "base/types.hpp"
#include "linalg/active_set.hpp"
#include "linalg/principal_block.hpp"
#include "linalg/schur_factor.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

class ConstrainedSolver {
 public:
  /// X may be shared with others (the Newmark iteration matrix is).
  ConstrainedSolver(std::shared_ptr<const CholeskyInverse> X, const SparseMatrix& B);
  ConstrainedSolver(std::unique_ptr<DiagonalInverse> X, const SparseMatrix& B);
  ConstrainedSolver(std::unique_ptr<CholeskyInverse> X, const SparseMatrix& B)
      : ConstrainedSolver(std::shared_ptr<const CholeskyInverse>(std::move(X)), B) {}

  /// x solves X x = r + G^T mu, G x = h (h: one value per contact node).
  /// Once x has its size and the Schur complement of the set is cached, a
  /// solve allocates nothing (workspaces below: one solve at a time).
  void solve(const ActiveSet& active, const Vector& r, const Vector& h, Vector& x) const;
  /// The same with h = 0 (accelerations, velocities).
  void solve(const ActiveSet& active, const Vector& r, Vector& x) const;

  const SpdInverse& inverse() const { return *X_; }

 private:
  // Column of B that is row k of G: the stiffness row if contact k is open,
  // the unit row if it is closed.
  Index column(const ActiveSet& active, Index k) const { return active[k] ? n_c_ + k : k; }

  /// The factor of the Schur complement of a set: cached, else bordered on
  /// the factor of its base (a set that depends on the set alone) if they
  /// differ at few nodes (schur_factor.hpp), else fresh.
  const SchurFactor& schur(const ActiveSet& active) const;
  void solve_with_factor(const ActiveSet& active, const Vector& r, const Vector& h,
                         Vector& x) const;
  void solve_with_diagonal(const ActiveSet& active, const Vector& r, const Vector& h,
                           Vector& x) const;

  std::shared_ptr<const SpdInverse> X_;
  const CholeskyInverse* cholesky_ = nullptr;  // X_, when it is one
  const DiagonalInverse* diagonal_ = nullptr;  // X_, when it is one
  const SparseMatrix& B_;
  Index n_c_;
  // With cholesky_: W = B^T X^-1 B (before Y_: the forward substitutions form
  // both), Y = L^{-1} P B; and the factors of W[c, c] (memory: the cache's
  // byte budget plus the base; bordered factors hold 2 n_c r doubles each, a
  // fresh one n_c^2).
  Matrix W_;
  SparseMatrix Y_;
  mutable ActiveSetCache<std::shared_ptr<const SchurFactor>> schur_;
  mutable std::shared_ptr<const SchurFactor> base_;
  // With diagonal_: W (sparse) and the factors of W[F, F], F the set's
  // columns in ascending order (open nodes' stiffness columns first).
  std::optional<PrincipalBlocks> sparse_W_;
  mutable ActiveSetCache<PrincipalBlockFactor> blocks_;
  mutable std::vector<Index> F_;
  const Vector zero_;  // h = 0
  mutable Vector mu_;
};

/// x solves X x = r + G^T mu, G x = h for one active set, with an X used for
/// this one solve (the mass matrix at a start): only the set's n_c columns of
/// Y and their n_c x n_c Schur complement are formed, not the 2 n_c columns
/// and the (2 n_c)^2 matrix W that a ConstrainedSolver keeps for every set.
void solve_constrained_once(const CholeskyInverse& X, const SparseMatrix& B,
                            const ActiveSet& active, const Vector& r, const Vector& h,
                            Vector& x);

}  // namespace nbm
