// Backbones of nonsmooth modes from grazing on the user's model: the front
// end of backbone.hpp for the FreeFEM binding. Like user_orbit.hpp, free of
// Eigen and FreeFEM types (backbone.hpp shares its options).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "periodic/periodic_defaults.hpp"
#include "periodic/user_orbit.hpp"

namespace nbm {

class ContactProblem;

struct BackboneOptions {
  /// Orbits on the backbone, the grazing orbit included.
  long points = 20;
  /// Pseudo-arclength step in unknowns scaled by the last orbit's vibration
  /// amplitude, velocity scale and period (continuation.hpp); a failed
  /// corrector, or an orbit farther than twice the step from the last (a
  /// jump to another branch, from the second step on), retries with step/4,
  /// step/16, step/64.
  double step = 0.05;
  /// Half-period shooting (orbits at rest at 0 and T/2, like the linear
  /// mode's); false: full-period shooting.
  bool half_period = true;
  /// Stop after the first orbit whose vibration energy exceeds this.
  double max_energy = std::numeric_limits<double>::infinity();
  int max_iterations = periodic_max_iterations;
  /// User dof whose amplitude (max - min) / 2 over the period is reported
  /// at every orbit, as for forced orbits (user_forced_orbit.hpp): any dof
  /// that is not fixed; -1: the dof of largest amplitude along the grazing
  /// orbit, kept along the backbone.
  long probe = -1;
  /// How the backbone goes on past its first orbit beyond grazing
  /// (method.md §6, "The primary branch"): `arclength`, pseudo-arclength
  /// steps of `step` (follows any curve of orbits, internal-resonance
  /// tongues included), or `frequency`, natural continuation in the
  /// frequency: orbits at fixed periods, each from the last, the frequency
  /// raised by `frequency_step` (relative) per step; an orbit whose
  /// vibration energy differs from the last one's by more than
  /// `energy_jump` (relative), or a failed Newton, is skipped and the next
  /// frequency tried from the same orbit, steps and jump bound growing
  /// with the number of skips (1 + skips), at most `max_skips` in a row;
  /// each skip is a "tongue" event of the next orbit.
  enum class Branch { arclength, frequency };
  Branch branch = Branch::arclength;
  double frequency_step = 0.002;
  double energy_jump = 0.4;
  int max_skips = 3;
  /// `frequency`: stop before an orbit above this circular frequency.
  double max_omega = std::numeric_limits<double>::infinity();
  /// Reduced basis (reduced_basis.hpp, as for periodic_orbit): this many
  /// fixed-interface modes plus the static contact shapes; 0: the full
  /// interior (at most 3000 dofs). The orbits' reports (BackboneReport::
  /// orbits) give the full model's residual along each.
  int modes = 0;
};

inline const char* name(BackboneOptions::Branch branch) {
  return branch == BackboneOptions::Branch::frequency ? "frequency" : "arclength";
}

/// One orbit of a backbone and its monitors.
struct BackbonePointReport {
  double omega = 0;   ///< circular frequency 2 pi / period
  double period = 0;
  /// Total energy minus that of the static state (which the load alone
  /// gives): 0 at rest, a^2 omega^2 / 2 on the linear mode.
  double energy = 0;
  /// max over the interior dofs of |u(0) - u_static| (t = 0: the turning
  /// point away from the obstacle, where the orbit is at rest).
  double amplitude = 0;
  /// Extremes of the probe dof over the period (the exact flow sampled 512
  /// times and at every switch) and probe_amplitude = (max - min) / 2: the
  /// amplitude a forced response reports (ForcedResponsePoint::amplitude).
  double probe_min = 0, probe_max = 0, probe_amplitude = 0;
  double contact_time = 0;
  long switches = 0;  ///< contact switches per period
  std::vector<double> multipliers_re, multipliers_im;  ///< by decreasing modulus
  double max_multiplier = 0;                           ///< the largest modulus
  bool stable = false;
  double periodicity_residual = 0;
  /// Space-separated: "grazing" (the start, or the number of switches
  /// changed since the previous orbit: a contact touched or left), "fold-
  /// frequency" / "fold-energy" (the frequency / the energy turns here
  /// along the backbone), "stability" (changed since the previous orbit),
  /// "tongue[j:r]" (branch = frequency: a frequency skipped just before
  /// this orbit; j the open system's mode whose frequency is nearest an
  /// integer multiple >= 2 of the skipped one, r = omega_j / omega there).
  std::string events;
};

struct BackboneReport {
  double linear_omega = 0;      ///< omega_j of the open (linear) system
  double grazing_amplitude = 0; ///< modal amplitude a of the grazing orbit
  long grazing_contact = -1;    ///< the contact node (position in the contact list) that grazes
  long probe = -1;              ///< the user dof of probe_amplitude
  std::vector<BackbonePointReport> points;
  std::string stop_reason;
  std::string summary;
  /// The orbits by index (orbits->report(k) is the orbit of points[k]), as
  /// periodic_orbit reports them: their states (orbit_states), and their
  /// family (continue_orbit goes on along the backbone from two of them).
  std::shared_ptr<const OrbitSequence> orbits;
};

/// The backbone of mode `mode` (0: the lowest; modes of the system with
/// every contact open, the contact dofs slaved as for an open contact) of
/// `problem` under the constant load F (user vector), from its grazing orbit
/// (backbone.hpp, method.md §6). Throws InputError naming the argument
/// (mode out of range or rigid, no contact, a gap <= 0, a load that closes
/// a contact at rest, bad options, a probe out of range or fixed), NumericalError if the grazing orbit
/// cannot be analysed; a corrector failure along the backbone ends it
/// (stop_reason).
BackboneReport backbone(const ContactProblem& problem, const std::vector<double>& F, long mode,
                        const BackboneOptions& options);

}  // namespace nbm
