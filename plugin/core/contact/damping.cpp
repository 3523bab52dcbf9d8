#include "contact/damping.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

void check_coefficient(double x, const char* name, const char* unit) {
  if (!std::isfinite(x) || x < 0)
    throw InputError(std::string(name) + ": " + std::to_string(x) +
                     ", expected a finite Rayleigh coefficient >= 0 (" + unit + ")");
}

}  // namespace

void check_damping(const Damping& damping, Index n) {
  check_coefficient(damping.a_M, "damping a_M", "the mass-proportional one, 1/s");
  check_coefficient(damping.b_K, "damping b_K", "the stiffness-proportional one, s");
  if (!damping.has_matrix()) return;
  const SparseMatrix& C = damping.C_user;
  if (C.rows() != n || C.cols() != n)
    throw InputError("damping matrix: size " + std::to_string(C.rows()) + "x" +
                     std::to_string(C.cols()) + ", expected " + std::to_string(n) + "x" +
                     std::to_string(n) + " (the size of M and K)");
  double c_max = 0;
  for (Index j = 0; j < C.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C, j); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InputError("damping matrix: non-finite entry at (" + std::to_string(it.row()) +
                         ", " + std::to_string(j) + ")");
      c_max = std::max(c_max, std::abs(it.value()));
    }
  const SparseMatrix D = C - SparseMatrix(C.transpose());
  for (Index j = 0; j < D.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(D, j); it; ++it)
      if (std::abs(it.value()) > kSymmetryTolerance * c_max)
        throw InputError("damping matrix: not symmetric at (" + std::to_string(it.row()) + ", " +
                         std::to_string(j) + "); expected a symmetric matrix");
  for (Index j = 0; j < C.cols(); ++j)
    if (C.coeff(j, j) < 0)
      throw InputError("damping matrix: negative diagonal entry at (" + std::to_string(j) + ", " +
                       std::to_string(j) + "); expected a positive semidefinite matrix");
}

SparseMatrix damping_matrix(const Damping& damping, const SparseMatrix& M, const SparseMatrix& K) {
  if (damping.none()) return SparseMatrix();
  SparseMatrix C = damping.a_M * M + damping.b_K * K;
  if (damping.has_matrix()) C += damping.C_user;
  C.prune(0.0);
  return C;
}

}  // namespace nbm
