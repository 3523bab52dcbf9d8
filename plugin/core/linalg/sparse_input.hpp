// A user's matrix in coordinate form (CooMatrix, coo_matrix.hpp: what FreeFEM
// hands over) as a sparse matrix, checked. Shared by the Solver and the front ends
// of the periodic solvers.
#pragma once

#include "base/types.hpp"
#include "linalg/coo_matrix.hpp"

namespace nbm {

/// Throws InputError naming `name` on an empty matrix, inconsistent
/// coordinate arrays or an entry outside the matrix. A lower_half matrix is
/// completed by symmetry.
SparseMatrix to_sparse(const CooMatrix& A, const char* name);

}  // namespace nbm
