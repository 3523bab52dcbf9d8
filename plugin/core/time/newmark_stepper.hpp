// The paper's NBM contact step (active set consistent at t_{n+1}; method.md
// §5, §5.2) composed with an implicit time scheme (implicit_scheme.hpp:
// Newmark, generalized-alpha; written below with Newmark's beta, gamma,
// which stand for the scheme's effective beta', gamma'). With damping C
// (method.md §9) the constrained form (4.3) gains C v: the iteration matrix is
// M + gamma dt C + beta dt^2 K and the right-hand side -C v~; the contact
// dofs' damping forces reach the interior through P^T, like their inertia.
#pragma once

#include <memory>

#include "linalg/constrained_solver.hpp"
#include "linalg/lcp.hpp"
#include "time/nbm_stepper.hpp"
#include "time/implicit_scheme.hpp"

namespace nbm {

struct NewmarkParameters {
  /// Newmark's beta, gamma (average acceleration by default: energy
  /// conserving) or generalized-alpha (generalized_alpha.hpp).
  SchemeParameters scheme;
  int max_active_set_iterations = 25;
  /// What the energy-stable step (method.md §5.3) bounds; kNone: the
  /// paper's step alone. Taken with average acceleration and no damping.
  EnergyControl energy = EnergyControl::kNone;
};

class NewmarkStepper final : public NbmStepper {
 public:
  /// Factors S = M + gamma' dt C + beta' dt^2 K once (implicit_scheme.hpp).
  /// Throws InputError on bad damping, NumericalError if S is not positive
  /// definite.
  NewmarkStepper(const ContactProblem& problem, double dt, NewmarkParameters parameters = {},
                 const Damping& damping = {});

  using Stepper::step;

  const NewmarkParameters& parameters() const { return parameters_; }

 protected:
  const SparseMatrix& mass() const override { return problem_.M(); }
  void solve_acceleration(const ContactLoad& load) override;
  StepReport advance_interior(const ContactLoad& next) override;

 private:
  /// u_{n+1} and a_{n+1} for a given active set from the predictor u_pred:
  /// S u = M u_hat + beta dt^2 (F - C v~) + G^T mu, G u = h, G a = h''
  /// (method.md §8, §9),
  /// where u_hat is u_pred with its contact part from the nodal boundary
  /// relation of that set (G u_hat = h - beta dt^2 h''), solved in
  /// acceleration form (S a = F - C v~ - K u_hat + G^T mu',
  /// u = u_hat + beta dt^2 a):
  /// a is never formed as (u - u_hat)/(beta dt^2), which loses every digit
  /// when beta dt^2 |a| is below the round-off of u.
  void solve_step(const ActiveSet& active, const ContactLoad& next, Vector& u_next,
                  Vector& a_next);

  /// A solve kept for the fallback, with how far its set is from being
  /// consistent (NodalBoundary::violation).
  struct Candidate {
    ActiveSet set;
    Vector u_next, a_next;
    double violation = 0;
  };
  /// Appends a candidate to the tried_ ones; the slots are reused from step
  /// to step, so that keeping candidates does not allocate once warm.
  Candidate& add_candidate();
  /// Step of the fallback (§5), when no active set tried was consistent.
  void fall_back(const ContactLoad& next, StepReport& report);

  // The energy-stable step (newmark_energy.cpp, method.md §5.3).
  /// After the paper's step to u_, v_, a_, active_ from u_start_, v_start_:
  /// keeps it if its balance is allowed, else takes the state between it
  /// and the dissipative candidate whose balance is.
  void limit_energy(const ContactLoad& next);
  /// One backward-Euler step of dt/2 (matrix S) from (u, v) under the load F
  /// against the gaps g, in place.
  void backward_euler_half_step(Vector& u, Vector& v, const Vector& F, const Vector& g);
  /// u_, v_ at theta of the way from the dissipative candidate to the paper's
  /// step, u_C onto the relation, v M-projected onto its velocities; the
  /// balance's excess over the allowed one.
  double blend(double theta, const ContactLoad& next);

  NewmarkParameters parameters_;
  ImplicitScheme iteration_;
  ConstrainedSolver solver_;  // with the iteration matrix
  // Workspaces of a step (sized by the first one): u_pred_, v_pred_ the
  // predictors; u_hat_, h_, r_ of solve_step; the guessed active set and the
  // solution for it; the candidates tried_[0 .. n_tried_).
  Vector u_pred_, v_pred_, u_hat_, h_, h_accel_, r_, u_next_, a_next_, u_lcp_;
  ActiveSet guess_, predictor_set_;
  std::vector<Candidate> tried_;
  std::size_t n_tried_ = 0;
  // The energy-stable step: M with the relation's constraints (velocity
  // projections, consistent accelerations), the LCP of a half step
  // ((dt/2)^2 W_CC), the candidates and workspaces.
  std::unique_ptr<ConstrainedSolver> mass_;
  std::unique_ptr<CachedLcpSolver> half_lcp_;
  Vector u_paper_, v_paper_, u_dissipative_, v_dissipative_, u_best_, v_best_, load_mean_;
  Vector rhs_, correction_, q_, h_rate_;
  ActiveSet start_set_, blend_set_, best_set_;
  std::vector<bool> open_;
  double allowed_ = 0;
};

}  // namespace nbm
