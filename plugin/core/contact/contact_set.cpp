#include "contact/contact_set.hpp"

#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Tolerance on |n| = 1: normals computed by the .idp helpers are normalised
// in double precision, so anything further off is a user error.
constexpr double kUnitTolerance = 1e-10;

std::string node_str(Index k) { return "contact node " + std::to_string(k); }

// Householder reflection H (symmetric, orthogonal) with H e_1 = n, returned
// column-major in h (dim x dim). Its first column is n; the others span the
// tangent space.
void householder_basis(const double* n, int dim, double* h) {
  bool first_axis = n[0] == 1.0;
  for (int i = 1; i < dim; ++i) first_axis = first_axis && n[i] == 0.0;
  if (first_axis) {  // the user's axes themselves (ContactSet::in_user_axes)
    for (int j = 0; j < dim; ++j)
      for (int i = 0; i < dim; ++i) h[j * dim + i] = i == j ? 1.0 : 0.0;
    return;
  }
  // w = n - e_1, H = I - 2 w w^T / (w.w); when n is (close to) e_1, w.w
  // is small and H would be ill-defined: reflect with n + e_1 and flip signs.
  std::vector<double> w(n, n + dim);
  const double sign = n[0] > 0 ? 1.0 : -1.0;
  w[0] += sign;  // w = n + sign e_1, |w|^2 >= 1
  double ww = 0;
  for (double c : w) ww += c * c;
  // H' = I - 2 w w^T/ww maps e_1 to -sign n; scaling by -sign gives H e_1 = n
  // while keeping H orthogonal.
  for (int j = 0; j < dim; ++j)
    for (int i = 0; i < dim; ++i)
      h[j * dim + i] = -sign * ((i == j ? 1.0 : 0.0) - 2.0 * w[i] * w[j] / ww);
}

}  // namespace

ContactSet::ContactSet(Index n_dofs, std::vector<Index> dofs, std::vector<double> normals,
                       Vector gaps, const std::vector<Index>& fixed)
    : dofs_(std::move(dofs)), normals_(std::move(normals)), gaps_(std::move(gaps)) {
  const Index n_nodes = gaps_.size();
  if (n_nodes == 0) throw InputError("contact set is empty: expected at least one contact node");
  if (dofs_.size() % n_nodes != 0)
    throw InputError("contact dofs: " + std::to_string(dofs_.size()) +
                     " entries is not a multiple of the number of gaps (" +
                     std::to_string(n_nodes) + ")");
  dim_ = static_cast<int>(dofs_.size() / n_nodes);
  if (dim_ < 1 || dim_ > 3)
    throw InputError("contact dofs: " + std::to_string(dim_) +
                     " dofs per contact node, expected 1, 2 or 3");
  if (normals_.size() != dofs_.size())
    throw InputError("normals: size " + std::to_string(normals_.size()) + ", expected " +
                     std::to_string(dofs_.size()) + " (one component per contact dof)");

  std::vector<char> owner(n_dofs, 0);  // 1: contact dof, 2: fixed dof
  for (Index f : fixed) {
    if (f < 0 || f >= n_dofs)
      throw InputError("fixed: index " + std::to_string(f) + " outside [0, " +
                       std::to_string(n_dofs) + ")");
    owner[f] = 2;
  }
  for (Index k = 0; k < n_nodes; ++k) {
    for (int j = 0; j < dim_; ++j) {
      const Index d = dof(k, j);
      if (d < 0 || d >= n_dofs)
        throw InputError("contact dofs: index " + std::to_string(d) + " of " + node_str(k) +
                         " outside [0, " + std::to_string(n_dofs) + ")");
      if (owner[d] == 1)
        throw InputError("contact dofs: dof " + std::to_string(d) + " appears twice");
      if (owner[d] == 2)
        throw InputError("contact dofs: dof " + std::to_string(d) + " of " + node_str(k) +
                         " is also a fixed (Dirichlet) dof");
      owner[d] = 1;
    }
    double nn = 0;
    for (int j = 0; j < dim_; ++j) {
      const double c = normal(k, j);
      if (!std::isfinite(c))
        throw InputError("normals: non-finite component at " + node_str(k));
      nn += c * c;
    }
    if (std::abs(std::sqrt(nn) - 1.0) > kUnitTolerance)
      throw InputError("normals: " + node_str(k) + " has |n| = " + std::to_string(std::sqrt(nn)) +
                       ", expected a unit vector");
    if (!std::isfinite(gaps_(k)))
      throw InputError("gaps: non-finite gap at " + node_str(k));
  }
}

ContactSet ContactSet::in_user_axes(Index n_dofs, std::vector<Index> dofs, int dim,
                                    const std::vector<Index>& fixed) {
  if (dim < 1 || dim > 3 || dofs.size() % dim != 0)
    throw InputError("contact dofs: " + std::to_string(dofs.size()) + " entries with " +
                     std::to_string(dim) + " dofs per node, expected a multiple of 1, 2 or 3");
  const Index n_nodes = static_cast<Index>(dofs.size()) / dim;
  std::vector<double> normals(dofs.size(), 0.0);
  for (Index k = 0; k < n_nodes; ++k) normals[k * dim] = 1.0;
  return ContactSet(n_dofs, std::move(dofs), std::move(normals), Vector::Zero(n_nodes), fixed);
}

SparseMatrix ContactSet::rotation(Index n_dofs) const {
  std::vector<Triplet> t;
  std::vector<char> in_contact(n_dofs, 0);
  std::vector<double> h(dim_ * dim_);
  for (Index k = 0; k < size(); ++k) {
    householder_basis(&normals_[k * dim_], dim_, h.data());
    for (int i = 0; i < dim_; ++i) {
      in_contact[dof(k, i)] = 1;
      for (int j = 0; j < dim_; ++j)
        if (h[j * dim_ + i] != 0.0) t.emplace_back(dof(k, i), dof(k, j), h[j * dim_ + i]);
    }
  }
  for (Index d = 0; d < n_dofs; ++d)
    if (!in_contact[d]) t.emplace_back(d, d, 1.0);
  SparseMatrix T(n_dofs, n_dofs);
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

Vector ContactSet::normal_displacement(const Vector& u) const {
  Vector un = Vector::Zero(size());
  for (Index k = 0; k < size(); ++k)
    for (int j = 0; j < dim_; ++j) un(k) += normal(k, j) * u(dof(k, j));
  return un;
}

}  // namespace nbm
