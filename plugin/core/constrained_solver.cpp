#include "constrained_solver.hpp"

#include "errors.hpp"

namespace nbm {

ConstrainedSolver::ConstrainedSolver(std::shared_ptr<const SpdInverse> X, const SparseMatrix& B)
    : X_(std::move(X)),
      B_(B),
      n_c_(B.cols() / 2),
      W_(X_->gram(B)),
      zero_(Vector::Zero(n_c_)),
      mu_(n_c_),
      correction_(B.rows()) {}

ConstrainedSolver::ConstrainedSolver(std::shared_ptr<const CholeskyInverse> X,
                                     const SparseMatrix& B)
    : X_(std::move(X)),
      cholesky_(static_cast<const CholeskyInverse*>(X_.get())),
      B_(B),
      n_c_(B.cols() / 2),
      Y_(cholesky_->forward(B)),
      W_(inner_products(Y_)),
      zero_(Vector::Zero(n_c_)),
      mu_(n_c_) {}

const Eigen::LDLT<Matrix>& ConstrainedSolver::schur(const ActiveSet& active) const {
  return schur_.get(active, [&] {
    Matrix S(n_c_, n_c_);
    for (Index a = 0; a < n_c_; ++a)
      for (Index b = 0; b < n_c_; ++b) S(a, b) = W_(column(active, a), column(active, b));
    Eigen::LDLT<Matrix> ldlt(S);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all())
      throw NumericalError("the constraint Schur complement of an active set is singular");
    return ldlt;
  });
}

void ConstrainedSolver::solve(const ActiveSet& active, const Vector& r, Vector& x) const {
  solve(active, r, zero_, x);
}

void ConstrainedSolver::solve(const ActiveSet& active, const Vector& r, const Vector& h,
                              Vector& x) const {
  if (cholesky_ != nullptr) return solve_with_factor(active, r, h, x);
  const auto& S = schur(active);
  x = r;
  X_->solve_in_place(x);
  for (Index k = 0; k < n_c_; ++k) mu_(k) = h(k) - B_.col(column(active, k)).dot(x);
  mu_ = S.solve(mu_);
  correction_.setZero();
  for (Index k = 0; k < n_c_; ++k) correction_ += mu_(k) * B_.col(column(active, k));
  X_->solve_in_place(correction_);
  x += correction_;
}

void ConstrainedSolver::solve_with_factor(const ActiveSet& active, const Vector& r,
                                          const Vector& h, Vector& x) const {
  const auto& S = schur(active);
  x = r;
  cholesky_->forward_in_place(x);  // y
  for (Index k = 0; k < n_c_; ++k) mu_(k) = h(k) - Y_.col(column(active, k)).dot(x);
  mu_ = S.solve(mu_);
  for (Index k = 0; k < n_c_; ++k) x += mu_(k) * Y_.col(column(active, k));
  cholesky_->backward_in_place(x);
}

}  // namespace nbm
