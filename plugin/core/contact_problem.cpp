#include "contact_problem.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.hpp"

namespace nbm {
namespace {

// FreeFEM's default tgv is 1e30; any diagonal this large is a penalty.
constexpr double kTgvThreshold = 1e29;
// Assembly in double precision leaves K symmetric to a few ulps.
constexpr double kSymmetryTolerance = 1e-10;

void check_matrix(const SparseMatrix& A, Index n, const char* name) {
  const std::string id = name;
  if (A.rows() != A.cols())
    throw InputError(id + ": " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) +
                     " is not square");
  if (A.rows() != n)
    throw InputError(id + ": size " + std::to_string(A.rows()) + ", expected " +
                     std::to_string(n) + " (the size of the other matrix)");
  double a_max = 0;
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InputError(id + ": non-finite entry at (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + ")");
      a_max = std::max(a_max, std::abs(it.value()));
    }
  const SparseMatrix At = A.transpose();
  const SparseMatrix D = A - At;
  for (Index j = 0; j < D.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(D, j); it; ++it)
      if (std::abs(it.value()) > kSymmetryTolerance * a_max)
        throw InputError(id + ": not symmetric at (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + "); expected a symmetric matrix");
}

}  // namespace

std::vector<Index> detect_tgv_dofs(const SparseMatrix& M, const SparseMatrix& K) {
  std::vector<Index> fixed;
  const Index n = std::min(M.rows(), K.rows());
  for (Index i = 0; i < n; ++i)
    if (std::abs(K.coeff(i, i)) >= kTgvThreshold || std::abs(M.coeff(i, i)) >= kTgvThreshold)
      fixed.push_back(i);
  return fixed;
}

ContactProblem::ContactProblem(const SparseMatrix& M, const SparseMatrix& K,
                               ContactSet contacts, std::vector<Index> fixed)
    : n_dofs_(K.rows()), contacts_(std::move(contacts)), fixed_(std::move(fixed)) {
  check_matrix(K, n_dofs_, "K");
  check_matrix(M, n_dofs_, "M");
  std::sort(fixed_.begin(), fixed_.end());
  fixed_.erase(std::unique(fixed_.begin(), fixed_.end()), fixed_.end());

  // Internal numbering: free dofs in their original order.
  std::vector<Index> internal(n_dofs_, -1);
  Index n = 0;
  {
    std::size_t f = 0;
    for (Index d = 0; d < n_dofs_; ++d) {
      if (f < fixed_.size() && fixed_[f] == d) {
        ++f;
        continue;
      }
      internal[d] = n++;
    }
  }
  SparseMatrix select(n, n_dofs_);
  {
    std::vector<Triplet> t;
    for (Index d = 0; d < n_dofs_; ++d)
      if (internal[d] >= 0) t.emplace_back(internal[d], d, 1.0);
    select.setFromTriplets(t.begin(), t.end());
  }
  const SparseMatrix T = contacts_.rotation(n_dofs_);
  to_internal_ = select * SparseMatrix(T.transpose());
  const SparseMatrix back = to_internal_.transpose();
  M_ = to_internal_ * M * back;
  K_ = to_internal_ * K * back;
  M_.prune(0.0);
  K_.prune(0.0);

  const Index nc = contacts_.size();
  contact_.resize(nc);
  for (Index k = 0; k < nc; ++k) contact_[k] = internal[contacts_.dof(k, 0)];

  K_CC_.resize(nc, nc);
  for (Index a = 0; a < nc; ++a)
    for (Index b = 0; b < nc; ++b) K_CC_(a, b) = K_.coeff(contact_[a], contact_[b]);

  std::vector<Triplet> t;
  for (Index k = 0; k < nc; ++k) {
    for (SparseMatrix::InnerIterator it(K_, contact_[k]); it; ++it)
      t.emplace_back(it.row(), k, it.value());  // column c of K = row c (symmetry)
    t.emplace_back(contact_[k], nc + k, 1.0);
  }
  B_.resize(n, 2 * nc);
  B_.setFromTriplets(t.begin(), t.end());
}

Vector ContactProblem::to_internal(const Vector& x) const { return to_internal_ * x; }

Vector ContactProblem::to_user(const Vector& x) const { return to_internal_.transpose() * x; }

}  // namespace nbm
