#include "mass_solve.hpp"

#include <cmath>

#include "errors.hpp"
#include "spd_inverse.hpp"

namespace nbm {
namespace {

// Far above what a mass matrix needs (tens); a matrix that needs more is
// factored.
constexpr int kMaxIterations = 500;

}  // namespace

Vector solve_mass(const SparseMatrix& M, const Vector& r, const std::string& what) {
  const Vector diagonal = M.diagonal();
  for (Index i = 0; i < diagonal.size(); ++i)
    if (!(diagonal(i) > 0))
      throw NumericalError(what + " is not positive definite (diagonal entry " +
                           std::to_string(i) + " is " + std::to_string(diagonal(i)) + ")");
  const Vector inverse = diagonal.cwiseInverse();
  const double target = kMassSolveTolerance * r.norm();
  Vector x = Vector::Zero(r.size());
  if (target == 0) return x;
  Vector residual = r, z = inverse.cwiseProduct(residual), p = z, Mp(r.size());
  double rz = residual.dot(z);
  for (int k = 0; k < kMaxIterations; ++k) {
    Mp.noalias() = M * p;
    const double pMp = p.dot(Mp);
    if (!(pMp > 0)) break;  // not positive definite (or broken down): the factor decides
    const double alpha = rz / pMp;
    x += alpha * p;
    residual -= alpha * Mp;
    if (residual.norm() <= target) {
      // The recursive residual drifts from the true one: confirm.
      residual.noalias() = r - M * x;
      if (residual.norm() <= target) return x;
    }
    z = inverse.cwiseProduct(residual);
    const double rz_next = residual.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  x = r;
  make_cholesky_inverse(M, what)->solve_in_place(x);
  return x;
}

}  // namespace nbm
