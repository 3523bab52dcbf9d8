// The NBM schemes (method.md §3-5, §8): the contact dofs are never
// integrated; u_C, v_C and a_C follow the nodal boundary relation of the
// active set, u_C = A u_O + e(t), v_C = A v_O + e'(t), a_C = A a_O + e''(t).
// This class holds the relation and completes every step with it; a scheme
// (Newmark, massless Newmark, central differences) implements advance(),
// solve_acceleration() and mass().
#pragma once

#include "contact/nodal_boundary.hpp"
#include "time/energy_budget.hpp"
#include "time/implicit_scheme.hpp"
#include "time/stepper.hpp"

namespace nbm {

class NbmStepper : public Stepper {
 public:
  using Stepper::reactions;
  /// lambda = F_C - (K u)_C (method.md §2).
  void reactions(Vector& lambda) const override { boundary_.reactions(u_, F_, lambda); }

  /// Whether the scheme takes an energy-stable step (method.md §5.1, §5.3).
  bool energy_stable() const { return energy_stable_; }
  /// What switching steps have lost and a later step may still return
  /// (EnergyControl::kBounded): E_n + D_n - W_n plus it never rises. Negative
  /// by round-off where a step rose by round-off (either control): the next
  /// balanced steps take that back.
  double returnable_loss() const { return budget_.returnable(); }
  /// Steps since the start that were taken between two candidates: those on
  /// which the scheme's own step would have gained more than allowed.
  long balanced_steps() const { return budget_.balanced_steps(); }
  /// [returnable_loss()] with the energy-stable step, the time scheme's state
  /// (generalized-alpha's algorithmic acceleration) with a scheme that has
  /// one, else empty.
  Vector scheme_state() const override;
  /// The returnable loss of a previous energy-stable run (a global budget:
  /// it outlives the contact set).
  void carry_over(const Stepper& previous) override;

 protected:
  /// `energy`: what the energy-stable step bounds, if the scheme has one
  /// (`has_energy_step`) and energy is not kNone.
  NbmStepper(const ContactProblem& problem, double dt, const Damping& damping,
             EnergyControl energy = EnergyControl::kNone, bool has_energy_step = false);

  /// An implicit scheme's stepper hands its time scheme over (constructor),
  /// whose own state this class then starts, finishes each step with, saves
  /// and restores.
  void uses_scheme(ImplicitScheme& scheme) { scheme_ = &scheme; }

  /// u_C from the LCP, v_C = A v_O + e', then solve_acceleration (and
  /// nothing returnable yet); the time scheme's state from a.
  void start(const ContactLoad& load) override;
  void restore_scheme_state(const Vector& state) override;
  /// advance_interior(), then v_C and a_C from the nodal boundary relation of
  /// the new active set, and the time scheme's state from them.
  StepReport advance(const ContactLoad& next) final;
  /// The scheme's step of u_, v_, a_ and active_; their contact parts are
  /// completed afterwards.
  virtual StepReport advance_interior(const ContactLoad& next) = 0;
  /// Solves mass() a = F - K u + G^T mu, G a = h'' for the current active set
  /// and the load and obstacle of `load` (the current ones).
  virtual void solve_acceleration(const ContactLoad& load) = 0;
  bool exact_impenetrability() const override { return true; }

  /// Right-hand sides of G x = h (method.md §4, §8) for the displacement, the
  /// velocity and the acceleration: g, g', g'' on closed contacts, F_C and
  /// its rates on open ones.
  void displacement_constraint(const ContactLoad& load, const ActiveSet& active,
                               Vector& h) const;
  void rate_constraint(const ContactLoad& load, const ActiveSet& active, Vector& h) const;
  void acceleration_constraint(const ContactLoad& load, const ActiveSet& active,
                               Vector& h) const;

  // The energy-stable steps' balance (method.md §5.1, §5.3), shared by the
  // mass treatments.
  /// E = v'Mv/2 + u'Ku/2 - F.u (leaves K u in Ku_, M v in Mv_).
  double energy(const Vector& u, const Vector& v, const Vector& F);
  /// E + the step's dissipation - the work of the obstacle and of the load's
  /// change over the step, for the end state (u, v) of the current step
  /// (from u_start_, v_start_, under F_ to F).
  double balance(const Vector& u, const Vector& v, double work, const Vector& F);
  /// E at the step's start (u_start_, v_start_, F_), and the round-off of
  /// the energies there (of the size of their largest term) in *roundoff.
  double start_energy(double* roundoff);

  NodalBoundary boundary_;
  const bool energy_stable_;  // the step of method.md §5.1 / §5.3 is taken
  EnergyBudget budget_;       // what it bounds
  Vector u_start_, v_start_;  // the step's start, kept by the energy-stable steps
  Vector Ku_, Mv_;            // energy()'s products

 private:
  /// h_k = closed(k) on closed contacts, (*open)(c_k) (0 if null) on open ones.
  void constraint(const Vector& closed, const Vector* open, const ActiveSet& active,
                  Vector& h) const;

  ImplicitScheme* scheme_ = nullptr;  // the derived class's, if implicit
  Vector h_;       // workspace: the constraints of the rates
  Vector mean_velocity_;  // workspace of balance()
};

}  // namespace nbm
