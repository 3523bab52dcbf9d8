// Mass redistribution (Khenous, Laborde & Renard 2008; method.md §4): the
// mass of the contact dofs is moved onto nearby interior dofs so that
// M_CC = 0 and M_CO = 0. The reduced NBM field is then Lipschitz, the
// contact nodes carry no kinetic energy, and the semi-discrete energy is
// conserved through impacts.
//
// Construction: M' = Pi^T M Pi, where Pi replaces the normal displacement of
// every contact node (or every component of it, MasslessPart) by a weighted
// combination of interior dofs,
//     u_n(k) = sum_j n_kj u_kj  ~  sum_j n_kj sum_d w_{kj,d} u_d,
// d running over the interior dofs of the same component near dof kj (its
// neighbours in the graph of M, widened ring by ring until the weights are
// determined). The weights are the minimum-norm ones that reproduce affine
// fields exactly: sum_d w = 1 and sum_d w x_d = x_kj. Hence
//   - M' is symmetric positive semi-definite (a congruence of M), definite
//     on the interior dofs, and its contact rows and columns vanish;
//   - rigid translations are reproduced: the total mass and the momentum are
//     those of M, and affine reproduction keeps the centre of mass.
#pragma once

#include "base/types.hpp"
#include "contact/contact_problem.hpp"

namespace nbm {

/// Which displacements of a contact node lose their mass.
enum class MasslessPart {
  kNormal,  ///< the normal one, u_n (the contact dof): the massless boundary
  /// every component: a node whose normal may change (the contact frame
  /// following the body, following_frame_stepper.hpp) keeps no mass in any
  /// direction, so that M' does not depend on the normals. The problem's
  /// contact nodes must not be rotated (ContactProblem::exact_round_trip).
  kAllComponents,
};

/// M' in internal coordinates. M_user: the user's mass matrix (its graph
/// must not couple two components of a contact node, as vector mass
/// matrices rho u.w do not); positions: one row per user dof, the
/// coordinates of its node. Throws InputError on wrong sizes, non-finite
/// positions or a mass coupling components, NumericalError if the interior
/// neighbours of a contact dof do not determine affine weights.
SparseMatrix redistributed_mass(const ContactProblem& problem, const SparseMatrix& M_user,
                                const Matrix& positions,
                                MasslessPart part = MasslessPart::kNormal);

}  // namespace nbm
