// Factors a problem's sparse SPD matrices (the iteration matrix of the
// implicit schemes, the mass at a start) with the library of its choice:
// CHOLMOD in this process, or MUMPS on every rank of MPI_COMM_WORLD (one
// rank in a plain run; mumps_inverse.hpp, method.md §4).
#pragma once

#include <memory>
#include <string>

#include "base/types.hpp"
#include "linalg/mumps_inverse.hpp"
#include "linalg/sparse_solver.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

class SparseFactorizer {
 public:
  explicit SparseFactorizer(SparseSolver solver = SparseSolver::kCholmod) : solver_(solver) {}

  SparseSolver solver() const { return solver_; }

  /// X^-1 for plain solves. Throws NumericalError naming `what` if X is not
  /// positive definite.
  std::unique_ptr<CholeskyInverse> factor(const SparseMatrix& X, const std::string& what) const;
  /// X^-1 for the constrained solves with the columns `constraints`
  /// (ConstrainedSolver): CHOLMOD orders for them, MUMPS condenses on the
  /// rows they touch.
  std::unique_ptr<CholeskyInverse> factor(const SparseMatrix& X, const std::string& what,
                                          const SparseMatrix& constraints) const;

 private:
  SparseSolver solver_;
};

}  // namespace nbm
