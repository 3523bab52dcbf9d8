#include "contact/contact_problem.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "contact/mass_redistribution.hpp"

namespace nbm {
namespace {

// Sizes, finite entries and symmetry of A. Rows and columns of fixed dofs
// are ignored by the solver, so they are left out of the symmetry test and
// of its scale (whatever a front end leaves in them, e.g. a penalty).
void check_matrix(const SparseMatrix& A, Index n, const std::vector<char>& is_fixed,
                  const char* name) {
  const std::string id = name;
  if (A.rows() != A.cols())
    throw InputError(id + ": " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) +
                     " is not square");
  if (A.rows() != n)
    throw InputError(id + ": size " + std::to_string(A.rows()) + ", expected " +
                     std::to_string(n) + " (the size of the other matrix)");
  auto free_entry = [&](Index i, Index j) { return !is_fixed[i] && !is_fixed[j]; };
  double a_max = 0;
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InputError(id + ": non-finite entry at (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + ")");
      if (free_entry(it.row(), j)) a_max = std::max(a_max, std::abs(it.value()));
    }
  const SparseMatrix At = A.transpose();
  const SparseMatrix D = A - At;
  for (Index j = 0; j < D.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(D, j); it; ++it)
      if (free_entry(it.row(), j) && std::abs(it.value()) > kSymmetryTolerance * a_max)
        throw InputError(id + ": not symmetric at (" + std::to_string(it.row()) + ", " +
                         std::to_string(it.col()) + "); expected a symmetric matrix");
}

}  // namespace

ContactProblem::ContactProblem(const SparseMatrix& M, const SparseMatrix& K,
                               ContactSet contacts, std::vector<Index> fixed,
                               const Matrix* massless_positions)
    : n_dofs_(K.rows()), contacts_(std::move(contacts)), fixed_(std::move(fixed)) {
  std::sort(fixed_.begin(), fixed_.end());
  fixed_.erase(std::unique(fixed_.begin(), fixed_.end()), fixed_.end());
  std::vector<char> is_fixed(n_dofs_, 0);
  for (Index f : fixed_) {
    if (f < 0 || f >= n_dofs_)
      throw InputError("fixed: index " + std::to_string(f) + " outside [0, " +
                       std::to_string(n_dofs_) + ")");
    is_fixed[f] = 1;
  }
  check_matrix(K, n_dofs_, is_fixed, "K");
  check_matrix(M, n_dofs_, is_fixed, "M");

  // Internal numbering: free dofs in their original order.
  internal_.assign(n_dofs_, -1);
  std::vector<Index>& internal = internal_;
  Index n = 0;
  free_.reserve(n_dofs_ - fixed_.size());
  {
    std::size_t f = 0;
    for (Index d = 0; d < n_dofs_; ++d) {
      if (f < fixed_.size() && fixed_[f] == d) {
        ++f;
        continue;
      }
      internal[d] = n++;
      free_.push_back(d);
    }
  }
  SparseMatrix select(n, n_dofs_);
  {
    std::vector<Triplet> t;
    for (Index d = 0; d < n_dofs_; ++d)
      if (internal[d] >= 0) t.emplace_back(internal[d], d, 1.0);
    select.setFromTriplets(t.begin(), t.end());
  }
  user_lumped_mass_ = M * Vector::Ones(n_dofs_);
  const SparseMatrix T = contacts_.rotation(n_dofs_);
  to_internal_ = select * SparseMatrix(T.transpose());
  to_internal_.prune(0.0);
  {
    // One entry +-1 per row: the round trip user <-> internal only moves and
    // negates numbers, which is exact.
    std::vector<int> entries(to_internal_.rows(), 0);
    for (Index j = 0; j < to_internal_.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(to_internal_, j); it; ++it) {
        ++entries[it.row()];
        if (std::abs(it.value()) != 1.0) exact_round_trip_ = false;
      }
    for (int e : entries)
      if (e != 1) exact_round_trip_ = false;
  }
  M_ = to_internal(M);
  K_ = to_internal(K);

  const Index nc = contacts_.size();
  contact_.resize(nc);
  for (Index k = 0; k < nc; ++k) contact_[k] = internal[contacts_.dof(k, 0)];

  // K_CC from the contact columns of K, rows renumbered (-1: not a contact dof).
  std::vector<Index> node_of(static_cast<std::size_t>(n), -1);
  for (Index k = 0; k < nc; ++k) node_of[contact_[k]] = k;
  std::vector<Triplet> coupling;
  for (Index b = 0; b < nc; ++b)
    for (SparseMatrix::InnerIterator it(K_, contact_[b]); it; ++it)
      if (const Index a = node_of[it.row()]; a >= 0)
        coupling.emplace_back(static_cast<int>(a), static_cast<int>(b), it.value());
  K_CC_.resize(nc, nc);
  K_CC_.setFromTriplets(coupling.begin(), coupling.end());

  std::vector<Triplet> t;
  for (Index k = 0; k < nc; ++k) {
    for (SparseMatrix::InnerIterator it(K_, contact_[k]); it; ++it)
      t.emplace_back(it.row(), k, it.value());  // column c of K = row c (symmetry)
    t.emplace_back(contact_[k], nc + k, 1.0);
  }
  B_.resize(n, 2 * nc);
  B_.setFromTriplets(t.begin(), t.end());
  if (massless_positions) make_boundary_massless(redistributed_mass(*this, M, *massless_positions));
}

ContactProblem ContactProblem::with_massless_boundary(const SparseMatrix& M,
                                                     const SparseMatrix& K,
                                                     ContactSet contacts) {
  ContactProblem p(M, K, std::move(contacts), {});
  p.make_boundary_massless(p.M_);
  return p;
}

Vector ContactProblem::lumped_mass() const {
  for (Index k = 0; k < contacts_.size(); ++k) {
    const double m0 = user_lumped_mass_(contacts_.dof(k, 0));
    for (int j = 1; j < contacts_.dim(); ++j) {
      const double mj = user_lumped_mass_(contacts_.dof(k, j));
      if (std::abs(mj - m0) > kSymmetryTolerance * std::max(std::abs(m0), std::abs(mj)))
        throw InputError("M: the lumped masses of the components of contact node " +
                         std::to_string(k) + " differ (" + std::to_string(m0) + ", " +
                         std::to_string(mj) +
                         "); the explicit scheme needs one nodal mass per contact node");
    }
  }
  Vector m(size());
  for (Index i = 0; i < size(); ++i) m(i) = user_lumped_mass_(free_[i]);
  return m;
}

void ContactProblem::make_boundary_massless(SparseMatrix M) {
  if (M.rows() != size() || M.cols() != size())
    throw InputError("redistributed mass: size " + std::to_string(M.rows()) + ", expected " +
                     std::to_string(size()));
  std::vector<char> is_contact(size(), 0);
  for (Index c : contact_) is_contact[c] = 1;
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
      if ((is_contact[it.row()] || is_contact[j]) && it.value() != 0.0)
        throw InputError("redistributed mass: entry (" + std::to_string(it.row()) + ", " +
                         std::to_string(j) + ") couples a contact dof, expected M_CC = 0, M_CO = 0");
  M_ = std::move(M);
  massless_boundary_ = true;
}

SparseMatrix ContactProblem::to_internal(const SparseMatrix& A) const {
  // Symmetric to the last bit (the input is symmetric to kSymmetryTolerance):
  // Cholesky factors and the LCP rely on it.
  SparseMatrix B = to_internal_ * A * SparseMatrix(to_internal_.transpose());
  B = 0.5 * (B + SparseMatrix(B.transpose()));
  B.prune(0.0);
  return B;
}

Vector ContactProblem::to_internal(const Vector& x) const { return to_internal_ * x; }

Vector ContactProblem::to_user(const Vector& x) const { return to_internal_.transpose() * x; }

}  // namespace nbm
