// The libraries that can factor a model's sparse SPD matrices (Eigen-free:
// the facade's options name them).
#pragma once

namespace nbm {

enum class SparseSolver {
  kCholmod,  ///< supernodal Cholesky in this process (the default)
  kMumps,    ///< MUMPS, its factorization distributed over the MPI ranks
};
/// The name front ends and messages use: "cholmod", "mumps".
const char* name(SparseSolver solver);

}  // namespace nbm
