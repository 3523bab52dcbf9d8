#include "contact/mass_redistribution.hpp"

#include <string>
#include <vector>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Rings of graph neighbours tried before giving up on affine weights.
constexpr int kMaxRings = 4;
// Reciprocal condition of the (pdim+1)^2 moment matrix below which the
// neighbour positions are taken as affinely dependent.
constexpr double kMinRcond = 1e-10;
// The dofs of one contact node must have positions equal to this fraction of
// the body's extent.
constexpr double kSamePointTolerance = 1e-10;

// Minimum-norm w with V w = b, V = [1; x_d] (columns: candidate dofs).
// Returns false if the candidates do not span the affine hull.
bool affine_weights(const Matrix& X, const Vector& x0, Vector& w) {
  const Index pdim = x0.size(), m = X.cols();
  Matrix V(pdim + 1, m);
  V.row(0).setOnes();
  V.bottomRows(pdim) = X;
  Vector b(pdim + 1);
  b << 1.0, x0;
  // Centre on x0 to keep the moment matrix well scaled.
  for (Index i = 0; i < pdim; ++i) V.row(i + 1).array() -= x0(i);
  b.tail(pdim).setZero();
  const Matrix G = V * V.transpose();
  const Eigen::LDLT<Matrix> ldlt(G);
  const Vector d = ldlt.vectorD();
  if (d.minCoeff() <= kMinRcond * d.maxCoeff()) return false;
  w = V.transpose() * ldlt.solve(b);
  return true;
}

}  // namespace

SparseMatrix redistributed_mass(const ContactProblem& problem, const SparseMatrix& M_user,
                                const Matrix& positions, MasslessPart part) {
  const bool all_components = part == MasslessPart::kAllComponents;
  if (all_components && !problem.exact_round_trip())
    throw InputError("mass redistribution of every component of the contact nodes needs "
                     "contact nodes in the user's axes (no rotation)");
  const Index n_user = problem.n_dofs();
  if (M_user.rows() != n_user || M_user.cols() != n_user)
    throw InputError("M: size " + std::to_string(M_user.rows()) + ", expected " +
                     std::to_string(n_user));
  if (positions.rows() != n_user || positions.cols() < 1 || positions.cols() > 3)
    throw InputError("positions: " + std::to_string(positions.size()) +
                     " values, expected 1, 2 or 3 coordinates per dof (" +
                     std::to_string(n_user) + " dofs)");
  if (!positions.allFinite()) throw InputError("positions: non-finite coordinates");

  const ContactSet& contacts = problem.contacts();
  // The dofs of a contact node are the components of one point: nothing else
  // tells a third component taken from another node (d = 3 dofs per node on
  // a 2D problem) from a node's own. Equal to round-off of the body's extent
  // (different nodes of a mesh are apart by a mesh size).
  {
    const double extent =
        (positions.colwise().maxCoeff() - positions.colwise().minCoeff()).maxCoeff();
    const double tol = kSamePointTolerance * extent;
    for (Index k = 0; k < contacts.size(); ++k)
      for (int j = 1; j < contacts.dim(); ++j) {
        const Index d0 = contacts.dof(k, 0), dj = contacts.dof(k, j);
        const double distance = (positions.row(dj) - positions.row(d0)).cwiseAbs().maxCoeff();
        if (distance > tol)
          throw InputError("contact dofs: dofs " + std::to_string(d0) + " and " +
                           std::to_string(dj) + " of contact node " + std::to_string(k) +
                           " are at different positions (" + std::to_string(distance) +
                           " apart, by positions); expected the " +
                           std::to_string(contacts.dim()) +
                           " components of one node, at one point");
      }
  }
  std::vector<char> excluded(n_user, 0);  // contact-node and fixed dofs
  for (Index k = 0; k < contacts.size(); ++k)
    for (int j = 0; j < contacts.dim(); ++j) excluded[contacts.dof(k, j)] = 1;
  for (Index d = 0; d < n_user; ++d)
    if (problem.internal_index(d) < 0) excluded[d] = 1;

  // Rows of Pi: identity except the contact dofs' rows (built below).
  const Index n = problem.size();
  std::vector<char> is_contact(n, 0);
  for (Index k = 0; k < contacts.size(); ++k)
    for (int j = 0; j < (all_components ? contacts.dim() : 1); ++j)
      is_contact[all_components ? problem.internal_index(contacts.dof(k, j))
                                : problem.contact_index()[k]] = 1;
  std::vector<Triplet> pi;
  for (Index i = 0; i < n; ++i)
    if (!is_contact[i]) pi.emplace_back(i, i, 1.0);

  std::vector<int> ring(n_user, -1);
  for (Index k = 0; k < contacts.size(); ++k) {
    for (int a = 1; a < contacts.dim(); ++a)
      if (M_user.coeff(contacts.dof(k, 0), contacts.dof(k, a)) != 0.0)
        throw InputError("M: couples the components of contact node " + std::to_string(k) +
                         "; mass redistribution needs a mass matrix without such coupling");
    for (int j = 0; j < contacts.dim(); ++j) {
      const Index d0 = contacts.dof(k, j);
      // Breadth-first rings of the graph of M around d0 (same component).
      std::vector<Index> frontier{d0}, visited{d0}, candidates;
      ring[d0] = 0;
      Vector w;
      bool found = false;
      for (int r = 1; r <= kMaxRings && !found; ++r) {
        std::vector<Index> next;
        for (Index d : frontier)
          for (SparseMatrix::InnerIterator it(M_user, d); it; ++it)
            if (ring[it.row()] < 0 && it.value() != 0.0) {
              ring[it.row()] = r;
              visited.push_back(it.row());
              next.push_back(it.row());
              if (!excluded[it.row()]) candidates.push_back(it.row());
            }
        frontier = next;
        if (candidates.empty()) continue;
        Matrix X(positions.cols(), candidates.size());
        for (std::size_t c = 0; c < candidates.size(); ++c)
          X.col(c) = positions.row(candidates[c]).transpose();
        found = affine_weights(X, positions.row(d0).transpose(), w);
      }
      for (Index d : visited) ring[d] = -1;
      if (!found)
        throw NumericalError("mass redistribution: the interior dofs near contact node " +
                             std::to_string(k) +
                             " do not determine affine weights (too few or aligned nodes)");
      // Row of the replaced displacement: u_kj itself, or u_n(k) which sums
      // the components' rows weighted by the normal.
      const Index row = all_components ? problem.internal_index(d0) : problem.contact_index()[k];
      const double weight = all_components ? 1.0 : contacts.normal(k, j);
      for (std::size_t c = 0; c < candidates.size(); ++c)
        pi.emplace_back(row, problem.internal_index(candidates[c]), weight * w(c));
    }
  }
  SparseMatrix Pi(n, n);
  Pi.setFromTriplets(pi.begin(), pi.end());  // sums the components' contributions
  SparseMatrix Mr = SparseMatrix(Pi.transpose()) * problem.M() * Pi;
  Mr = 0.5 * (Mr + SparseMatrix(Mr.transpose()));
  Mr.prune(0.0);
  return Mr;
}

}  // namespace nbm
