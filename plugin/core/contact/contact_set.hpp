// The contact boundary: contact nodes with their dofs, outward unit normals
// and initial gaps to the obstacle (method.md §2, sign conventions §7).
//
// A node has `dim` dofs (1 for scalar fields and 1D bars, 2 for plane
// vectors, 3 in space). Its dof tuple is rotated into (normal, tangential)
// coordinates by an orthogonal block whose first column is the normal n, so
// that the normal displacement u_n = n.u becomes an ordinary unknown: the
// contact dof of the node. Tangential components remain interior unknowns
// (frictionless contact).
#pragma once

#include <vector>

#include "base/types.hpp"

namespace nbm {

class ContactSet {
 public:
  /// dofs: node k owns dofs[k*dim .. k*dim+dim-1]; normals likewise; gaps[k] is
  /// the distance along n from the undeformed node to the obstacle.
  /// `fixed` lists Dirichlet dofs, which must not be contact dofs.
  /// Throws InputError naming the argument on any inconsistency.
  ContactSet(Index n_dofs, std::vector<Index> dofs, std::vector<double> normals,
             Vector gaps, const std::vector<Index>& fixed = {});

  /// Contact nodes kept in the user's axes (normal e_1, gap 0, rotation the
  /// identity): for a contact frame that follows the body
  /// (following_frame_stepper.hpp), whose normals live outside the set.
  static ContactSet in_user_axes(Index n_dofs, std::vector<Index> dofs, int dim,
                                 const std::vector<Index>& fixed = {});

  Index size() const { return gaps_.size(); }
  int dim() const { return dim_; }
  const Vector& gaps() const { return gaps_; }
  /// Global dof k*dim+j of node k (component j).
  Index dof(Index node, int j) const { return dofs_[node * dim_ + j]; }
  double normal(Index node, int j) const { return normals_[node * dim_ + j]; }

  /// Orthogonal change of basis T (n_dofs x n_dofs): u = T u_rot, where u_rot
  /// holds u_n of node k in slot dof(k, 0) and tangential components in the
  /// node's other slots; identity elsewhere.
  SparseMatrix rotation(Index n_dofs) const;

  /// Normal displacement n.u of every node for a displacement u (original dofs).
  Vector normal_displacement(const Vector& u) const;

 private:
  int dim_ = 1;
  std::vector<Index> dofs_;
  std::vector<double> normals_;
  Vector gaps_;
};

}  // namespace nbm
