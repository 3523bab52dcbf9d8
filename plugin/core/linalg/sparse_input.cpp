#include "linalg/sparse_input.hpp"

#include <string>
#include <vector>

#include "base/errors.hpp"

namespace nbm {

SparseMatrix to_sparse(const CooMatrix& A, const char* name) {
  const std::string id = name;
  if (A.rows <= 0 || A.cols <= 0)
    throw InputError(id + ": empty matrix (" + std::to_string(A.rows) + "x" +
                     std::to_string(A.cols) + ")");
  if (A.i.size() != A.value.size() || A.j.size() != A.value.size())
    throw InputError(id + ": inconsistent coordinate arrays");
  std::vector<Triplet> t;
  t.reserve(A.value.size() * (A.lower_half ? 2 : 1));
  for (std::size_t k = 0; k < A.value.size(); ++k) {
    const long i = A.i[k], j = A.j[k];
    if (i < 0 || i >= A.rows || j < 0 || j >= A.cols)
      throw InputError(id + ": entry (" + std::to_string(i) + ", " + std::to_string(j) +
                       ") outside the matrix");
    t.emplace_back(i, j, A.value[k]);
    if (A.lower_half && i != j) t.emplace_back(j, i, A.value[k]);
  }
  SparseMatrix S(A.rows, A.cols);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

}  // namespace nbm
