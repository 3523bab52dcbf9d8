#include "periodic/continuation.hpp"

#include <string>
#include <utility>

#include "base/errors.hpp"

namespace nbm {

OrbitFamily::OrbitFamily(const ReducedField& field, ShootingOptions shooting, Scaling scaling)
    : field_(field), shooting_(std::move(shooting)), scaling_(std::move(scaling)) {}

Vector OrbitFamily::unknowns(const PeriodicOrbit& p) const {
  const Index n = field_.size();
  if (p.u0.size() != n || p.v0.size() != n)
    throw InputError("continuation: orbit of size " + std::to_string(p.u0.size()) +
                     ", expected " + std::to_string(n) + " interior dofs");
  Vector y(2 * n + 1);
  y << p.u0, p.v0, p.period;
  return y;
}

ArclengthNode OrbitFamily::node(const PeriodicOrbit& previous, const PeriodicOrbit& last) const {
  ArclengthNode k;
  k.y = unknowns(last);
  k.tangent = k.y - unknowns(previous);
  if (!(weights(k.y).cwiseProduct(k.tangent).norm() > 0))
    throw InputError("continuation: the two orbits coincide; no direction to continue in");
  k.iterations = last.iterations;
  return k;
}

Vector OrbitFamily::weights(const Vector& y) const {
  const Index n = field_.size();
  const FamilyScales s = scaling_(y.head(n), y(2 * n));
  if (!(s.length > 0) || !(s.velocity > 0) || !(s.time > 0))
    throw InputError("continuation: the scales of the unknowns must be > 0");
  Vector w(2 * n + 1);
  w << Vector::Constant(n, 1 / s.length), Vector::Constant(n, 1 / s.velocity), 1 / s.time;
  return w;
}

ArclengthCorrection<PeriodicOrbit> OrbitFamily::correct(const Vector& guess, const Vector& border,
                                                        double target,
                                                        const ArclengthNode&) const {
  // Shooting's arclength condition border . (y - anchor) = 0, anchored at the
  // projection of the guess on the hyperplane.
  const Index n = field_.size();
  ShootingOptions s = shooting_;
  const Vector anchor = guess + ((target - border.dot(guess)) / border.squaredNorm()) * border;
  s.arclength = ShootingOptions::Arclength{border, anchor};
  ArclengthCorrection<PeriodicOrbit> c;
  c.point = shoot(field_, guess.head(n), guess.segment(n, n), guess(2 * n), s);
  c.y = unknowns(c.point);
  c.iterations = c.point.iterations;
  return c;  // no tangent: the driver takes the secant
}

namespace {

PeriodicOrbit one_step(const ReducedField& field, const PeriodicOrbit& previous,
                       const PeriodicOrbit& last, const ShootingOptions& shooting,
                       const ContinuationOptions& c, double min_step, double& used) {
  if (!(c.step > 0) || !(c.length > 0) || !(c.velocity > 0) || !(c.time > 0))
    throw InputError("continuation: step and scales must be > 0");
  const FamilyScales scales{c.length, c.velocity, c.time};
  const OrbitFamily family(field, shooting, [scales](const Vector&, double) { return scales; });
  ArclengthCurve<PeriodicOrbit> curve;
  curve.nodes.push_back(family.node(previous, last));
  curve.points.push_back(last);
  ArclengthOptions o;
  o.step = o.max_step = c.step;
  o.min_step = min_step;
  o.shrink = 4;
  o.max_points = 2;
  continue_curve(family, o, curve);
  if (curve.stop == ArclengthStop::step_too_small) throw NumericalError(curve.reason);
  used = curve.nodes.back().step;
  return std::move(curve.points.back());
}

}  // namespace

PeriodicOrbit continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                const PeriodicOrbit& last, const ShootingOptions& shooting,
                                const ContinuationOptions& options) {
  double used;
  return one_step(field, previous, last, shooting, options, options.step, used);
}

PeriodicOrbit shortening_continuation_step(const ReducedField& field, const PeriodicOrbit& previous,
                                           const PeriodicOrbit& last,
                                           const ShootingOptions& shooting,
                                           const ContinuationOptions& options, double& used) {
  return one_step(field, previous, last, shooting, options, options.step / 64, used);
}

}  // namespace nbm
