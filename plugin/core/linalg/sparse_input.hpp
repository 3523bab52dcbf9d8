// A user's matrix in coordinate form (CooMatrix, solver.hpp: what FreeFEM hands
// over) as a sparse matrix, checked. Shared by the Solver and the front ends
// of the periodic solvers.
#pragma once

#include "api/solver.hpp"
#include "base/types.hpp"

namespace nbm {

/// Throws InputError naming `name` on an empty matrix, inconsistent
/// coordinate arrays or an entry outside the matrix. A lower_half matrix is
/// completed by symmetry.
SparseMatrix to_sparse(const CooMatrix& A, const char* name);

}  // namespace nbm
