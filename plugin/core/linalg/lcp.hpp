// Exact solver for the linear complementarity problem of the nodal boundary
// relation (method.md §3):
//
//     find z >= 0 with w = q + A z >= 0 and z . w = 0,
//
// for a symmetric positive definite A (A = K_CC; non-symmetric P-matrices are
// rejected, since principal blocks are factored by Cholesky).
//
// The solution is unique; it is found by block principal pivoting
// (Judice & Pires 1994) safeguarded by Murty's single least-index pivoting,
// which terminates finitely on every P-matrix. Termination is decided by the
// signs of the exact subproblem solutions, never by a convergence tolerance:
// the returned active set is the one whose principal subproblem is feasible,
// and complementarity holds to round-off. The round-off tolerances of those
// sign checks scale with the data; rows whose right-hand side is larger than
// the others' by orders of magnitude (a contact node far from the obstacle)
// are judged apart so that they do not loosen the others' checks (lcp.cpp,
// solve_two_scale).
#pragma once

#include <vector>

#include "base/types.hpp"
#include "linalg/active_set.hpp"
#include "linalg/principal_block.hpp"

namespace nbm {

struct LcpResult {
  Vector z;                   ///< z >= 0 (the gaps, in the nodal boundary relation)
  Vector w;                   ///< w = q + A z >= 0 up to round-off (the reactions lambda)
  std::vector<bool> active;   ///< active[i]: z_i = 0 (contact closed)
  int pivots = 0;             ///< number of principal subproblems solved
};

/// Workspaces of the pivoting, kept by CachedLcpSolver between solves so
/// that a solve allocates nothing (internal).
struct LcpWorkspace {
  explicit LcpWorkspace(Index n = 0);
  std::vector<Index> free, infeasible, order;
  std::vector<bool> frozen;
  Vector rhs;
  LcpResult first;
};

class LcpSolver {
 public:
  /// Solves the LCP(q, A). `guess` (optional, size n) is a warm start for the
  /// active set {i : z_i = 0}. Throws InputError on wrong sizes, non-finite
  /// data or a non-symmetric A, NumericalError if a principal block it has to
  /// factor is not positive definite.
  static LcpResult solve(const Matrix& A, const Vector& q,
                         const std::vector<bool>& guess = {});

  /// max_i |min(z_i, w_i)| relative to the scale of (q, A z): a merit
  /// function that is zero exactly at the solution.
  static double residual(const Matrix& A, const Vector& q, const Vector& z);
};

/// The LCP of one matrix solved for a new q at every time step. Same pivoting
/// and result as LcpSolver::solve, but the Cholesky factors of the principal
/// blocks are kept per active set (the sets recur from step to step: a step
/// whose set is known costs two triangular solves and a product, not a
/// factorization), and so are the workspaces: once every set a solve meets
/// is known, the solve allocates nothing. One solve at a time. A sparse
/// matrix (K_CC) gets sparse factors and sparse products (principal_block.hpp).
class CachedLcpSolver {
 public:
  /// Checks A as LcpSolver::solve does (size, finite, symmetric), once.
  /// A sparse A (K_CC) is kept sparse unless it is dense enough
  /// (principal_block.hpp).
  explicit CachedLcpSolver(Matrix A);
  explicit CachedLcpSolver(const SparseMatrix& A);

  /// The solution for q (size n), warm-started from `guess` (size n); valid
  /// until the next call. Throws as LcpSolver::solve does.
  const LcpResult& solve(const Vector& q, const std::vector<bool>& guess) const;

  const PrincipalBlocks& matrix() const { return A_; }
  /// The cached factor of A[F, F], F the free rows {i : !active[i]} (in
  /// ascending order), made if the set is new: the solves' own, shared with
  /// a caller that factors the same blocks (the nodal boundary relation's
  /// open blocks). Valid until the next call or solve.
  const PrincipalBlockFactor& principal_factor(const std::vector<bool>& active,
                                               const std::vector<Index>& F) const;

 private:
  PrincipalBlocks A_;
  double a_max_;
  mutable ActiveSetCache<PrincipalBlockFactor> principal_blocks_;
  mutable LcpResult result_;
  mutable LcpWorkspace workspace_;
};

}  // namespace nbm
