// Forced periodic orbits of the damped reduced NBM equations (method.md §9)
// by shooting on the exact flow (exact_flow.hpp).
//
// The excitation of frequency omega fixes the period, T = 2 pi m / omega
// (m = 1: harmonic response; m > 1: a subharmonic), and the time origin:
// there is no phase condition and the period is not an unknown. Unknowns
// (u0, v0) at t = 0; equations x(T) - x0 = 0, a square system whose
// Jacobian is X - I (X the monodromy), solved by the damped Gauss-Newton
// loop of the periodic solvers. Within one region the flow is affine in x0,
// so an orbit that never switches (the linear limit) converges in one step.
//
// For continuation in omega or in the load amplitude (not here): a point is
// the fixed point of forced_period_map for the ExactFlow of that excitation;
// the parameter derivative of the map is what a bordered corrector adds.
#pragma once

#include "periodic/exact_flow.hpp"
#include "periodic/gauss_newton.hpp"
#include "periodic/periodic_orbit.hpp"

namespace nbm {

struct ForcedShootingOptions {
  int subharmonic = 1;  ///< m: the period is 2 pi m / omega
  double tolerance = 1e-12;  ///< on the periodicity residual (periodic_orbit.hpp)
  int max_iterations = periodic_max_iterations;
  /// Periods of the exact flow run from the guess before Newton starts: for
  /// a stable orbit, a cheap way into Newton's basin (the period map is only
  /// piecewise smooth, and a guess across a grazing boundary can stall it).
  int transient_periods = 0;
};

/// The period of the forced orbit: 2 pi m / omega. Throws InputError if the
/// flow has no harmonic load or m < 1.
double forced_period(const ExactFlow& flow, int subharmonic);

/// Newton from the guess (u0, v0) at t = 0; the returned orbit is analysed
/// with analyse_orbit(flow, orbit, false): Floquet multipliers without a
/// trivial one, stable if all |mu| < 1. Throws InputError on a bad guess or
/// option, NumericalError if Newton does not converge.
PeriodicOrbit shoot_forced(const ExactFlow& flow, const Vector& u0, const Vector& v0,
                           const ForcedShootingOptions& options = {});

}  // namespace nbm
