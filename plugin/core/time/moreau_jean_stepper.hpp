// Moreau-Jean time stepping with a Newton impact law: the classical peer of
// NBM (reference paper, introduction), on the same FE problem and sharing
// its factorization and complementarity solver. Contact dofs are ordinary
// unknowns here (not slaved to the interior).
//
// theta = 1/2 on the velocity (method of Jean 1999):
//   (M + dt^2/4 K) v+ = M v + dt (F - K u) - dt^2/4 K v - E_C p,
//   u+ = u + dt (v + v+)/2,
// the same matrix as average-acceleration Newmark (beta = 1/4). With damping
// C (method.md §9) the velocity at mid-step (v + v+)/2 damps it: the matrix
// gains dt/2 C and the right-hand side -dt/2 C v. For the
// contacts predicted closed, gap(u) - dt/2 gap_rate <= 0, the impulses p
// and the separation velocities w = -v_C solve the LCP of Newton's law
//   0 <= w+ + e w  _|_  p >= 0   (e: restitution coefficient in [0, 1]),
// w = g' - v_C the rate of the gap (the obstacle may move, method.md §8),
// with the matrix W_CC = E_C^T (M + dt^2/4 K)^-1 E_C formed once.
// Impenetrability holds at the velocity level only: positions may
// penetrate by O(dt v); contacts stick after impact for e = 0.
#pragma once

#include <memory>

#include "time/implicit_scheme.hpp"
#include "time/stepper.hpp"

namespace nbm {

class MoreauJeanStepper final : public Stepper {
 public:
  /// Throws InputError unless 0 <= restitution <= 1, NumericalError if
  /// M + dt^2/4 K is not positive definite.
  MoreauJeanStepper(const ContactProblem& problem, double dt, double restitution,
                    const Damping& damping = {});

  using Stepper::reactions;
  using Stepper::step;
  /// Average contact force over the last step, p/dt.
  void reactions(Vector& lambda) const override { lambda = impulse_ / dt_; }
  /// The last impulse p: restored with the state, so that the reactions of
  /// a restarted run are those of the uninterrupted one.
  Vector scheme_state() const override { return impulse_; }

 protected:
  const SparseMatrix& mass() const override { return problem_.M(); }
  /// The given state is taken as it is (no nodal boundary relation).
  void start(const ContactLoad& load) override;
  StepReport advance(const ContactLoad& next) override;
  /// Positions may penetrate by O(dt v): states are not checked for it.
  bool exact_impenetrability() const override { return false; }
  void restore_scheme_state(const Vector& state) override;

 private:
  /// Reported only (the scheme is first order in velocity): M a = F - K u - C v.
  void solve_acceleration(const Vector& F);

  double restitution_;
  ImplicitScheme iteration_;  // its matrix M + dt/2 C + dt^2/4 K (beta = 1/4)
  const CholeskyInverse& S_;
  Matrix W_CC_;
  Vector impulse_;
};

}  // namespace nbm
