// The discrete contact problem M u'' + K u = F + contact (method.md §2) in the
// solver's internal coordinates: Dirichlet dofs removed, contact nodes rotated
// so that each normal displacement is one dof.
#pragma once

#include <vector>

#include "base/types.hpp"
#include "contact/contact_set.hpp"
#include "linalg/sparse_factorizer.hpp"

namespace nbm {

class ContactProblem {
 public:
  /// M, K: symmetric, n x n (full storage). `fixed`: dofs held at zero; their
  /// rows and columns are ignored (whatever they hold, e.g. a penalty).
  /// With `massless_positions` (one row per user dof: its node's
  /// coordinates), the mass of the contact dofs is redistributed
  /// (mass_redistribution.hpp): M_CC = 0, M_CO = 0, the massless boundary of
  /// method.md §4. The problem does not change once built.
  /// Throws InputError naming M or K on wrong sizes, non-finite or
  /// non-symmetric entries (and as redistributed_mass does).
  ContactProblem(const SparseMatrix& M, const SparseMatrix& K, ContactSet contacts,
                 std::vector<Index> fixed, const Matrix* massless_positions = nullptr);

  /// A problem whose M already has M_CC = 0, M_CO = 0 (checked: InputError
  /// otherwise), flagged as the massless boundary: the reduced model of a
  /// massless boundary (periodic/reduced_basis.hpp), whose coordinates are
  /// not nodes and have no positions to redistribute by.
  static ContactProblem with_massless_boundary(const SparseMatrix& M, const SparseMatrix& K,
                                               ContactSet contacts);

  Index n_dofs() const { return n_dofs_; }        ///< size of the user's vectors
  /// Internal index of a user dof, -1 for a fixed dof.
  Index internal_index(Index user_dof) const { return internal_[user_dof]; }
  Index size() const { return M_.rows(); }         ///< internal unknowns
  Index n_contact() const { return contacts_.size(); }
  const ContactSet& contacts() const { return contacts_; }
  const std::vector<Index>& fixed() const { return fixed_; }

  const SparseMatrix& M() const { return M_; }
  const SparseMatrix& K() const { return K_; }
  const Vector& gaps() const { return contacts_.gaps(); }
  /// Internal index of the contact dof (normal displacement) of each node.
  const std::vector<Index>& contact_index() const { return contact_; }
  /// K_CC (sparse: a contact node couples to its neighbours on the contact
  /// boundary): the LCP matrix of the nodal boundary relation (§3).
  const SparseMatrix& K_CC() const { return K_CC_; }
  /// B = [K_{:,C}  E_C] (size x 2 n_contact): the rows of the constraint
  /// matrix G of §4 are columns of B (stiffness row for an open contact,
  /// unit row for a closed one).
  const SparseMatrix& constraint_basis() const { return B_; }

  /// Row-sum lumped mass in internal coordinates (explicit scheme). Lumping
  /// is done on the user's M, before the rotation of the contact nodes, so it
  /// is the usual nodal mass whatever the normals. Throws InputError if the
  /// components of a contact node carry different lumped masses (the rotated
  /// mass would not be diagonal).
  Vector lumped_mass() const;

  /// True for a problem built with the massless boundary: M_CC = 0, M_CO = 0.
  bool massless_boundary() const { return massless_boundary_; }

  /// Internal coordinates of a user vector (displacement, velocity or load).
  Vector to_internal(const Vector& x) const;
  /// Internal coordinates of a user matrix like M and K (e.g. a damping
  /// matrix, method.md §9): rows and columns of fixed dofs dropped, contact
  /// nodes rotated, symmetrized to the last bit.
  SparseMatrix to_internal(const SparseMatrix& A) const;
  /// User vector of internal coordinates; fixed dofs are zero.
  Vector to_user(const Vector& x) const;
  /// True if to_internal(to_user(x)) == x bit for bit for every finite x:
  /// every contact normal is a coordinate axis (or there is no rotation).
  /// Otherwise the rotation rounds, and a front end that hands out user
  /// vectors must round its state through them to restart exactly.
  bool exact_round_trip() const { return exact_round_trip_; }

  /// The library that factors the problem's sparse matrices (CHOLMOD unless
  /// set: the option `solver` of a model, before the problem is shared).
  const SparseFactorizer& factorizer() const { return factorizer_; }
  void set_factorizer(SparseFactorizer factorizer) { factorizer_ = factorizer; }

 private:
  /// Sets M (built by redistributed_mass()); throws InputError if its rows
  /// and columns of the contact dofs do not vanish.
  void make_boundary_massless(SparseMatrix M);

  Index n_dofs_;
  ContactSet contacts_;
  std::vector<Index> fixed_;
  SparseMatrix to_internal_;  // selection of free dofs times T^T
  std::vector<Index> free_;      // user dof of each internal unknown
  std::vector<Index> internal_;  // internal index of each user dof, -1 if fixed
  Vector user_lumped_mass_;   // row sums of the user's M
  SparseMatrix M_, K_;
  std::vector<Index> contact_;
  SparseMatrix K_CC_;
  SparseMatrix B_;
  bool massless_boundary_ = false;
  bool exact_round_trip_ = true;
  SparseFactorizer factorizer_;
};

}  // namespace nbm
