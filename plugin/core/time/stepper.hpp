// Time integration of the reduced NBM equations (method.md §5). The state is
// (u, v, a) in internal coordinates; only the interior parts are integrated,
// the contact parts are always reconstructed from the nodal boundary relation.
//
// The base class holds the state and runs the stepping protocol shared by
// every scheme (input checks, the obstacle and its work, the clock, exact
// restart); a scheme implements start(), advance() (the update of u, v, a
// and the active set), reactions() and mass(). The NBM schemes, whose contact
// dofs follow the nodal boundary relation, derive from NbmStepper
// (nbm_stepper.hpp); Moreau-Jean, whose contact dofs are ordinary unknowns,
// from Stepper directly. The implicit steppers are contact steps composed
// with a time scheme (implicit_scheme.hpp: Newmark, generalized-alpha); a new
// implicit scheme is a parameter set there, a new contact treatment one
// subclass. State of its own that a restart needs goes through
// scheme_state() / restore_scheme_state().
#pragma once

#include "contact/contact_problem.hpp"
#include "contact/damping.hpp"
#include "linalg/active_set.hpp"

namespace nbm {

struct Energies {
  double kinetic = 0;  ///< 1/2 v^T M v (v_C = A v_O + e')
  double elastic = 0;  ///< 1/2 u^T K u
  double load = 0;     ///< -F^T u, the potential of the (current) load
  /// Work done on the body by a moving obstacle since the start,
  /// -int lambda . g'(t) dt (trapezoidal rule over the steps; method.md §8).
  /// With a constant load, total() - total(start) equals it (to the scheme's
  /// accuracy; exactly for the massless boundary).
  double obstacle_work = 0;
  /// Energy dissipated by the damping since the start, D = int v^T C v dt
  /// (midpoint rule over the steps, v at mid-step the mean of its ends:
  /// exact for average-acceleration Newmark on a linear system; method.md
  /// §9). total() + dissipated - obstacle_work stays constant for a fixed
  /// load, to the scheme's accuracy.
  double dissipated = 0;
  /// What a load changing in time does to the total energy since the start,
  /// -sum (F_{n+1} - F_n) . (u_n + u_{n+1}) / 2 over the steps (the
  /// trapezoidal rule's balance of the potential -F.u; method.md §5.1):
  /// total() + dissipated - obstacle_work - load_work stays constant.
  double load_work = 0;
  double total() const { return kinetic + elastic + load; }
};

/// The rigid obstacle at one time (method.md §8): per contact node, the gap
/// g along the node's normal (fixed at construction) and its first and
/// second time derivatives, which the schemes need for v_C and a_C.
struct Obstacle {
  Vector g, g_rate, g_accel;
  /// An obstacle at rest at gaps g.
  static Obstacle at_rest(const Vector& g);
};

/// What drives a step, at the step's end time: the load F (internal
/// coordinates) and the obstacle. The load's rates enter only through the
/// contact dofs (the nodal boundary relation of open contacts, (K u)_C = F_C,
/// moves with F_C); null means a load constant in time there.
struct ContactLoad {
  const Vector& F;
  const Obstacle& obstacle;
  const Vector* F_rate = nullptr;   ///< dF/dt
  const Vector* F_accel = nullptr;  ///< d2F/dt2
};

struct StepReport {
  int active_set_iterations = 0;  ///< linear solves with a guessed active set
  bool fallback = false;          ///< cycling was detected and resolved (§5)
  /// Nodes outside the contact set found inside the obstacle at the step's
  /// end (schemes that know the obstacle's geometry; method.md §10).
  int crossings = 0;
};

class Stepper {
 public:
  /// `damping` in the problem's (internal) coordinates; throws InputError
  /// as check_damping() does.
  Stepper(const ContactProblem& problem, double dt, const Damping& damping = {});
  virtual ~Stepper() = default;
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  /// Starts at time t from displacement u and velocity v under `load`
  /// (internal coordinates); start() completes the state (for NBM: u_C and
  /// v_C replaced by their nodal boundary values, the acceleration of the
  /// reduced equations). Throws InputError on wrong sizes, non-finite
  /// entries, or if u penetrates the obstacle.
  void initialize(const Vector& u, const Vector& v, const ContactLoad& load, double t = 0);
  /// The same against the contact set's gaps, at rest.
  void initialize(const Vector& u, const Vector& v, const Vector& F, double t = 0);
  /// initialize() from a state a run of the same scheme reached, e.g. under
  /// another contact description (Solver::replace_contacts): its penetration
  /// is checked only for the schemes that never penetrate.
  void continue_from(const Vector& u, const Vector& v, const ContactLoad& load, double t);
  /// After continue_from(): takes over what of `previous`'s scheme state
  /// outlives its contact set; nothing by default.
  virtual void carry_over(const Stepper& previous) { (void)previous; }
  /// Advances by dt to the load and obstacle of `next` at the new time.
  /// Sizes and the obstacle are checked; the load's entries are taken as
  /// finite (the front end checks them: one pass over the dofs, not two).
  StepReport step(const ContactLoad& next);
  /// Advances by dt under the load F at the new time, the obstacle staying
  /// as it is (its gaps and rates unchanged).
  StepReport step(const Vector& F_next) { return step(ContactLoad{F_next, obstacle_}); }

  /// Exact restart: restores a state saved after initialize() or step() --
  /// displacement, velocity, acceleration, active set, the load and obstacle
  /// at time t, and the scheme's own state (scheme_state(); empty for the
  /// schemes that have none) -- as it is (nothing is recomputed), so that
  /// stepping on from it reproduces the uninterrupted run bit for bit. The
  /// caches of factorizations per active set are pure memoization. The
  /// obstacle's work and the dissipated energy restart from zero. Throws InputError on wrong sizes,
  /// non-finite entries or, for the NBM schemes, a penetrating u.
  void restore(const Vector& u, const Vector& v, const Vector& a, const ActiveSet& active,
               const ContactLoad& load, double t, const Vector& scheme_state = Vector());
  /// The same against the contact set's gaps, at rest.
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
  const Obstacle& obstacle() const { return obstacle_; }
  /// Contact force lambda >= 0 per contact node (for NBM, method.md §2).
  Vector reactions() const {
    Vector lambda;
    reactions(lambda);
    return lambda;
  }
  virtual void reactions(Vector& lambda) const = 0;
  /// g - u_n per contact node, against the current obstacle (a scheme whose
  /// contact frame follows the body: the true distance phi(x + u)).
  virtual Vector gaps() const { return gaps(u_, obstacle_.g); }
  Energies energies() const;
  /// The damping matrix C in internal coordinates (method.md §9); 0 x 0
  /// without damping.
  const SparseMatrix& damping() const { return C_; }
  bool damped() const { return C_.size() != 0; }
  /// State of the scheme beyond (u, v, a, active set, load, obstacle) that an
  /// exact restart needs; empty by default.
  virtual Vector scheme_state() const { return Vector(); }

 protected:
  /// The mass matrix of the scheme (consistent or lumped), for energies.
  virtual const SparseMatrix& mass() const = 0;
  /// Completes the initial state (u_, v_, F_, obstacle_ and t_ set from the
  /// arguments of initialize(); `load` holds the load's rates): a_, active_,
  /// and whatever the scheme derives.
  virtual void start(const ContactLoad& load) = 0;
  /// The scheme's step: u_, v_, a_ and active_ at t + dt from the state at t
  /// and `next`. The base class then advances the clock and the obstacle.
  virtual StepReport advance(const ContactLoad& next) = 0;
  /// True for schemes whose positions never penetrate the obstacle (the NBM
  /// ones): their restored states are checked for penetration.
  virtual bool exact_impenetrability() const = 0;
  /// Sets the scheme's own state (scheme_state()) at the end of restore();
  /// throws InputError if it does not fit. Default: only an empty one fits.
  virtual void restore_scheme_state(const Vector& state);
  /// g - u_C per contact node for the displacement u and the gaps g.
  Vector gaps(const Vector& u, const Vector& g) const;
  /// Throws InputError if u penetrates the obstacle at gaps g beyond round-off.
  void check_penetration(const Vector& u, const Vector& g, const char* what) const;
  /// True while start() runs for initialize() (a new state), false for
  /// continue_from() (a state a run reached, under another contact set).
  bool fresh_start() const { return fresh_start_; }
  /// Adds to the obstacle's work a scheme that accounts for it itself (a
  /// contact frame that follows the body, whose obstacle is not a gap vector).
  void add_obstacle_work(double work) { obstacle_work_ += work; }
  /// True for a scheme that adds a moving obstacle's work itself
  /// (add_obstacle_work) because its contact force over a step is not the
  /// mean of the reactions at the step's ends.
  virtual bool accounts_obstacle_work() const { return false; }
  /// Throws InputError if a gap of `next` differs from the current one by
  /// more than its rates allow over dt (a jump of the obstacle, method.md §8).
  void check_obstacle_motion(const Obstacle& next) const;

  const ContactProblem& problem_;
  double dt_;
  double t_ = 0;
  bool initialized_ = false;
  Vector u_, v_, a_, F_;
  Obstacle obstacle_;
  ActiveSet active_;
  /// C = a_M M + b_K K + C_user (consistent or redistributed M of the
  /// problem); a scheme with another mass (lumped) sets its own.
  SparseMatrix C_;

 private:
  void begin(const Vector& u, const Vector& v, const ContactLoad& load, double t, bool check);
  /// u, v, the load and obstacle at time t, the energy counters from zero:
  /// what a new start and a restore share.
  void set_state(const Vector& u, const Vector& v, const ContactLoad& load, double t);
  /// Sizes and finite entries of `load`; with `whole` false, the load's
  /// entries are not scanned (the obstacle's are).
  void check_load(const ContactLoad& load, bool whole) const;

  double obstacle_work_ = 0;
  double load_work_ = 0;
  double dissipated_ = 0;
  bool fresh_start_ = true;
  // Workspaces of a step: the gap change and the reactions at both ends of a
  // step of a moving obstacle; the mid-step velocity and C times it.
  // u_n, when the load changes over the step.
  Vector dg_, lambda_old_, lambda_new_, v_mid_, Cv_, u_before_;
};

}  // namespace nbm
