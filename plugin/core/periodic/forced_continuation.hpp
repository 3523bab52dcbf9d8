// Continuation of forced periodic orbits (method.md §9, "Continuation of
// forced orbits"): frequency-response and amplitude-response curves of the
// damped, harmonically forced reduced NBM equations, with Floquet
// multipliers, stability and flagged events at every point.
//
// A point is a fixed point x0 = (u0, v0) of the period map of the exact flow
// (shooting.hpp, a forced problem) at a parameter p: the forcing frequency omega
// (T = 2 pi m / omega changes with it) or a scale factor on the harmonics of
// the HarmonicLoad, load and gaps (the constant load F0 and gaps g0 of the
// field are not scaled).
// Pseudo-arclength on the scaled unknowns (u0 / L, v0 / (L omega_0), p / P):
// tangent predictor, Newton corrector on the bordered system
//
//     [ W (X - I)   W dPhi/dp ] [dx]     [ W (Phi(x0, p) - x0) ]
//     [      tangent^T        ] [dp] = - [ tangent . (y - y_k) - h ]
//
// with dPhi/dp by central differences of the exact flow; the steps, bounds
// and events are the continuation driver's (arclength_continuation.hpp).
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "contact/damping.hpp"
#include "periodic/harmonic_load.hpp"
#include "periodic/periodic_orbit.hpp"
#include "periodic/shooting.hpp"

namespace nbm {

enum class ForcedParameter {
  frequency,  ///< omega of the HarmonicLoad
  amplitude   ///< scale factor s on its harmonics, of the load and of the gaps (x_k -> s x_k)
};

/// The load at parameter value p: `load` with omega = p (frequency) or its
/// harmonics times p (amplitude).
HarmonicLoad forced_load(const HarmonicLoad& load, ForcedParameter parameter, double p);

struct ForcedContinuationOptions {
  ForcedParameter parameter = ForcedParameter::frequency;
  /// Bounds of the parameter (required; for the frequency, 0 < min). The
  /// start (load.omega, or the scale 1) must lie within them.
  double parameter_min = std::numeric_limits<double>::quiet_NaN();
  double parameter_max = std::numeric_limits<double>::quiet_NaN();
  int direction = 1;  ///< +1 / -1: sign of the parameter change at the start
  /// Arclength steps, in the scaled unknowns: first step, bounds.
  double step = 0.02, min_step = 1e-5, max_step = 0.2;
  double growth = 1.5;       ///< step factor after a corrector of <= easy_iterations
  int easy_iterations = 3;
  /// A corrected point farther than max_jump * step from the previous point
  /// (scaled) is rejected like a failed corrector: it jumped to another
  /// branch. Must be >= 1 (the point lies on the hyperplane at `step`).
  double max_jump = 2;
  /// Largest angle (radians) between the tangents of consecutive points; a
  /// sharper turn is rejected like a failed corrector. On a C^1 curve it
  /// vanishes with the step; a corrector that converged back onto the part
  /// of the curve already followed turns by about pi.
  double max_turn = 0.5;
  int max_points = 200;      ///< including the first point
  /// Scales: L of the displacements (0: from the first orbit, the larger of
  /// |u0| and |v0| / omega_0) and P of the parameter (0: |p_0|).
  double length = 0, parameter_scale = 0;
  /// Relative step of the central differences of the period map in p
  /// (times P).
  double difference_step = 1e-6;
  /// Newton iterations of a corrector before it counts as failed (the step
  /// is then halved).
  int corrector_iterations = 12;
  /// Subharmonic order m of every point: its period is 2 pi m / omega.
  int subharmonic = 1;
  /// Newton tolerance of every corrector; the first point is shot with all
  /// of it (max_iterations, transient_periods).
  ShootingOptions shooting;
  /// Events bracketed between two points are located by bisection on the
  /// arclength down to event_tolerance (scaled); with locate_events false,
  /// or if a corrector fails during the bisection, by interpolation.
  bool locate_events = true;
  double event_tolerance = 1e-8;
  int max_bisections = 60;
};

struct ForcedPoint {
  double parameter = 0;    ///< p
  double omega = 0;        ///< forcing frequency at this point
  double scale = 1;        ///< amplitude factor at this point
  double arclength = 0;    ///< scaled arclength from the first point
  /// d p / d s of the unit tangent (scaled), oriented along the curve (away
  /// from the previous point): its sign changes at a fold.
  double tangent_parameter = 0;
  PeriodicOrbit orbit;     ///< analysed: multipliers, stability, switches, energies
  int switches = 0;        ///< contact switches per period
  /// Smallest gap of any contact over 256 samples of the period (0 if one
  /// closes): it reaches 0 at grazing from the open side.
  double min_gap = 0;
  Vector peak;             ///< max over the samples of |u_O(t)|, per interior dof
  int corrector_iterations = 0;
};

enum class ForcedEventKind { fold, period_doubling, neimark_sacker, grazing };
std::string to_string(ForcedEventKind kind);

struct ForcedEvent {
  ForcedEventKind kind = ForcedEventKind::fold;
  /// Between points[point] and points[point + 1] of the curve.
  Index point = 0;
  double parameter = 0, arclength = 0;
  /// true: bisection on the arclength to event_tolerance; false:
  /// interpolation in the bracket (for a fold between the two points, the
  /// vertex of the parabola whose slope dp/ds is linear between their
  /// tangents; else the middle of the bracket, on the chord). `orbit` is the
  /// corrected point nearest past the event (points[point + 1] if none).
  bool bisected = false;
  PeriodicOrbit orbit;
  /// The critical multiplier at `orbit`: nearest +1 (fold), nearest -1 among
  /// the real ones (period doubling), nearest the unit circle among the
  /// complex ones (Neimark-Sacker); 0 for grazing.
  std::complex<double> multiplier;
  std::string description;  ///< one line: kind, parameter, point, multiplier
};

enum class ForcedStop {
  max_points,       ///< max_points reached
  parameter_bound,  ///< the last point is on a bound of the parameter
  step_too_small    ///< the corrector failed (or jumped) down to min_step
};

struct ForcedCurve {
  std::vector<ForcedPoint> points;
  std::vector<ForcedEvent> events;
  ForcedStop stop = ForcedStop::max_points;
  std::string stop_reason;  ///< a sentence: why the curve ends where it does
  double length = 0, parameter_scale = 0;  ///< the scales used
};

/// The curve through the forced orbit of `load` (p_0 = load.omega, or the
/// scale 1) near the guess (u0, v0), shot with options.shooting. Throws
/// InputError on bad options or input, NumericalError if the first orbit is
/// not found; failures further on end the curve with a stop reason.
ForcedCurve continue_forced(const ReducedField& field, const Damping& damping,
                            const HarmonicLoad& load, const Vector& u0, const Vector& v0,
                            const ForcedContinuationOptions& options);

struct PeriodDoubledOrbit {
  PeriodicOrbit orbit;      ///< subharmonic 2 m, analysed (shoot, forced problem)
  double parameter = 0;     ///< where it was found, near the event's
  /// |Phi_T(x0) - x0| in the scaled unknowns (T the period before doubling):
  /// of the order of `amplitude` for a true period-2 orbit, ~0 for the
  /// period-1 orbit it branches from.
  double separation = 0;
};

/// Branch switching at a period-doubling event of `curve` (same field,
/// damping, load and options): from the event's orbit x*, the period-2m
/// orbit through x* + amplitude e, e the eigenvector of the multiplier -1 of
/// its monodromy (at t = 0, where x* is given), found by the bordered
/// corrector with m doubled and the condition e . (y - y*) = amplitude
/// (scaled), then shot (shoot, forced problem). Throws InputError if the event is
/// not a period doubling or amplitude <= 0, NumericalError if no orbit is
/// found or the one found is the period-1 orbit.
PeriodDoubledOrbit switch_at_period_doubling(const ReducedField& field, const Damping& damping,
                                             const HarmonicLoad& load,
                                             const ForcedContinuationOptions& options,
                                             const ForcedCurve& curve, const ForcedEvent& event,
                                             double amplitude = 1e-3);

}  // namespace nbm
