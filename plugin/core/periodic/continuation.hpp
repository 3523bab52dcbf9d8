// Pseudo-arclength continuation of a family of periodic orbits (method.md
// §6: nonsmooth modes as curves of orbits), on top of shooting: secant
// predictor, corrector with the arclength condition of ShootingOptions.
// Unlike a natural parameter (amplitude, energy, period), the arclength
// follows a family through folds of that parameter.
#pragma once

#include "periodic/shooting.hpp"

namespace nbm {

struct ContinuationOptions {
  /// Step length in the scaled unknowns (u0 / length, v0 / velocity, T / time).
  double step = 0.01;
  double length = 1, velocity = 1, time = 1;  ///< scales of the unknowns
};

/// The orbit at distance `options.step` beyond `last` along the family
/// through `previous` and `last` (two nearby orbits of it). `shooting`
/// supplies probe, half_period, tolerance and iterations; its amplitude
/// condition is replaced by the arclength one. Throws NumericalError if the
/// corrector does not converge (retry with a shorter step).
PeriodicOrbit continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                const PeriodicOrbit& last, ShootingOptions shooting,
                                const ContinuationOptions& options);

/// continuation_step with options.step, and where the corrector fails with
/// step/4, step/16 and step/64: the period map is only piecewise smooth, and
/// near a switch appearing or a branch point shorter steps follow. Returns
/// the orbit; `used` is the step that converged. Throws the NumericalError
/// of the last attempt if none converges.
PeriodicOrbit shortening_continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                           const PeriodicOrbit& last,
                                           const ShootingOptions& shooting,
                                           const ContinuationOptions& options, double& used);

}  // namespace nbm
