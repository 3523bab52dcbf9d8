// Shooting for periodic orbits of the reduced NBM equations (method.md §6,
// §9) on the exact flow (exact_flow.hpp): Newton's method on the period map
// with the exact monodromy matrix, for either kind of periodic problem
// (periodic_problem.hpp).
//
// Forced orbits: unknowns (u0, v0) at t = 0; equations x(T) - x0 = 0 with
// the excitation's period, a square system whose Jacobian is X - I (X the
// monodromy). Within one region the flow is affine in x0, so an orbit that
// never switches (the linear limit) converges in one step.
//
// Autonomous orbits, full shooting: unknowns (u0, v0, T); equations
// x(T) - x0 = 0, the phase
// condition v0[probe] = 0 (t = 0 at a turning point of the probe dof) and
// an amplitude condition. The system is overdetermined by one equation and
// consistent (on a conservative family, the monodromy has two multipliers
// at 1); Newton steps are least-squares solutions.
//
// Autonomous half-period shooting, for orbits through a state at rest: unknowns
// (u0, T/2) with v0 = 0; equations v(T/2) = 0 and the amplitude condition.
// The reduced equations are reversible (the field depends on u_O only), so
// an orbit at rest at 0 and T/2 retraces itself: it is periodic.
#pragma once

#include <optional>

#include "periodic/gauss_newton.hpp"
#include "periodic/periodic_orbit.hpp"
#include "periodic/periodic_problem.hpp"

namespace nbm {

/// The options of both kinds of problem; the phase and amplitude conditions
/// (probe, kind, amplitude, arclength, half_period) are an autonomous
/// problem's (a forced one refuses amplitude, arclength and half_period).
struct ShootingOptions {
  enum class Amplitude { displacement, energy, period };
  Index probe = 0;  ///< interior dof of the phase and displacement conditions
  /// The condition that picks one orbit of a family: u0[probe] = amplitude,
  /// total energy = amplitude, or period = amplitude. Unset (NaN): the value
  /// of the initial guess.
  Amplitude kind = Amplitude::displacement;
  double amplitude = std::numeric_limits<double>::quiet_NaN();
  /// Pseudo-arclength continuation: if set, replaces the amplitude
  /// condition by tangent . ((u0, v0, T) - anchor) = 0 (2n + 1 entries each;
  /// the tangent carries the continuation's scaling of the unknowns).
  struct Arclength {
    Vector tangent, anchor;
  };
  std::optional<Arclength> arclength;
  bool half_period = false;
  double tolerance = 1e-12;  ///< on the periodicity residual (periodic_orbit.hpp)
  int max_iterations = periodic_max_iterations;
  /// Periods of the exact flow run from the guess before Newton starts: for
  /// a stable forced orbit, a cheap way into Newton's basin (the period map
  /// is only piecewise smooth, and a guess across a grazing boundary can
  /// stall it).
  int transient_periods = 0;
};

/// The amplitude condition (shared by shooting and harmonic balance) at the
/// state (u, v) of an orbit of the given period: u[probe], the total energy
/// or the period.
double amplitude_value(const ReducedField& field, ShootingOptions::Amplitude kind, Index probe,
                       const Vector& u, const Vector& v, double period);
/// Its gradient in (u, v, period): 2n + 1 entries.
Vector amplitude_gradient(const ReducedField& field, ShootingOptions::Amplitude kind,
                          Index probe, const Vector& u, const Vector& v);

/// Newton from the guess (u0, v0, T) (T: a forced problem's period()); the
/// returned orbit is analysed (analyse_orbit): an autonomous one with its
/// trivial multiplier, a forced one without (stable if all |mu| < 1).
/// Throws NumericalError if Newton does not converge, InputError on a bad
/// guess or option.
PeriodicOrbit shoot(const PeriodicProblem& problem, const Vector& u0, const Vector& v0, double T,
                    const ShootingOptions& options);

}  // namespace nbm
