// A CholeskyInverse factored by MUMPS, on one process or on all the ranks of
// an MPI communicator (method.md §4, "The iteration matrix on MUMPS").
//
// The constrained solves of ConstrainedSolver need the two halves of a
// solve, y = L^-1 P x and x = P' L^-T y, and the columns Y = L^-1 P B of the
// constraint basis. MUMPS does not hand out its triangular factors, but it
// condenses a problem on a set S of variables: with X ordered as
//
//     X = [X_II  X_IS]      S_X = X_SS - X_SI X_II^-1 X_IS  (its Schur
//         [X_SI  X_SS],     complement, dense, returned on the host),
//
// X = P' L L' P with L = [L_I 0; L_SI L_S], L_S the dense Cholesky factor of
// S_X. Forward: MUMPS's reduction phase eliminates the interior of x and
// keeps it internally, returning r_S = x_S - X_SI X_II^-1 x_I; y_S =
// L_S^-1 r_S. Backward: x_S = L_S^-T y_S, and MUMPS's expansion phase
// solves the interior from what the reduction kept. When S holds every row
// the constraint basis touches, Y has rows on S only (Y_I = 0), so a
// constrained solve changes y on S only, and the interior the reduction kept
// is still the right one when backward runs.
//
// Hence the contract of this inverse: y (size n) carries L_S^-1 r_S at the
// positions of S, zeros elsewhere; backward_in_place continues the last
// forward_in_place (one solve at a time, as every inverse's workspaces
// already demand); forward(B) needs the rows of B inside S.
//
// Parallel runs: every rank calls every method with the same arguments (the
// whole core runs redundantly on each rank, so the small contact problems
// give the same answer everywhere). MUMPS reads the matrix and right-hand
// sides on the host (rank 0) and distributes the factorization over the
// ranks; the host's results are broadcast, so every rank holds them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/types.hpp"
#include "linalg/mpi_ranks.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

/// MUMPS's factor of the SPD matrix X (full storage, symmetric), condensed
/// on `schur_variables` (ascending, distinct; may be empty: then forward is
/// the identity and backward a whole solve, and forward(B) needs B = 0).
/// Throws NumericalError naming `what` if X is not positive definite, and
/// with MUMPS's error code if MUMPS fails.
std::unique_ptr<CholeskyInverse> make_mumps_inverse(const SparseMatrix& X, const std::string& what,
                                                    std::vector<Index> schur_variables,
                                                    MpiCommunicator comm);

/// What MUMPS's analysis of X (condensed on `schur_variables`, as
/// make_mumps_inverse does) expects of its factorization on the ranks of
/// `comm`: its own estimates, available at sizes whose factorization would
/// not fit (bench/mumps-scale.sh projects from them).
struct MumpsEstimate {
  double factor_entries;   ///< space for the factors in doubles, all ranks (INFOG(3))
  double flops;            ///< of the elimination, all ranks (RINFOG(1))
  double memory_max_mb;    ///< MUMPS's data on the rank that needs most, in core (INFOG(16))
  double memory_total_mb;  ///< the same summed over the ranks (INFOG(17))
};
/// The pivot order MUMPS factors in: CHOLMOD's fill-reducing order with the
/// Schur variables last (what make_mumps_inverse uses), or MUMPS's own
/// choice (with a Schur complement: minimum degree), for comparison.
enum class MumpsOrdering { kFillReducing, kMumpsOwn };
MumpsEstimate estimate_mumps_factorization(
    const SparseMatrix& X, const std::string& what, const std::vector<Index>& schur_variables,
    MpiCommunicator comm, MumpsOrdering ordering = MumpsOrdering::kFillReducing);

/// The rows in which `constraints` has entries (ascending): the Schur
/// variables a constrained solver with these constraints needs.
std::vector<Index> touched_rows(const SparseMatrix& constraints);

}  // namespace nbm
