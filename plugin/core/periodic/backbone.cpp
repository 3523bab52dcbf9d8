#include "periodic/backbone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// A mode component whose size is below this fraction of the largest
// component of phi^T f (static load) or of |H| |phi| (normal motion of the
// contact nodes) is round-off.
constexpr double kRoundOff = 1e-12;

std::string str(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// K_S u_s = f_S on the open region, modally: the load must not move a rigid
// mode (a free body under a load has no static state).
Vector static_state(const Region& open) {
  const Vector p = open.modes.transpose() * open.f;
  const double scale = p.cwiseAbs().maxCoeff();
  Vector q = Vector::Zero(p.size());
  for (Index k = 0; k < p.size(); ++k) {
    if (open.omega2(k) > 0)
      q(k) = p(k) / open.omega2(k);
    else if (std::abs(p(k)) > kRoundOff * scale)
      throw InputError("F: the load moves rigid-body mode " + std::to_string(k) +
                       " of the open system: there is no static state to start a backbone from");
  }
  return open.modes * q;
}

// Vibration energy and amplitude of an orbit about the static state.
BackbonePoint point_of(const ReducedField& field, const GrazingOrbit& g, PeriodicOrbit orbit) {
  BackbonePoint p;
  const Vector rest = Vector::Zero(g.static_state.size());
  p.energy = orbit.energy_start(3) - field.energies(g.static_state, rest)(3);
  p.amplitude = (orbit.u0 - g.static_state).cwiseAbs().maxCoeff();
  p.orbit = std::move(orbit);
  return p;
}

void add_event(std::string& events, const char* name) {
  if (!events.empty()) events += ' ';
  events += name;
}

// Events between consecutive orbits (BackbonePointReport::events): a turn
// of the frequency or of the energy at an interior point, a change of the
// number of switches (a contact touched or left in between) or of stability.
void mark_events(std::vector<BackbonePoint>& points) {
  auto turns = [&](std::size_t k, auto value) {
    const double before = value(points[k]) - value(points[k - 1]);
    return before * (value(points[k + 1]) - value(points[k])) < 0;
  };
  auto frequency = [](const BackbonePoint& p) { return 1 / p.orbit.period; };
  auto energy = [](const BackbonePoint& p) { return p.energy; };
  add_event(points[0].events, "grazing");
  for (std::size_t k = 1; k < points.size(); ++k) {
    const PeriodicOrbit &a = points[k - 1].orbit, &b = points[k].orbit;
    if (a.switches.size() != b.switches.size()) add_event(points[k].events, "grazing");
    if (k + 1 < points.size() && turns(k, frequency))
      add_event(points[k].events, "fold-frequency");
    if (k + 1 < points.size() && turns(k, energy)) add_event(points[k].events, "fold-energy");
    if (a.stable != b.stable) add_event(points[k].events, "stability");
  }
}

// The first orbit past grazing when the first step along the linear
// family fails, with mass on the contact nodes (method.md §6): the family
// leaves grazing with a vertical tangent, T - T_g ~ sqrt(A - A_g), so the
// corrector on the hyperplane across the linear direction meets that square
// root (on the clamped plate's bending mode it fails down to step/64). The
// tangent is the period's direction: an orbit at the fixed period
// T_g (1 - eps) (the obstacle stiffens the system), from the linear orbit at
// 1.1 a, for eps = 3e-3, 1e-2, 1e-3 in turn; the first with contact, or none.
std::optional<PeriodicOrbit> vertical_start(const ReducedField& field, const GrazingOrbit& g,
                                            ShootingOptions s) {
  s.kind = ShootingOptions::Amplitude::period;
  const Vector guess = g.static_state + 1.1 * (g.orbit.u0 - g.static_state);
  for (double eps : {3e-3, 1e-2, 1e-3}) {
    s.amplitude = g.orbit.period * (1 - eps);
    try {
      PeriodicOrbit o = shoot(field, guess, g.orbit.v0, s.amplitude, s);
      if (!o.switches.empty() || o.contact_time > 0) return o;
    } catch (const NumericalError&) {
      // the next eps
    }
  }
  return std::nullopt;
}

}  // namespace

GrazingOrbit grazing_orbit(const ReducedField& field, Index mode) {
  const Index n = field.size(), nc = field.n_contact();
  if (nc == 0)
    throw InputError("contacts: the model has no contact node; a backbone starts where a mode "
                     "grazes the obstacle");
  for (Index k = 0; k < nc; ++k)
    if (!(field.gaps()(k) > 0))
      throw InputError("gaps: contact " + std::to_string(k) + " has gap " +
                       str(field.gaps()(k)) +
                       "; a backbone from grazing needs every gap > 0 (the contacts open at rest)");
  if (mode < 0 || mode >= n)
    throw InputError("mode: " + std::to_string(mode) + " out of range [0, " + std::to_string(n) +
                     ") (the modes of the open system, by increasing frequency)");
  const auto open_held = field.region(ActiveSet(static_cast<std::size_t>(nc), false));
  const Region& open = *open_held;
  if (!(open.omega2(mode) > 0))
    throw InputError("mode: " + std::to_string(mode) +
                     " is a rigid-body mode (frequency 0): it has no periodic orbit");

  GrazingOrbit g;
  g.static_state = static_state(open);
  g.mode = open.modes.col(mode);
  g.omega = std::sqrt(open.omega2(mode));
  const Vector h_s = open.H * g.static_state + open.d;
  for (Index k = 0; k < nc; ++k)
    if (!(h_s(k) > 0))
      throw InputError("F: the static state under the load closes contact " + std::to_string(k) +
                       " (gap " + str(h_s(k)) +
                       "); a backbone from grazing starts from an open static state");
  // The gaps along the mode's orbits (see the header): a = min_k h_s,k / |G_k|.
  const Vector G = open.H * g.mode;
  const Vector size = open.H.cwiseAbs() * g.mode.cwiseAbs();
  if (!(G.cwiseAbs().maxCoeff() > kRoundOff * size.maxCoeff()))
    throw InputError("mode: " + std::to_string(mode) +
                     " does not move any contact node along its normal: its orbits never graze");
  g.amplitude = std::numeric_limits<double>::infinity();
  for (Index k = 0; k < nc; ++k)
    if (std::abs(G(k)) > kRoundOff * size.maxCoeff() && h_s(k) / std::abs(G(k)) < g.amplitude)
      g.amplitude = h_s(k) / std::abs(G(k)), g.contact = k;
  const double s = G(g.contact) > 0 ? 1 : -1;
  g.mode.cwiseAbs().maxCoeff(&g.probe);
  g.orbit.u0 = g.static_state + (s * g.amplitude) * g.mode;
  g.orbit.v0 = Vector::Zero(n);
  g.orbit.period = 2 * M_PI / g.omega;
  analyse_orbit(field, g.orbit);
  return g;
}

Backbone backbone(const ReducedField& field, Index mode, const BackboneOptions& o) {
  if (o.points < 1) throw InputError("points: expected >= 1, got " + std::to_string(o.points));
  if (!(o.step > 0) || !std::isfinite(o.step))
    throw InputError("step: expected a finite step > 0, got " + str(o.step));
  if (!(o.max_energy > 0))
    throw InputError("energy: expected a limit > 0, got " + str(o.max_energy));
  if (o.max_iterations < 1) throw InputError("iterations: expected >= 1");
  Backbone b;
  b.grazing = grazing_orbit(field, mode);
  const GrazingOrbit& g = b.grazing;
  b.points.push_back(point_of(field, g, g.orbit));

  ShootingOptions shooting;
  shooting.probe = g.probe;
  shooting.half_period = o.half_period;
  shooting.max_iterations = o.max_iterations;
  // The first secant: from the linear orbit at half the amplitude, on the
  // same affine family u0 = u_s + s a phi, v0 = 0, T = 2 pi / omega.
  PeriodicOrbit previous;
  previous.u0 = 0.5 * (g.static_state + g.orbit.u0);
  previous.v0 = g.orbit.v0;
  previous.period = g.orbit.period;
  b.stop_reason = "points: " + std::to_string(o.points) + " orbits computed";
  while (static_cast<long>(b.points.size()) < o.points) {
    const BackbonePoint& last = b.points.back();
    if (last.energy > o.max_energy) {
      b.stop_reason = "energy: the last orbit's energy " + str(last.energy) + " exceeds " +
                      str(o.max_energy);
      break;
    }
    ContinuationOptions c;
    c.step = o.step;
    c.length = last.amplitude;
    c.time = last.orbit.period;
    c.velocity = c.length * 2 * M_PI / c.time;
    PeriodicOrbit next;
    try {
      double used;
      next = shortening_continuation_step(field, previous, last.orbit, shooting, c, used);
    } catch (const NumericalError& e) {
      std::optional<PeriodicOrbit> start;
      if (b.points.size() == 1 && !field.massless_boundary())
        start = vertical_start(field, g, shooting);
      if (start) {
        previous = g.orbit;
        b.points.push_back(point_of(field, g, std::move(*start)));
        continue;
      }
      b.stop_reason = "the corrector failed at step " + str(o.step / 64) + " after orbit " +
                      std::to_string(b.points.size() - 1) + ": " + e.what() +
                      (b.points.size() == 1 && !field.massless_boundary()
                           ? " (and no orbit at the fixed periods of the vertical start)"
                           : "");
      break;
    }
    previous = last.orbit;
    b.points.push_back(point_of(field, g, std::move(next)));
    // No switch and no contact: an orbit of the open (linear) system again.
    // (No switch with a contact closed throughout is an orbit of a closed
    // region: the family goes on.)
    const PeriodicOrbit& added = b.points.back().orbit;
    if (added.switches.empty() && added.contact_time == 0) {
      b.stop_reason = "the family reached an orbit without contact (back on the linear system)";
      break;
    }
  }
  mark_events(b.points);
  return b;
}

}  // namespace nbm
