#include "linalg/sparse_factorizer.hpp"

namespace nbm {

const char* name(SparseSolver solver) {
  switch (solver) {
    case SparseSolver::kCholmod: return "cholmod";
    case SparseSolver::kMumps: return "mumps";
  }
  return "?";
}

std::unique_ptr<CholeskyInverse> SparseFactorizer::factor(const SparseMatrix& X,
                                                          const std::string& what) const {
  if (solver_ == SparseSolver::kMumps) return make_mumps_inverse(X, what, {}, mpi_world());
  return make_cholesky_inverse(X, what);
}

std::unique_ptr<CholeskyInverse> SparseFactorizer::factor(const SparseMatrix& X,
                                                          const std::string& what,
                                                          const SparseMatrix& constraints) const {
  if (solver_ == SparseSolver::kMumps)
    return make_mumps_inverse(X, what, touched_rows(constraints), mpi_world());
  return make_cholesky_inverse(X, what, constraints);
}

}  // namespace nbm
