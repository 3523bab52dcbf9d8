// Time integration of the reduced NBM equations (method.md §5). The state is
// (u, v, a) in internal coordinates; only the interior parts are integrated,
// the contact parts are always reconstructed from the nodal boundary relation.
#pragma once

#include "active_set.hpp"
#include "contact_problem.hpp"
#include "nodal_boundary.hpp"

namespace nbm {

struct Energies {
  double kinetic = 0;  ///< 1/2 v^T M v (v_C = A v_O)
  double elastic = 0;  ///< 1/2 u^T K u
  double load = 0;     ///< -F^T u, the potential of the (current) load
  double total() const { return kinetic + elastic + load; }
};

struct StepReport {
  int active_set_iterations = 0;  ///< linear solves with a guessed active set
  bool fallback = false;          ///< cycling was detected and resolved (§5)
};

class Stepper {
 public:
  Stepper(const ContactProblem& problem, double dt);
  virtual ~Stepper() = default;
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  /// Starts at time t from displacement u and velocity v under the load F
  /// (internal coordinates); start() completes the state (for NBM: u_C and
  /// v_C replaced by their nodal boundary values, the acceleration of the
  /// reduced equations). Throws InputError if u penetrates the obstacle.
  void initialize(const Vector& u, const Vector& v, const Vector& F, double t = 0);
  /// Advances by dt under the load F at the new time.
  virtual StepReport step(const Vector& F_next) = 0;

  /// Exact restart: restores a state saved after initialize() or step() --
  /// displacement, velocity, acceleration, active set, the load F at time t --
  /// as it is (nothing is recomputed), so that stepping on from it reproduces
  /// the uninterrupted run bit for bit. The steppers keep nothing else between
  /// steps that affects the results (caches of factorizations per active set
  /// are pure memoization). Moreau-Jean's last impulse is not part of the
  /// state: reactions() is zero until the next step. Throws InputError on wrong
  /// sizes, non-finite entries or, for the NBM schemes, a penetrating u.
  void restore(const Vector& u, const Vector& v, const Vector& a, const ActiveSet& active,
               const Vector& F, double t);
  /// Overwrites u, v and a (same sizes, unchecked), keeping the rest of the
  /// state: for a front end that rounds the state through its own coordinates
  /// after every step, so that a restart from them is exact.
  void replace_kinematics(Vector u, Vector v, Vector a);

  bool initialized() const { return initialized_; }
  double dt() const { return dt_; }
  double time() const { return t_; }
  const Vector& u() const { return u_; }
  const Vector& v() const { return v_; }
  const Vector& a() const { return a_; }
  const ActiveSet& active() const { return active_; }
  /// Contact force lambda >= 0 per contact node (for NBM, method.md §2).
  virtual Vector reactions() const { return boundary_.reactions(u_, F_); }
  Vector gaps() const { return boundary_.gaps(u_); }
  Energies energies() const;

 protected:
  /// The mass matrix of the scheme (consistent or lumped), for energies.
  virtual const SparseMatrix& mass() const = 0;
  /// Completes the initial state; by default the NBM one: u_C from the LCP,
  /// v_C = A v_O, then solve_acceleration.
  virtual void start();
  /// Solves mass() a = F - K u + G^T mu, G a = 0 for the current active set.
  virtual void solve_acceleration(const Vector& F) = 0;
  /// Completes a step: v_C, a_C from the new active set, time advanced.
  void finish_step(const Vector& F_next);
  /// False for a scheme whose positions may penetrate (Moreau-Jean): its
  /// restored states are not checked for penetration.
  virtual bool exact_impenetrability() const { return true; }
  /// Called at the end of restore(): resets what is not part of the state.
  virtual void restored() {}
  /// Throws InputError if u penetrates the obstacle beyond round-off.
  void check_penetration(const Vector& u, const char* what) const;

  const ContactProblem& problem_;
  NodalBoundary boundary_;
  double dt_;
  double t_ = 0;
  bool initialized_ = false;
  Vector u_, v_, a_, F_;
  ActiveSet active_;
};

}  // namespace nbm
