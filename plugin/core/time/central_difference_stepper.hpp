// Explicit central differences (Newmark beta = 0, gamma = 1/2) with lumped
// mass on the reduced NBM equations (method.md §5). The active set at t_{n+1}
// follows from the LCP at the new interior displacement, which is known
// before the acceleration: the scheme stays explicit.
//
// Damping (method.md §9): central differences take C at v_{n+1} =
// v~ + dt/2 a_{n+1}, (M + dt/2 C) a_{n+1} = F - K u_{n+1} - C v~ + G^T mu,
// second order and stable for the undamped critical step (gamma = 1/2). The
// scheme stays explicit only if M + dt/2 C is diagonal: mass-proportional
// damping a_M on the lumped mass, C = a_M M_lumped, is taken exactly (the
// system is M's, scaled by 1 + a_M dt/2). Stiffness-proportional or
// assembled damping would need a factorization of M + dt/2 C per active set
// (or a lagged, first-order velocity): they are refused; scheme "newmark"
// takes them.
#pragma once

#include "linalg/constrained_solver.hpp"
#include "time/nbm_stepper.hpp"

namespace nbm {

/// Estimate of the largest eigenvalue omega_max^2 of the pencil (K, diag(m)):
/// power iteration (Rayleigh quotient, a lower bound that converges to it),
/// capped by the Gershgorin bound (an upper bound).
double max_eigenvalue(const SparseMatrix& K, const Vector& m);

class CentralDifferenceStepper final : public NbmStepper {
 public:
  /// Throws InputError if a lumped mass is not positive or if dt exceeds the
  /// critical time step 2 / omega_max (the reduced system's omega_max is
  /// bounded by the full one's, so this is a safe bound), or if the damping
  /// has a stiffness part b_K or a matrix (header).
  CentralDifferenceStepper(const ContactProblem& problem, double dt, const Damping& damping = {});

  using Stepper::step;

  double critical_dt() const { return critical_dt_; }

 protected:
  const SparseMatrix& mass() const override { return lumped_; }
  void solve_acceleration(const ContactLoad& load) override;
  /// a for the current u_ and active set: (1 + a_M dt_c) M a = F - K u -
  /// a_M M v + G^T mu, G a = h'' (dt_c = 0 at the start, dt/2 in a step; v
  /// is read only with damping).
  void solve_acceleration(const ContactLoad& load, const Vector& v, double dt_c);
  StepReport advance_interior(const ContactLoad& next) override;

 private:
  SparseMatrix lumped_;
  ConstrainedSolver solver_;  // before critical_dt_: it validates the lumped mass
  double critical_dt_;
  double a_M_;
  Vector a_old_, v_tilde_, r_, h_accel_;  // workspaces of a step
};

}  // namespace nbm
