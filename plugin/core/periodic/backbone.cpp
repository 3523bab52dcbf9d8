#include "periodic/backbone.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// Vibration energy of an orbit: total energy minus the static state's.
double vibration_energy(const ReducedField& field, const GrazingOrbit& g,
                        const PeriodicOrbit& orbit) {
  const Vector rest = Vector::Zero(g.static_state.size());
  return orbit.energy_start(3) - field.energies(g.static_state, rest)(3);
}

// Vibration energy and amplitude of an orbit about the static state.
BackbonePoint point_of(const ReducedField& field, const GrazingOrbit& g, PeriodicOrbit orbit) {
  BackbonePoint p;
  p.energy = vibration_energy(field, g, orbit);
  p.amplitude = (orbit.u0 - g.static_state).cwiseAbs().maxCoeff();
  p.orbit = std::move(orbit);
  return p;
}

void add_event(std::string& events, const std::string& name) {
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
// family fails (method.md §6). With mass on the contact nodes the family
// leaves grazing with a vertical tangent, T - T_g ~ sqrt(A - A_g), so the
// corrector on the hyperplane across the linear direction meets that square
// root (on the clamped plate's bending mode it fails down to step/64). With
// the massless boundary the first step fails where many contact nodes graze
// within a small amplitude range (the 3D blade's flat tip: each retried
// step still crosses several grazings). Either way an orbit at the fixed
// period T_g (1 - eps) (the obstacle stiffens the system), from the linear
// orbit at 1.1 a, for eps = 3e-3, 1e-2, 1e-3 in turn; the first with
// contact, or none.
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

// The backbone as a family for the driver: distances scaled by the last
// orbit's vibration amplitude about the static state and its period; it
// ends past the energy limit, or at an orbit without contact after the
// first (no switch and no closed contact: an orbit of the open, linear
// system again; no switch with a contact closed throughout is an orbit of a
// closed region, and the family goes on).
class BackboneFamily : public OrbitFamily {
 public:
  BackboneFamily(const ReducedField& field, const GrazingOrbit& g, const ShootingOptions& s,
                 double max_energy)
      : OrbitFamily(field, s,
                    [&g](const Vector& u0, double period) {
                      FamilyScales c;
                      c.length = (u0 - g.static_state).cwiseAbs().maxCoeff();
                      c.time = period;
                      c.velocity = c.length * 2 * M_PI / c.time;
                      return c;
                    }),
        g_(g), max_energy_(max_energy) {}

  std::string end(const std::vector<PeriodicOrbit>& orbits) const override {
    const PeriodicOrbit& last = orbits.back();
    if (orbits.size() > 1 && last.switches.empty() && last.contact_time == 0)
      return "the family reached an orbit without contact (back on the linear system)";
    const double energy = vibration_energy(field(), g_, last);
    if (energy > max_energy_)
      return "energy: the last orbit's energy " + str(energy) + " exceeds " + str(max_energy_);
    return {};
  }

 private:
  const GrazingOrbit& g_;
  double max_energy_;
};

// The "tongue[j:r]" event of a frequency skipped by the frequency branch:
// the open system's mode j whose frequency is nearest (relative to it) an
// integer multiple k >= 2 of omega, and r = omega_j / omega. A guide to
// the internal resonance there, not a proof of it (the nonsmooth orbit's
// harmonics meet the modes of the regions it visits, which the open ones
// only approximate).
std::string tongue_event(const Vector& omega_open, double omega) {
  Index best = -1;
  double distance = std::numeric_limits<double>::infinity();
  for (Index j = 0; j < omega_open.size(); ++j) {
    const double r = omega_open(j) / omega, k = std::max(2.0, std::round(r));
    if (std::abs(r - k) / k < distance) distance = std::abs(r - k) / k, best = j;
  }
  if (best < 0) return "tongue";
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.3f", omega_open(best) / omega);
  return "tongue[" + std::to_string(best) + ":" + ratio + "]";
}

// The frequency branch (BackboneOptions::Branch::frequency, method.md §6
// "The primary branch"): from the last orbit, orbits at fixed periods at
// frequencies raised by frequency_step per step; tongue orbits (an energy
// jump beyond energy_jump) and failed correctors skipped, up to max_skips
// in a row. Appends to `orbits` (and, per orbit, its tongue events to
// `events`); returns why it stopped.
std::string frequency_branch(const ReducedField& field, const GrazingOrbit& g, ShootingOptions s,
                             const BackboneOptions& o, const BackboneFamily& family,
                             std::vector<PeriodicOrbit>& orbits,
                             std::vector<std::string>& events) {
  s.kind = ShootingOptions::Amplitude::period;
  const auto open = field.region(ActiveSet(static_cast<std::size_t>(field.n_contact()), false));
  const Vector omega_open = open->omega2.cwiseMax(0).cwiseSqrt();
  int skips = 0;
  std::string skipped, why;
  while (static_cast<long>(orbits.size()) < o.points) {
    const PeriodicOrbit& last = orbits.back();
    const double energy = vibration_energy(field, g, last);
    const double omega = 2 * M_PI / last.period * (1 + o.frequency_step * (1 + skips));
    if (omega > o.max_omega)
      return "frequency: the next orbit's omega " + str(omega) + " exceeds " + str(o.max_omega);
    s.amplitude = 2 * M_PI / omega;
    // Secant predictor in the frequency from the last two orbits; after a
    // skip the last orbit itself (the secant's reach grows with the step).
    const PeriodicOrbit& before = orbits[orbits.size() - 2];
    const double w_last = 2 * M_PI / last.period, w_before = 2 * M_PI / before.period;
    const double r =
        skips == 0 && w_last > w_before ? (omega - w_last) / (w_last - w_before) : 0;
    const Vector u = last.u0 + r * (last.u0 - before.u0), v = last.v0 + r * (last.v0 - before.v0);
    try {
      PeriodicOrbit next = shoot(field, u, v, s.amplitude, s);
      const double jump = std::abs(vibration_energy(field, g, next) / energy - 1);
      if (jump <= o.energy_jump * (1 + skips)) {
        orbits.push_back(std::move(next));
        events.push_back(skipped);
        skipped.clear();
        skips = 0;
        if (std::string end = family.end(orbits); !end.empty()) return end;
        continue;
      }
      why = "the orbit at omega " + str(omega) + " changed the energy by " + str(jump) +
            " of the last one's";
    } catch (const NumericalError& e) {
      why = "at omega " + str(omega) + ": " + e.what();
    }
    add_event(skipped, tongue_event(omega_open, omega));
    if (++skips > o.max_skips)
      return "frequency: no orbit of the branch at " + std::to_string(skips) +
             " frequencies in a row after omega " + str(2 * M_PI / last.period) + " (last: " +
             why + ")";
  }
  return "points: " + std::to_string(o.points) + " orbits computed";
}

// Why an arclength backbone stopped.
std::string stop_reason(const ArclengthCurve<PeriodicOrbit>& curve, const BackboneOptions& o) {
  switch (curve.stop) {
    case ArclengthStop::max_points:
      return "points: " + std::to_string(o.points) + " orbits computed";
    case ArclengthStop::step_too_small:
      return "the corrector failed at step " + str(o.step / 64) + " after orbit " +
             std::to_string(curve.points.size() - 1) + ": " + curve.reason;
    case ArclengthStop::ended:
    case ArclengthStop::bound:  // no bound on a backbone
      break;
  }
  return curve.reason;
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
  if (o.branch == BackboneOptions::Branch::frequency) {
    if (!(o.frequency_step > 0) || !std::isfinite(o.frequency_step))
      throw InputError("frequencyStep: expected a finite relative step > 0, got " +
                       str(o.frequency_step));
    if (!(o.energy_jump > 0) || !std::isfinite(o.energy_jump))
      throw InputError("energyJump: expected a finite relative bound > 0, got " +
                       str(o.energy_jump));
    if (o.max_skips < 0)
      throw InputError("skips: expected >= 0, got " + std::to_string(o.max_skips));
    if (!(o.max_omega > 0))
      throw InputError("to: expected a frequency > 0, got " + str(o.max_omega));
  }
  Backbone b;
  b.grazing = grazing_orbit(field, mode);
  const GrazingOrbit& g = b.grazing;
  b.points.push_back(point_of(field, g, g.orbit));
  ShootingOptions shooting;
  shooting.probe = g.probe;
  shooting.half_period = o.half_period;
  shooting.max_iterations = o.max_iterations;
  const BackboneFamily family(field, g, shooting, o.max_energy);
  // The first secant: from the linear orbit at half the amplitude, on the
  // same affine family u0 = u_s + s a phi, v0 = 0, T = 2 pi / omega.
  PeriodicOrbit previous;
  previous.u0 = 0.5 * (g.static_state + g.orbit.u0);
  previous.v0 = g.orbit.v0;
  previous.period = g.orbit.period;
  ArclengthCurve<PeriodicOrbit> curve;
  curve.points.push_back(g.orbit);
  curve.nodes.push_back(family.node(previous, g.orbit));
  // Fixed steps in the last orbit's scales; a failed one is retried with
  // step/4, step/16 and step/64, and the next goes back to `step`.
  ArclengthOptions a;
  a.step = a.max_step = o.step;
  a.min_step = o.step / 64;
  a.shrink = 4;
  a.growth = 64;
  a.easy_iterations = std::numeric_limits<int>::max();
  // The first step takes the linear family's direction, which is not the
  // nonsmooth family's tangent (with mass on the contact nodes that one is
  // vertical: the corrected point lies far from the predictor); where it
  // fails, the fixed-period start above. From the
  // second on, a point farther than twice the step jumped to another branch
  // (round-off can decide where an unguarded corrector lands).
  a.max_points = static_cast<int>(std::min<long>(o.points, 2));
  continue_curve(family, a, curve);
  if (curve.stop == ArclengthStop::step_too_small && curve.points.size() == 1) {
    if (std::optional<PeriodicOrbit> start = vertical_start(field, g, shooting)) {
      curve.nodes.push_back(family.node(g.orbit, *start));
      curve.points.push_back(std::move(*start));
    } else {
      curve.reason += " (and no orbit at the fixed periods of the vertical start)";
    }
  }
  std::vector<std::string> tongues(curve.points.size());
  if (curve.points.size() == 2 && o.branch == BackboneOptions::Branch::frequency) {
    b.stop_reason = frequency_branch(field, g, shooting, o, family, curve.points, tongues);
  } else {
    if (curve.points.size() == 2) {
      a.max_points = static_cast<int>(std::min<long>(o.points, std::numeric_limits<int>::max()));
      a.max_jump = 2;
      continue_curve(family, a, curve);
    }
    b.stop_reason = stop_reason(curve, o);
  }
  for (std::size_t k = 1; k < curve.points.size(); ++k)
    b.points.push_back(point_of(field, g, std::move(curve.points[k])));
  mark_events(b.points);
  for (std::size_t k = 0; k < tongues.size() && k < b.points.size(); ++k)
    if (!tongues[k].empty()) add_event(b.points[k].events, tongues[k]);
  return b;
}

}  // namespace nbm
