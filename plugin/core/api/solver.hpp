// nbm::Solver: the NBM time integrator of a Model (api/model.hpp) on the
// user's dofs. This header is free of Eigen and FreeFEM so that the FreeFEM binding (whose headers do not
// mix with Eigen) and other front ends can include it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "api/model.hpp"
#include "time/energy_control.hpp"

namespace nbm {

/// The time scheme (method.md §5).
enum class TimeScheme {
  kNewmark,           ///< implicit NBM, Newmark's family (beta, gamma)
  kGeneralizedAlpha,  ///< implicit NBM, Chung and Hulbert's (rho_inf; §5.4)
  kHhtAlpha,          ///< implicit NBM, Hilber, Hughes and Taylor's (rho_inf; §5.4)
  kExplicit,          ///< central differences NBM (lumped mass)
  kMoreauJean,        ///< the Newton impact law peer (contact dofs not slaved)
};
/// The name front ends and messages use: "newmark", "generalized-alpha",
/// "hht-alpha", "explicit", "moreau-jean".
const char* name(TimeScheme scheme);

/// How the model is advanced in time: the scheme and its parameters.
struct SchemeOptions {
  double dt = 0;
  TimeScheme scheme = TimeScheme::kNewmark;
  /// Newmark parameters, scheme kNewmark only (default 1/4, 1/2: average
  /// acceleration); setting them with another scheme is an error.
  std::optional<double> beta, gamma;
  /// Spectral radius at infinite frequency of schemes kGeneralizedAlpha
  /// (in [0, 1], default 0.8) and kHhtAlpha (in [1/2, 1], default 0.8).
  std::optional<double> rho_inf;
  /// What the energy-stable step bounds (method.md §5.1, §5.3): kBounded
  /// (the default: the energy never exceeds its start plus the work done on
  /// the body; what touchdowns lose a later lift-off may return), kMonotone
  /// (no step raises it) or kNone (the plain step). Needs scheme kNewmark
  /// with beta = 1/4, gamma = 1/2, no rayleigh_stiffness and no obstacle, and
  /// with mass kConsistent no damping at all; the default is kNone where the
  /// step does not exist.
  std::optional<EnergyControl> energy;
  /// Restitution coefficient of scheme kMoreauJean, in [0, 1] (default 0).
  std::optional<double> restitution;
  /// Integrate the reduced model (method.md §6, "Time integration on the
  /// reduced model"): the interior on `modes` fixed-interface modes and the
  /// static contact shapes, the contact dofs kept. States, loads, energies
  /// and restarts stay on the user's dofs (the state is the reduced one
  /// expanded). Implicit NBM schemes only, not with the option obstacle nor
  /// replace_contacts(); 1 <= modes <= the number of interior dofs.
  std::optional<int> modes;
};

/// The options of the shorthand constructor: the model's and the scheme's.
struct SolverOptions : ModelOptions, SchemeOptions {};

struct StepInfo {
  int active_set_iterations = 0;
  bool fallback = false;
  /// With the option `obstacle`: nodes outside the contact set found inside
  /// the obstacle at the step's end (to add to the contact set).
  int crossings = 0;
};

class Solver {
 public:
  /// The time integrator of `model`: validates the scheme's options against
  /// the model and factors what the scheme needs; throws InputError or
  /// NumericalError (errors.hpp) with a message naming the faulty argument.
  Solver(std::shared_ptr<const Model> model, const SchemeOptions& options);
  /// Shorthand: the integrator of a model of its own.
  Solver(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
         const SolverOptions& options);
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  long n_dofs() const;
  long n_contact() const;
  /// The model's options and the scheme's.
  const SolverOptions& options() const;
  /// Fixed dofs: the `fixed` option, sorted, without repeats.
  std::vector<long> fixed_dofs() const;
  /// The model integrated (after replace_contacts(), the model with the new
  /// contact description).
  const std::shared_ptr<const Model>& model() const;

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
  /// Critical time step of the explicit scheme (0 for the implicit one).
  double critical_dt() const;
  /// With the option modes, the reduction error of the current state: the
  /// full model's residual P^T (M u'' + C u' + K u - F) at the expanded
  /// state under the last load, P its nodal boundary relation on the current
  /// contact set, relative to the size of its terms (method.md §6; 0 to
  /// round-off with every interior mode). InputError without modes or before
  /// a state.
  double reduction_residual() const;

  // Diagnostics of the current state (method.md §2, §7).
  std::vector<double> reactions() const;  ///< lambda >= 0 per contact node
  std::vector<double> gaps() const;       ///< g - u_n >= 0 per contact node
  std::vector<long> active() const;       ///< 1 where the contact is closed
  std::vector<double> acceleration() const;
  /// The scheme's own part of the state (Moreau-Jean: the last impulse per
  /// contact node; the energy-stable steps of the NBM schemes: the loss a
  /// later step may give back, method.md §5.1; empty otherwise), for
  /// restart(). With the option modes it ends with the reduced state
  /// (displacement, velocity, acceleration in the reduced coordinates), which
  /// a restart continues from bit for bit (it must expand to the u, v given).
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
