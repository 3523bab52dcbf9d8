// Forced periodic orbits on the user's dofs (method.md §9): the front end of
// shooting (shooting.hpp) and harmonic balance (harmonic_balance.hpp) on the
// forced periodic problem (periodic_problem.hpp) for the FreeFEM binding,
// reporting like the autonomous front end (user_orbit.hpp, OrbitReport).
// Free of Eigen and FreeFEM types.
//
// The excitation is the load
//     F(t) = F0 + sum_{k=1..H} ( Fc_k cos(k omega t) + Fs_k sin(k omega t) )
// and the motion of the obstacles, gaps
//     g(t) = g0 + sum_{k=1..H} ( gc_k cos(k omega t) + gs_k sin(k omega t) )
// (g0 the problem's gaps, method.md §8), on a damped model C = a_M M + b_K K
// + C_user (M the problem's mass: redistributed with the massless boundary;
// C_user an assembled matrix that vanishes on the contact dofs). The orbit
// has the period 2 pi m / omega and no phase condition (the excitation fixes
// the time origin). On the full interior, or with modes > 0 on the reduced
// basis of autonomous orbits (reduced_basis.hpp: damping, load and its
// harmonics projected; the contact dofs and the gap harmonics as they are),
// whose reduction error the report gives: the full model's residual, damping
// and excitation included, along the orbit.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "linalg/coo_matrix.hpp"
#include "periodic/periodic_defaults.hpp"
#include "periodic/user_orbit.hpp"

namespace nbm {

struct ForcedOrbitOptions {
  double omega = std::numeric_limits<double>::quiet_NaN();  ///< > 0, required
  int subharmonic = 1;                                       ///< m >= 1
  double rayleigh_mass = 0, rayleigh_stiffness = 0;          ///< a_M, b_K >= 0
  /// An assembled damping matrix on the user's dofs (as NBM's damping=);
  /// empty: none. Its flow is the state-space one (method.md §9).
  CooMatrix damping;
  /// User dof whose amplitude is reported (any dof that is not fixed);
  /// -1: the dof of largest amplitude along the orbit.
  long probe = -1;
  /// Periods of the exact flow run from the guess before Newton (a stable
  /// orbit's basin; shooting.hpp).
  int transient_periods = 0;
  int max_iterations = periodic_max_iterations;
  /// Reduced basis: this many fixed-interface modes plus the static contact
  /// shapes; 0: the full interior (at most 3000 dofs).
  int modes = 0;
  /// "shooting" (shooting.hpp) or "harmonic-balance"
  /// (harmonic_balance.hpp: `harmonics` harmonics of omega / m, the
  /// guess's flow its initial series; the report then has the coefficients,
  /// the Galerkin residual and the truncation estimate).
  std::string method = "shooting";
  int harmonics = 20;
  /// Harmonics of the gaps: gap_cos[k], gap_sin[k] (harmonic k + 1) hold
  /// one value per contact node (the problem's gap order); either list may
  /// be shorter than the other or empty (fixed obstacles).
  std::vector<std::vector<double>> gap_cos, gap_sin;
};

/// The forced orbit from the guess (u, v) at t = 0 (user vectors). F0 and
/// every harmonic are user vectors (size n_dofs); `load_cos[k]`,
/// `load_sin[k]` are the harmonic k + 1, either list may be shorter (zero
/// harmonics); with the gap harmonics of the options, not all empty. A load
/// harmonic on the normal component of a contact node moves the nodal
/// boundary relation like a gap harmonic (method.md §8).
/// Throws InputError naming the argument (F0, Fc, Fs, gapCos, gapSin, u, v,
/// omega, subharmonic, rayleighM, rayleighK, probe, transient, iterations,
/// method, harmonics),
/// NumericalError if Newton does not converge or an undamped mode is in
/// resonance with a harmonic.
OrbitReport forced_orbit(const ContactProblem& problem, const std::vector<double>& F0,
                         const std::vector<std::vector<double>>& load_cos,
                         const std::vector<std::vector<double>>& load_sin,
                         const std::vector<double>& u, const std::vector<double>& v,
                         const ForcedOrbitOptions& options);

/// Continuation of the forced orbit in the excitation frequency or in the
/// amplitude of the harmonics (forced_continuation.hpp): a frequency- or
/// amplitude-response curve with stability and events.
struct ForcedResponseOptions {
  /// "omega", or "amplitude": a factor on Fc, Fs and the gap harmonics (1 at the start).
  std::string parameter = "omega";
  /// The curve starts at the orbit of `omega` (or at the factor 1), heads
  /// towards `to` and stays within [min(from, to), max(from, to)]; `from`
  /// NaN: the start.
  double from = std::numeric_limits<double>::quiet_NaN();
  double to = std::numeric_limits<double>::quiet_NaN();
  double step = 0.02, max_step = 0.2;  ///< arclength steps in scaled unknowns
  int max_points = 200;
  bool locate_events = true;  ///< by bisection on the arclength (else interpolated)
  /// Branch switching (method.md §9, "Branch switching at a period
  /// doubling"): at the curve's first period doubling, the period-2m orbit
  /// through x* + amplitude e (scaled unknowns), then its branch continued
  /// with the same range and steps (ForcedResponse::doubling).
  bool doubling = false;
  double doubling_amplitude = 1e-3;
};

struct ForcedResponsePoint {
  double omega = 0, scale = 1, arclength = 0;
  /// The probe dof (ForcedResponse::probe) over one period, as in OrbitReport.
  double amplitude = 0, probe_min = 0, probe_max = 0;
  double energy = 0, energy_max = 0;  ///< total energy at t = 0 and its largest value
  double contact_time = 0, min_gap = 0, periodicity_residual = 0;
  long switches = 0;
  std::vector<double> moduli;  ///< |Floquet multipliers|, decreasing
  bool stable = false;
  std::string events;  ///< events between the previous point and this one, '+'-joined
};

struct ForcedResponseEvent {
  std::string kind;  ///< "fold", "period doubling", "Neimark-Sacker", "grazing"
  double parameter = 0, arclength = 0;
  long point = 0;  ///< the point just past it
  double multiplier_re = 0, multiplier_im = 0;  ///< the critical one (0 for grazing)
  std::string description;
};

struct ForcedDoubling;

struct ForcedResponse {
  std::vector<ForcedResponsePoint> points;
  std::vector<ForcedResponseEvent> events;
  long probe = -1;  ///< the user dof of the amplitudes
  std::string stop_reason;
  /// The points as orbits, by index (the nbmOrbit* accessors read the last
  /// one after the call, any one after nbmSelectOrbit).
  std::shared_ptr<const OrbitSequence> orbits;
  /// With ForcedResponseOptions::doubling: the switch and the period-2m branch.
  std::shared_ptr<const ForcedDoubling> doubling;
};

/// The period-2m branch from the first period doubling of a response curve.
struct ForcedDoubling {
  double event_parameter = 0;  ///< where the period doubling was located
  double parameter = 0;        ///< where the period-2m orbit was found, near it
  /// |Phi_T(x0) - x0| in the scaled unknowns of the curve (T the period
  /// before doubling): about `doubling_amplitude` for the period-2m orbit, 0
  /// for the period-m one (forced_continuation.hpp, PeriodDoubledOrbit).
  double separation = 0;
  OrbitReport orbit;      ///< the period-2m orbit found (subharmonic 2m)
  ForcedResponse branch;  ///< its continuation (points, events, orbits)
};

/// The response curve through the forced orbit of `orbit` (its omega,
/// damping, subharmonic, transient, iterations; its probe, or -1: the dof of
/// largest amplitude at the first point). Throws InputError naming the
/// argument (as forced_orbit, and parameter, from, to, step, maxStep,
/// points, doubling, doublingAmplitude; method must be "shooting"),
/// NumericalError if the first orbit is not found or, with `doubling`, no
/// period-2m orbit is found at the curve's first period doubling (InputError
/// `doubling` if the curve has none); the curve ends early with a stop reason
/// if the corrector fails further on.
ForcedResponse forced_response(const ContactProblem& problem, const std::vector<double>& F0,
                               const std::vector<std::vector<double>>& load_cos,
                               const std::vector<std::vector<double>>& load_sin,
                               const std::vector<double>& u, const std::vector<double>& v,
                               const ForcedOrbitOptions& orbit,
                               const ForcedResponseOptions& options);

/// One CSV row per point: point, omega, scale, arclength, amplitude,
/// probe_min, probe_max, energy, energy_max, contact_time, switches,
/// min_gap, max_multiplier, mu2, mu3, mu4 (moduli), stable, periodicity,
/// event. Throws InputError naming `argument` if the file cannot be written.
void write_forced_response(const ForcedResponse& response, const std::string& path,
                           const std::string& argument = "file");

}  // namespace nbm
