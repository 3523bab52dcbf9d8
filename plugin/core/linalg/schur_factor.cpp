#include "linalg/schur_factor.hpp"

#include <stdexcept>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Every matrix factored here is positive definite if W is (a principal
// submatrix of W, its Schur complement in a larger one, or E^T T^-1 E): a
// failure means a singular constraint Schur complement.
DenseCholesky cholesky(Matrix&& A) {
  DenseCholesky factor(std::move(A));
  if (!factor.positive_definite())
    throw NumericalError("the constraint Schur complement of an active set is singular");
  return factor;
}

}  // namespace

SchurFactor::SchurFactor(const Matrix& W, std::vector<Index> columns)
    : columns_(std::move(columns)) {
  const Index n = static_cast<Index>(columns_.size());
  // Lower triangle only (what the factorization reads), column by column.
  Matrix S(n, n);
  for (Index b = 0; b < n; ++b)
    for (Index a = b; a < n; ++a) S(a, b) = W(columns_[a], columns_[b]);
  // Blocked Cholesky, at matrix-product speed (dense_cholesky.hpp).
  llt_ = cholesky(std::move(S));
}

SchurFactor::SchurFactor(const Matrix& W, std::vector<Index> columns,
                         std::shared_ptr<const SchurFactor> base)
    : columns_(std::move(columns)), base_(std::move(base)) {
  const auto& c0 = base_->columns_;
  const Index n = static_cast<Index>(columns_.size());
  for (Index k = 0; k < n; ++k)
    if (columns_[k] != c0[k]) changed_.push_back(k);
  const Index r = static_cast<Index>(changed_.size());
  // With r = 0 every block below is empty (and Eigen's triangular solves
  // would bind references into null storage): the caller uses the base.
  if (r == 0) throw std::logic_error("SchurFactor: bordered on a base with the same columns");
  // T = [S0 B; B' C] = L_T L_T', L_T = [L0 0; X' L22]: X = L0^-1 B,
  // L22 L22' = C - X' X.
  X_.resize(n, r);
  Matrix C(r, r);
  for (Index i = 0; i < r; ++i) {
    const Index ci = columns_[changed_[i]];
    for (Index k = 0; k < n; ++k) X_(k, i) = W(c0[k], ci);
    for (Index j = 0; j < r; ++j) C(j, i) = W(columns_[changed_[j]], ci);
  }
  const auto L0 = base_->llt_.matrixL();
  L0.solveInPlace(X_);
  C.selfadjointView<Eigen::Lower>().rankUpdate(X_.transpose(), -1.0);
  llt_ = cholesky(std::move(C));
  // V = L_T^-1 E with E the unit columns of the removed rows c0(D) of T.
  V_ = Matrix::Zero(n + r, r);
  for (Index i = 0; i < r; ++i) V_(changed_[i], i) = 1.0;
  L0.solveInPlace(V_.topRows(n));
  V_.bottomRows(r).noalias() = -X_.transpose() * V_.topRows(n);
  llt_.matrixL().solveInPlace(V_.bottomRows(r));
  capacitance_ = cholesky(Matrix(V_.transpose() * V_));
  w_.resize(n + r);
  t_.resize(r);
}

void SchurFactor::solve_in_place(Vector& x) const {
  if (fresh()) {
    llt_.solve_in_place(x);
    return;
  }
  const Index n = static_cast<Index>(columns_.size()), r = t_.size();
  const auto L0 = base_->llt_.matrixL();
  // Right-hand side of T: b at each node's position, its changed nodes' in
  // the border (0 at the removed rows c0(D)).
  auto top = w_.head(n);
  auto bottom = w_.tail(r);
  top = x;
  for (Index i = 0; i < r; ++i) {
    bottom(i) = x(changed_[i]);
    top(changed_[i]) = 0.0;
  }
  // w = L_T^-1 b
  L0.solveInPlace(top);
  bottom.noalias() -= X_.transpose() * top;
  llt_.matrixL().solveInPlace(bottom);
  // z = L_T^-T (w + V t) with t such that z vanishes at the removed rows.
  t_.noalias() = -V_.transpose() * w_;
  capacitance_.solve_in_place(t_);
  w_.noalias() += V_ * t_;
  llt_.matrixU().solveInPlace(bottom);
  top.noalias() -= X_ * bottom;
  base_->llt_.matrixU().solveInPlace(top);
  x = top;
  for (Index i = 0; i < r; ++i) x(changed_[i]) = bottom(i);
}

Index SchurFactor::changes(const std::vector<Index>& a, const std::vector<Index>& b) {
  Index count = 0;
  for (std::size_t k = 0; k < a.size(); ++k) count += a[k] != b[k];
  return count;
}

std::size_t SchurFactor::bytes() const {
  const auto doubles = static_cast<std::size_t>(X_.size() + V_.size() + w_.size() + t_.size());
  return sizeof(*this) + llt_.bytes() + capacitance_.bytes() + doubles * sizeof(double) +
         (columns_.size() + changed_.size()) * sizeof(Index);
}

}  // namespace nbm
