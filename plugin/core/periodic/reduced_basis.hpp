// A reduced basis for the interior unknowns of large models (method.md §6):
// u_O ~ V q with V = [Phi, Psi], Phi the lowest modes of the interior with
// the contact dofs clamped (K_OO Phi = M_OO Phi w^2) and Psi = -K_OO^-1 K_OC
// the static responses to unit contact displacements (Craig-Bampton's
// shapes). The contact dofs stay unknowns of their own, so the reduced model
// is again a contact problem (reduced_field.hpp): its nodal boundary
// relation is the full model's restricted to range(V), a massless boundary
// stays massless, and every static state of the full model is represented
// exactly (range(Psi) holds the interior response to any contact state).
#pragma once

#include "contact/contact_problem.hpp"
#include "contact/damping.hpp"
#include "periodic/exact_flow.hpp"
#include "periodic/harmonic_load.hpp"
#include "periodic/reduced_field.hpp"

namespace nbm {

class ReducedBasis {
 public:
  /// `modes` fixed-interface modes (>= 1) of `problem` under the load F
  /// (internal coordinates). Throws InputError if modes is out of range,
  /// NumericalError if K_OO is singular or the eigensolver does not converge.
  ReducedBasis(const ContactProblem& problem, const Vector& F, int modes);

  /// The reduced contact problem: interior unknowns q, contact dofs last.
  const ReducedField& field() const { return *field_; }
  Index size() const { return V_.cols(); }
  /// Largest retained fixed-interface circular frequency.
  double cutoff_frequency() const { return cutoff_; }

  /// q of an interior vector u_O (M_OO-orthogonal projection onto range(V)).
  Vector reduce(const Vector& u_interior) const;
  /// u_O = V q.
  Vector expand(const Vector& q) const { return V_ * q; }

  /// The reduced model as a contact problem of its own, for the time
  /// steppers (method.md §6, "Time integration on the reduced model"):
  /// coordinates y = (q, u_C), contact dofs last with their node's normal as
  /// their only component, the full model's gaps, no fixed dofs; a massless
  /// boundary stays massless.
  ContactProblem contact_problem() const;
  /// y = (q, x_C) of a full internal vector x (q: the M_OO-orthogonal
  /// projection of x_O), and x = T y = (V q, u_C) back; expand_state of
  /// reduce_state is the identity on range(T).
  Vector reduce_state(const Vector& x) const;
  Vector expand_state(const Vector& y) const;
  /// expand_state of every column (one pass over V for all of them).
  Matrix expand_states(const Matrix& Y) const;

  /// The reduced problem's coordinates (q, u_C) are T^T x of the full
  /// model's internal ones, T = [V 0; 0 I]: a load F becomes T^T F, a
  /// damping matrix T^T C T, the harmonics of a forced orbit likewise (the
  /// gap harmonics, per contact, stay); Rayleigh coefficients carry over.
  Vector reduce_load(const Vector& F) const;
  Damping reduce(const Damping& damping) const;
  HarmonicLoad reduce(const HarmonicLoad& load) const;

  /// Residual of the full model's reduced equations P^T (M x'' + K x - F)
  /// (method.md §4) at the reduced state (q, q''), relative to the size of
  /// its terms: zero for an exact solution of the full model, so the
  /// reduction error of a state on an orbit of the reduced model.
  double full_residual(const Vector& q, const Vector& a) const;
  /// The same for a forced orbit, P^T (M x'' + C x' + K x - F(t)) at the
  /// reduced state (q, q', q'') at time t of `flow` (a flow of field(), the
  /// reduction of `damping` and `load`, which are the full model's).
  double full_residual(const Vector& q, const Vector& v, const Vector& a, double t,
                       const ExactFlow& flow, const Damping& damping,
                       const HarmonicLoad& load) const;
  /// The same residual at full internal vectors (x, x', x'') under the load
  /// F with the contacts of `active` closed: P^T (M x'' + C x' + K x - F)
  /// with P the full model's nodal boundary relation on that set, relative
  /// to the size of its terms (the time integrator's reduction error,
  /// api/solver.hpp).
  double equation_residual(const Vector& x, const Vector& xv, const Vector& xa, const Vector& F,
                           const Damping& damping, const ActiveSet& active) const;

 private:
  const ContactProblem& problem_;
  Vector F_;
  std::vector<Index> interior_, contact_;
  Matrix V_;               // n_O x (m + n_c), M_OO-orthonormal columns
  Matrix VtM_;             // V^T M_OO: reduce() is a projection
  double cutoff_ = 0;
  Matrix M_, K_;           // T^T M T, T^T K T (symmetrized)
  std::unique_ptr<ReducedField> field_;
};

}  // namespace nbm
