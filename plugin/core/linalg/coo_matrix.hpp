// A sparse matrix in coordinate form: what FreeFEM hands over, and what the
// front ends (api/solver.hpp, the periodic solvers' user_*.hpp) take.
// Plain C++, free of Eigen and FreeFEM like those front ends' headers;
// linalg/sparse_input.hpp turns it into a checked sparse matrix.
#pragma once

#include <vector>

namespace nbm {

/// A sparse matrix in coordinate form, as FreeFEM hands it over. With
/// `lower_half` only the lower triangle is stored (FreeFEM's sym=1).
struct CooMatrix {
  long rows = 0, cols = 0;
  std::vector<long> i, j;
  std::vector<double> value;
  bool lower_half = false;
};

}  // namespace nbm
