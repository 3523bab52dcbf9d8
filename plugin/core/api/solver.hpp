// nbm::Solver: the NBM time integrator on the user's dofs. This header is
// free of Eigen and FreeFEM so that the FreeFEM binding (whose headers do not
// mix with Eigen) and other front ends can include it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "linalg/coo_matrix.hpp"

namespace nbm {

class ContactProblem;

/// A function of time, w(t) = offset + rate t + accel t^2 / 2
/// + sum_j (c_j cos(omega_j t) + s_j sin(omega_j t)); `harmonics` holds the
/// triples (omega_j, c_j, s_j).
struct TimeLawDescription {
  double offset = 0, rate = 0, accel = 0;
  std::vector<double> harmonics;
};

/// A rigid obstacle held exactly: each step enforces phi(x + u, t) >= 0 at
/// every contact node with the normal taken where the node is (method.md
/// §10). Needs mass "redistributed" (every component of the contact nodes
/// massless) and scheme "newmark".
struct ObstacleDescription {
  /// "plane", "circle" (2D), "sphere" (3D) or "cylinder" (3D).
  std::string kind;
  /// A point of the plane, the centre, or a point of the cylinder's axis.
  std::vector<double> point;
  /// The plane's normal (out of the obstacle, towards the body), or the
  /// cylinder's axis; normalised.
  std::vector<double> axis;
  double radius = 0;  ///< circle, sphere, cylinder
  /// "outside" (the body outside the round obstacle) or "inside" (a casing).
  std::string side = "outside";
  /// Motion: a translation by translation(t) along `direction` (for a plane:
  /// along its normal, `direction` not used), and for round obstacles a
  /// change of radius radius_change(t).
  std::vector<double> direction;
  TimeLawDescription translation, radius_change;
};

/// Throws InputError naming the field if `obstacle` does not describe an
/// obstacle (unknown kind or side, wrong sizes, zero axis, non-finite or
/// negative radius, malformed time laws).
void check_obstacle(const ObstacleDescription& obstacle);
/// phi(x, t) of the obstacle: the signed distance of the point x at time t.
double obstacle_distance(const ObstacleDescription& obstacle, const std::vector<double>& x,
                         double t);

struct SolverOptions {
  double dt = 0;
  /// "newmark" (implicit NBM), "explicit" (central differences NBM) or
  /// "moreau-jean" (the Newton impact law peer, contact dofs not slaved).
  std::string scheme = "newmark";
  /// Newmark parameters, scheme "newmark" only (default 1/4, 1/2: average
  /// acceleration); setting them with scheme "explicit" is an error.
  std::optional<double> beta, gamma;
  /// Dirichlet dofs (held at zero; any order, repeats allowed). They are the
  /// only Dirichlet conditions the core knows: their rows and columns of M
  /// and K are ignored. A front end translates its own conventions into this
  /// list (the FreeFEM binding adds the dofs of on()'s tgv penalty,
  /// plugin/freefem/dirichlet.hpp); a huge diagonal on a dof not listed here
  /// is just a stiff (or heavy) entry.
  std::vector<long> fixed;
  /// "consistent" (the paper's NBM: contact nodes keep their mass) or
  /// "redistributed" (massless boundary, method.md §4: energy conserving;
  /// implicit scheme only). Redistribution needs `positions`: for every dof
  /// the d coordinates of its node, dof-major (size n_dofs * d, d = 1..3).
  std::string mass = "consistent";
  std::vector<double> positions;
  /// What the energy-stable step of mass "redistributed" bounds (method.md
  /// §5.1): "bounded" (the default: the energy never exceeds its start plus
  /// the work done on the body; what touchdowns lose a later lift-off may
  /// return) or "monotone" (no step raises it). Needs the step: beta = 1/4,
  /// gamma = 1/2, rayleigh_stiffness = 0 and no obstacle.
  std::optional<std::string> energy;
  /// Restitution coefficient of scheme "moreau-jean", in [0, 1] (default 0).
  std::optional<double> restitution;
  /// Viscous damping (method.md §9), C = rayleigh_mass M + rayleigh_stiffness K
  /// + damping: Rayleigh coefficients (finite, >= 0; M the scheme's mass:
  /// redistributed with mass "redistributed", lumped with scheme
  /// "explicit") and a matrix assembled like M and K (n_dofs x n_dofs,
  /// symmetric, nonnegative diagonal; rows = 0: none). Scheme "explicit"
  /// takes only rayleigh_mass; with mass "redistributed" the matrix must not
  /// couple the contact dofs.
  double rayleigh_mass = 0, rayleigh_stiffness = 0;
  CooMatrix damping;
  /// The obstacle held exactly with a contact frame that follows the body
  /// (method.md §10); the contact description then gives only the contact
  /// nodes (its normals and gaps are checked but not used: the obstacle
  /// replaces them).
  std::optional<ObstacleDescription> obstacle;
};

/// Contact nodes: node k owns dofs[k*d .. k*d+d-1] with normal components
/// normals[k*d ..] and gap gaps[k] (method.md §2, §7).
struct ContactDescription {
  std::vector<long> dofs;
  std::vector<double> normals;
  std::vector<double> gaps;
};

struct StepInfo {
  int active_set_iterations = 0;
  bool fallback = false;
  /// With the option `obstacle`: nodes outside the contact set found inside
  /// the obstacle at the step's end (to add to the contact set).
  int crossings = 0;
};

class Solver {
 public:
  /// Validates everything and factors what is needed; throws InputError or
  /// NumericalError (errors.hpp) with a message naming the faulty argument.
  Solver(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
         const SolverOptions& options);
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  long n_dofs() const;
  long n_contact() const;
  const SolverOptions& options() const;
  /// Fixed dofs: the `fixed` option, sorted, without repeats.
  std::vector<long> fixed_dofs() const;

  /// The rigid obstacle from the next initialize(), step() or restart() on
  /// (method.md §8): per contact node the gap along its normal (fixed at
  /// construction) and its first and second time derivatives, at the time
  /// that call reaches. It stays until set again; before any call, the
  /// construction's gaps at rest. Throws InputError on wrong sizes or
  /// non-finite entries.
  /// Throws InputError with the option `obstacle`, which moves by its own law.
  void set_obstacle(const std::vector<double>& g, const std::vector<double>& g_rate,
                    const std::vector<double>& g_accel);
  /// First and second time derivatives of the load (size n_dofs) at the time
  /// the next call reaches; only their contact-dof entries matter (the nodal
  /// boundary relation of open contacts follows F_C). Empty vectors: zero
  /// (a load constant in time on the contact dofs), the default.
  void set_load_rates(const std::vector<double>& F_rate, const std::vector<double>& F_accel);

  /// Sets the state at time t. u and v (size n_dofs) are updated in place:
  /// contact parts follow the nodal boundary relation, fixed dofs are zeroed.
  void initialize(std::vector<double>& u, std::vector<double>& v, const std::vector<double>& F,
                  double t = 0);
  /// Advances u and v in place by dt under the load F at the new time. u and
  /// v must be the arrays the previous call returned (checked).
  StepInfo step(std::vector<double>& u, std::vector<double>& v, const std::vector<double>& F);
  /// Exact restart from a state saved after initialize() or step(): u, v as
  /// returned, t = time(), a = acceleration(), active = active(), the load F
  /// at time t, the obstacle at time t (set_obstacle() before the call, for a
  /// moving one) and scheme_state() (empty for the schemes without one).
  /// Nothing is recomputed, so stepping on reproduces the uninterrupted run
  /// bit for bit. u, v are kept as given (fixed dofs zeroed); the step and
  /// fallback counters, the obstacle's work and the dissipated energy restart from zero.
  void restart(std::vector<double>& u, std::vector<double>& v, const std::vector<double>& F,
               double t, const std::vector<double>& a, const std::vector<long>& active,
               const std::vector<double>& scheme_state = {});

  /// Re-linearisation (method.md §8): replaces the contact description --
  /// nodes, normals, gaps, e.g. the obstacle linearised anew at the current
  /// configuration -- keeping the state, at the cost of one setup (the
  /// factorizations are rebuilt). u, v must be the arrays the last call
  /// returned; they come back with the contact parts of the new contact dofs
  /// from the new nodal boundary relation (u_O, v_O unchanged), and the
  /// acceleration is that of the new relation; F is the load at the current
  /// time. The obstacle becomes the new gaps at rest (set_obstacle() after
  /// this call for a moving one, before the next step). The obstacle's work
  /// restarts from zero; the step and fallback counters go on. Throws as the
  /// constructor does on a bad description, and InputError if the state
  /// penetrates the new obstacle (scheme "moreau-jean", whose states
  /// penetrate by O(dt v): deeper than it penetrates the last one).
  void replace_contacts(const ContactDescription& contact, std::vector<double>& u,
                        std::vector<double>& v, const std::vector<double>& F);

  bool initialized() const;
  double time() const;
  long steps() const;
  long fallbacks() const;
  /// The contact problem in internal coordinates (periodic-orbit solvers).
  const ContactProblem& problem() const;
  /// Critical time step of the explicit scheme (0 for the implicit one).
  double critical_dt() const;

  // Diagnostics of the current state (method.md §2, §7).
  std::vector<double> reactions() const;  ///< lambda >= 0 per contact node
  std::vector<double> gaps() const;       ///< g - u_n >= 0 per contact node
  std::vector<long> active() const;       ///< 1 where the contact is closed
  std::vector<double> acceleration() const;
  /// The scheme's own part of the state (Moreau-Jean: the last impulse per
  /// contact node; the energy-stable steps of the NBM schemes: the loss a
  /// later step may give back, method.md §5.1; empty otherwise), for
  /// restart().
  std::vector<double> scheme_state() const;
  /// kinetic, elastic, load potential, total (their sum), the work done by a
  /// moving obstacle since the start (method.md §8) and the energy dissipated
  /// by the damping since the start (method.md §9), and what the load's
  /// changes in time did to the total since the start (method.md §5.1):
  /// total + dissipated - total(start) = obstacle work + load work, to the
  /// scheme's accuracy (the massless boundary: never more).
  std::vector<double> energies() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nbm
