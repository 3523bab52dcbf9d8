#include "periodic/continuation.hpp"

#include <string>

#include "base/errors.hpp"

namespace nbm {

PeriodicOrbit continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                const PeriodicOrbit& last, ShootingOptions shooting,
                                const ContinuationOptions& c) {
  const Index n = field.size();
  if (!(c.step > 0) || !(c.length > 0) || !(c.velocity > 0) || !(c.time > 0))
    throw InputError("continuation: step and scales must be > 0");
  auto unknowns = [n](const PeriodicOrbit& p) {
    if (p.u0.size() != n || p.v0.size() != n)
      throw InputError("continuation: orbit of size " + std::to_string(p.u0.size()) +
                       ", expected " + std::to_string(n) + " interior dofs");
    Vector y(2 * n + 1);
    y << p.u0, p.v0, p.period;
    return y;
  };
  Vector scale(2 * n + 1);  // scaled unknowns: scale .* y
  scale << Vector::Constant(n, 1 / c.length), Vector::Constant(n, 1 / c.velocity), 1 / c.time;
  const Vector last_y = unknowns(last);
  Vector secant = scale.cwiseProduct(last_y - unknowns(previous));
  if (!(secant.norm() > 0))
    throw InputError("continuation: the two orbits coincide; no direction to continue in");
  secant.normalize();
  // Predictor: step along the secant; corrector: on the hyperplane through
  // the predictor orthogonal to the secant (in the scaled unknowns).
  const Vector predictor = last_y + c.step * secant.cwiseQuotient(scale);
  shooting.arclength = ShootingOptions::Arclength{scale.cwiseProduct(secant), predictor};
  return shoot(field, predictor.head(n), predictor.segment(n, n), predictor(2 * n), shooting);
}

PeriodicOrbit shortening_continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                           const PeriodicOrbit& last,
                                           const ShootingOptions& shooting,
                                           const ContinuationOptions& options, double& used) {
  ContinuationOptions c = options;
  for (;; c.step /= 4) {
    try {
      PeriodicOrbit next = continuation_step(field, previous, last, shooting, c);
      used = c.step;
      return next;
    } catch (const NumericalError&) {
      if (c.step < options.step / 60) throw;
    }
  }
}

}  // namespace nbm
