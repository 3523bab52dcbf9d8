#include "linalg/mass_solve.hpp"

#include <cmath>

#include "base/errors.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {
namespace {

// Far above what a mass matrix needs (tens); a matrix that needs more is
// factored.
constexpr int kMaxIterations = 500;

}  // namespace

MassSolver::MassSolver(const SparseMatrix& M, std::string what, int factor_after)
    : M_(M), what_(std::move(what)), inverse_diagonal_(M.diagonal()), factor_after_(factor_after) {
  for (Index i = 0; i < inverse_diagonal_.size(); ++i)
    if (!(inverse_diagonal_(i) > 0))
      throw NumericalError(what_ + " is not positive definite (diagonal entry " +
                           std::to_string(i) + " is " + std::to_string(inverse_diagonal_(i)) +
                           ")");
  inverse_diagonal_ = inverse_diagonal_.cwiseInverse();
}

MassSolver::~MassSolver() = default;

void MassSolver::factor() const { factor_ = make_cholesky_inverse(M_, what_); }

void MassSolver::solve(const Vector& r, Vector& x) const {
  if (!factor_ && factor_after_ > 0 && ++solves_ >= factor_after_) factor();
  if (factor_) {
    x = r;
    factor_->solve_in_place(x);
    return;
  }
  const double target = kMassSolveTolerance * r.norm();
  x.setZero(r.size());
  if (target == 0) return;
  residual_ = r;
  z_ = inverse_diagonal_.cwiseProduct(residual_);
  p_ = z_;
  double rz = residual_.dot(z_);
  for (int k = 0; k < kMaxIterations; ++k) {
    Mp_.noalias() = M_ * p_;
    const double pMp = p_.dot(Mp_);
    if (!(pMp > 0)) break;  // not positive definite (or broken down): the factor decides
    const double alpha = rz / pMp;
    x += alpha * p_;
    residual_ -= alpha * Mp_;
    if (residual_.norm() <= target) {
      // The recursive residual drifts from the true one: confirm.
      residual_ = r;
      residual_.noalias() -= M_ * x;
      if (residual_.norm() <= target) return;
    }
    z_ = inverse_diagonal_.cwiseProduct(residual_);
    const double rz_next = residual_.dot(z_);
    p_ = z_ + (rz_next / rz) * p_;
    rz = rz_next;
  }
  factor();
  x = r;
  factor_->solve_in_place(x);
}

Vector solve_mass(const SparseMatrix& M, const Vector& r, const std::string& what) {
  Vector x;
  MassSolver(M, what).solve(r, x);
  return x;
}

}  // namespace nbm
