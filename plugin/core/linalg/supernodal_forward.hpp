// Forward substitutions with many sparse right-hand sides on a supernodal
// Cholesky factor: Y = L^-1 P B, and optionally W = Y^T Y, the setup of the
// constrained solves (method.md §4) and of the massless boundary's contact
// compliance.
//
// A column of Y is nonzero only on the supernodes its column of B reaches in
// the supernodal elimination tree (the paths from the supernodes of its
// nonzeros to the root). The supernodes are visited once, children first;
// each gets the dense block of the columns that reach it, assembled from its
// entries of B and its children's updates (multifrontal), solved with its
// diagonal block (BLAS-3 triangular solve) and updated below it (BLAS-3
// product) for its parent. The solved rows are Y's rows of the supernode, and
// the Gram matrix takes them as they come (gram.hpp). Before, each column of
// B was one sparse triangular solve on a simplicial copy of L (CHOLMOD's
// sparse right-hand sides, without BLAS): 60% of the setup of a 3D block
// with 2178 contact nodes, and a second copy of the factor in memory.
#pragma once

#include <cholmod.h>

#include "base/types.hpp"

namespace nbm {

/// For the supernodal LL' factor L of CHOLMOD (int indices): with Y,
/// *Y = L^-1 P B, exact zeros left out (so the pattern is the reach of B's
/// columns in the elimination tree); with gram, *gram = Y^T Y (dense,
/// symmetric to the last bit). Without Y, Y is never held whole: only the
/// blocks of the supernodes under way.
void supernodal_forward(const cholmod_factor& L, const SparseMatrix& B, SparseMatrix* Y,
                        Matrix* gram);

}  // namespace nbm
