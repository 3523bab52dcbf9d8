// Families of autonomous periodic orbits (method.md §6: nonsmooth modes as
// curves of orbits) as curves for the arclength driver
// (arclength_continuation.hpp): unknowns (u0, v0, T), corrector by shooting
// with the arclength condition in place of the amplitude one, secant
// tangents. Unlike a natural parameter (amplitude, energy, period), the
// arclength follows a family through folds of that parameter.
#pragma once

#include <functional>

#include "periodic/arclength_continuation.hpp"
#include "periodic/shooting.hpp"

namespace nbm {

/// Scales of the unknowns of a family at one orbit: distances are measured
/// in (u0 / length, v0 / velocity, T / time).
struct FamilyScales {
  double length = 1, velocity = 1, time = 1;
};

class OrbitFamily : public ArclengthProblem<PeriodicOrbit> {
 public:
  using Scaling = std::function<FamilyScales(const Vector& u0, double period)>;
  /// `shooting` supplies probe, half_period, tolerance and iterations; its
  /// amplitude condition is replaced by the arclength one.
  OrbitFamily(const ReducedField& field, ShootingOptions shooting, Scaling scaling);

  /// (u0, v0, T) of an orbit of this field (InputError on a size mismatch).
  Vector unknowns(const PeriodicOrbit& orbit) const;
  /// The curve's first node at `last`, with the secant from `previous` as
  /// its tangent (InputError if the two orbits coincide).
  ArclengthNode node(const PeriodicOrbit& previous, const PeriodicOrbit& last) const;

  Vector weights(const Vector& y) const override;
  ArclengthCorrection<PeriodicOrbit> correct(const Vector& guess, const Vector& border,
                                             double target,
                                             const ArclengthNode& from) const override;

 protected:
  const ReducedField& field() const { return field_; }

 private:
  const ReducedField& field_;
  ShootingOptions shooting_;
  Scaling scaling_;
};

struct ContinuationOptions {
  /// Step length in the scaled unknowns (u0 / length, v0 / velocity, T / time).
  double step = 0.01;
  double length = 1, velocity = 1, time = 1;  ///< scales of the unknowns
};

/// The orbit at distance `options.step` beyond `last` along the family
/// through `previous` and `last` (two nearby orbits of it): one step of the
/// driver. Throws NumericalError if the corrector does not converge (retry
/// with a shorter step).
PeriodicOrbit continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                const PeriodicOrbit& last, const ShootingOptions& shooting,
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
