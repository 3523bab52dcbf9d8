// The nodal boundary relation (method.md §3): contact-dof values slaved to
// the interior ones, u_C = A u_O + e, through the LCP with the P-matrix K_CC.
#pragma once

#include "contact/contact_problem.hpp"
#include "linalg/active_set.hpp"
#include "linalg/lcp.hpp"

namespace nbm {

/// Sign checks of the active set accept round-off of this relative size
/// (NodalBoundary::violation); impenetrability is then exact to 1e-12 of
/// the displacement scale.
constexpr double kConsistencyTolerance = 1e-13;

class NodalBoundary {
 public:
  explicit NodalBoundary(const ContactProblem& problem);

  /// Solves the LCP at the interior part of u under the load F against the
  /// obstacle at gaps g, and overwrites u_C with its solution; returns the
  /// LCP result (z = gaps, w = reactions), valid until the next call.
  /// Nodes whose gap exceeds 1e3 times the displacement scale D =
  /// max(|u|, |F_C,k| / K_kk) are solved against a nearer obstacle, so that
  /// their huge gaps do not cost the other nodes their digits (exact: the
  /// solution is the same while they stay open, which is checked).
  const LcpResult& enforce(Vector& u, const Vector& F, const Vector& g,
                           const ActiveSet& guess) const;

  /// Imposes G x = h for the given active set by changing x_C only:
  /// x_i = h_i on closed contacts, (K x)_i = h_i on open ones.
  /// With h = (g, F_C) this is u_C = A u_O + e; with the rates of g and F_C,
  /// v_C = A v_O + e' and a_C = A a_O + e'' (method.md §8).
  void project(Vector& x, const ActiveSet& active, const Vector& h) const;

  /// lambda = F_C - (K u)_C (method.md §2).
  Vector reactions(const Vector& u, const Vector& F) const;
  void reactions(const Vector& u, const Vector& F, Vector& lambda) const;
  /// gap = g - u_C.
  Vector gaps(const Vector& u, const Vector& g) const;

  /// How far the active set is from the LCP's at u (obstacle at gaps g): the
  /// largest penetration of an open contact relative to its own displacement
  /// scale (the body's |u| and the node's |g_k|: a far node's large gap does
  /// not loosen the others' check) and the largest tensile reaction of a
  /// closed one relative to the force scale (|F_C|, |K_C| |u|); 0 if neither
  /// occurs. The set is consistent when this is <= kConsistencyTolerance.
  double violation(const Vector& u, const Vector& F, const Vector& g,
                   const ActiveSet& active) const;

 private:
  const ContactProblem& problem_;
  // Stiffness rows of the contact dofs, stored by rows: a product with a
  // dofs vector costs the rows' nonzeros, not a pass over all dofs.
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> K_C_;
  // Of K_CC; its principal-block factors are also the open blocks K_In,In
  // of project() (the LCP's free rows are the open contacts).
  CachedLcpSolver lcp_;
  // Workspaces (one value per contact node), so that the methods called at
  // every step do not allocate: one call at a time.
  mutable Vector q_, work_, Kx_, shift_;
  Vector K_CC_diagonal_;  // > 0 (K_CC is positive definite): displacement scales
  mutable LcpResult result_;  // enforce()'s result when it shifted obstacles
  mutable std::vector<Index> open_;
};

}  // namespace nbm
