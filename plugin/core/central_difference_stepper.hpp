// Explicit central differences (Newmark beta = 0, gamma = 1/2) with lumped
// mass on the reduced NBM equations (method.md §5). The active set at t_{n+1}
// follows from the LCP at the new interior displacement, which is known
// before the acceleration: the scheme stays explicit.
#pragma once

#include "constrained_solver.hpp"
#include "nbm_stepper.hpp"

namespace nbm {

/// Estimate of the largest eigenvalue omega_max^2 of the pencil (K, diag(m)):
/// power iteration (Rayleigh quotient, a lower bound that converges to it),
/// capped by the Gershgorin bound (an upper bound).
double max_eigenvalue(const SparseMatrix& K, const Vector& m);

class CentralDifferenceStepper final : public NbmStepper {
 public:
  /// Throws InputError if a lumped mass is not positive or if dt exceeds the
  /// critical time step 2 / omega_max (the reduced system's omega_max is
  /// bounded by the full one's, so this is a safe bound).
  CentralDifferenceStepper(const ContactProblem& problem, double dt);

  using Stepper::step;

  double critical_dt() const { return critical_dt_; }

 protected:
  const SparseMatrix& mass() const override { return lumped_; }
  void solve_acceleration(const ContactLoad& load) override;
  StepReport advance_interior(const ContactLoad& next) override;

 private:
  SparseMatrix lumped_;
  ConstrainedSolver solver_;  // before critical_dt_: it validates the lumped mass
  double critical_dt_;
  Vector a_old_, r_, h_accel_;  // workspaces of a step
};

}  // namespace nbm
