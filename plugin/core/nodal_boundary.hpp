// The nodal boundary relation (method.md §3): contact-dof values slaved to
// the interior ones, u_C = A u_O + e, through the LCP with the P-matrix K_CC.
#pragma once

#include <Eigen/Cholesky>

#include "active_set.hpp"
#include "contact_problem.hpp"
#include "lcp.hpp"

namespace nbm {

/// Sign checks of the active set accept round-off of this relative size
/// (NodalBoundary::consistent); impenetrability is then exact to 1e-12 of
/// the displacement scale.
constexpr double kConsistencyTolerance = 1e-13;

class NodalBoundary {
 public:
  explicit NodalBoundary(const ContactProblem& problem);

  /// Solves the LCP at the interior part of u under the load F and overwrites
  /// u_C with its solution; returns the LCP result (z = gaps, w = reactions),
  /// valid until the next call.
  const LcpResult& enforce(Vector& u, const Vector& F, const ActiveSet& guess) const;

  /// Imposes G x = h for the given active set by changing x_C only:
  /// x_i = h_i on closed contacts, (K x)_i = h_i on open ones.
  /// With h = (g, F) this is u_C = A u_O + e.
  void project(Vector& x, const ActiveSet& active, const Vector& h) const;
  /// The same with h = 0: v_C = A v_O (and a_C = A a_O).
  void project(Vector& x, const ActiveSet& active) const;

  /// Right-hand side h of G u = h for the displacement: g on closed
  /// contacts, F_C on open ones.
  void displacement_constraint(const ActiveSet& active, const Vector& F, Vector& h) const;

  /// lambda = F_C - (K u)_C (method.md §2).
  Vector reactions(const Vector& u, const Vector& F) const;
  void reactions(const Vector& u, const Vector& F, Vector& lambda) const;
  /// gap = g - u_C.
  Vector gaps(const Vector& u) const;

  /// True if the active set is the LCP's at u: gap >= -tol on open contacts
  /// and lambda >= -tol on closed ones, with tolerances at round-off scale
  /// (violation() <= 1e-13).
  bool consistent(const Vector& u, const Vector& F, const ActiveSet& active) const;
  /// How far the active set is from the LCP's at u: the largest penetration
  /// of an open contact relative to the displacement scale (|u|, |g|) and the
  /// largest tensile reaction of a closed one relative to the force scale
  /// (|F_C|, |K_C| |u|); 0 if neither occurs.
  double violation(const Vector& u, const Vector& F, const ActiveSet& active) const;

 private:
  const ContactProblem& problem_;
  // Stiffness rows of the contact dofs, stored by rows: a product with a
  // dofs vector costs the rows' nonzeros, not a pass over all dofs.
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> K_C_;
  CachedLcpSolver lcp_;  // of K_CC
  mutable ActiveSetCache<Eigen::LLT<Matrix>> open_block_;  // K_In,In factors
  // Workspaces (one value per contact node), so that the methods called at
  // every step do not allocate: one call at a time.
  const Vector zero_;
  mutable Vector q_, work_, Kx_;
  mutable std::vector<Index> open_;
};

}  // namespace nbm
