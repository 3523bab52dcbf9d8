// The one pseudo-arclength continuation driver of the periodic tools
// (method.md §6, "Continuation"): autonomous families, backbones from
// grazing and forced responses are curves y(s) of solutions of a system with
// one equation fewer than unknowns, and every one of them is followed by
// this loop: predictor along the tangent, corrector on the hyperplane across
// it at the step length, step control (shrink on failure, growth after easy
// correctors, rejection of jumps to another branch and of sharp turns),
// bounds on one unknown, and events located by bisection on the arclength.
//
// What a curve is -- its unknowns, its corrector, its analysed points and
// their event indicators -- belongs to the problem (ArclengthProblem); the
// driver knows none of it. Distances are measured in weighted unknowns
// w .* y, the weights given by the problem at the point a step starts from
// (constant for a forced response, the last orbit's amplitude and period
// along a backbone).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "base/types.hpp"

namespace nbm {

struct ArclengthOptions {
  /// Steps in the weighted unknowns: the first, and the bounds step control
  /// keeps within.
  double step = 0.02, min_step = 1e-5, max_step = 0.2;
  /// A failed step (the corrector, a jump, a turn) is retried with
  /// step / shrink; below min_step the curve ends.
  double shrink = 2;
  /// After a corrector of at most easy_iterations, the next step is
  /// min(step * growth, max_step).
  double growth = 1.5;
  int easy_iterations = 3;
  /// A corrected point farther than max_jump * step from the one the step
  /// started from jumped to another branch: rejected.
  double max_jump = std::numeric_limits<double>::infinity();
  /// Largest angle (radians) between consecutive tangents: a corrector
  /// that converged back onto the part already followed turns by about pi.
  double max_turn = M_PI;
  int max_points = 200;  ///< including the first point
  /// The unknown y(bounded) is held in [lower, upper]: a step that leaves
  /// lands on the bound (corrector on y(bounded) = bound) and ends the
  /// curve. -1: no bound.
  Index bounded = -1;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  /// Events are bracketed between consecutive points and, if locate_events,
  /// bisected on the arclength down to event_tolerance.
  bool locate_events = true;
  double event_tolerance = 1e-8;
  int max_bisections = 60;
};

/// A corrected point as the driver keeps it.
struct ArclengthNode {
  Vector y;        ///< the problem's unknowns
  Vector tangent;  ///< along the curve, away from the previous point (any length)
  double arclength = 0;  ///< weighted, from the first point
  double step = 0;       ///< the step that reached it (0 for the first point)
  int iterations = 0;    ///< of its corrector
};

template <class Point>
struct ArclengthCorrection {
  Vector y;
  /// The tangent at y, oriented along the secant from the node the step
  /// started from (or along that node's tangent if y is that node); empty:
  /// the driver takes the secant itself.
  Vector tangent;
  int iterations = 0;
  Point point;  ///< the analysed point at y
};

/// A curve for the driver: its corrector and what it knows of its points.
template <class Point>
class ArclengthProblem {
 public:
  virtual ~ArclengthProblem() = default;
  /// Weights of the unknowns for a step from y (distances are |w .* dy|).
  virtual Vector weights(const Vector& y) const { return Vector::Ones(y.size()); }
  /// Newton onto the curve from `guess` with the extra equation
  /// border . y = target; `from` is the node the step started from. Throws
  /// NumericalError if it does not converge.
  virtual ArclengthCorrection<Point> correct(const Vector& guess, const Vector& border,
                                             double target, const ArclengthNode& from) const = 0;
  /// Integer indicators of the events 0 .. event_kinds() - 1 at a point: an
  /// event lies between two points where happened() (by default: where the
  /// indicators differ).
  virtual int event_kinds() const { return 0; }
  virtual int indicator(int /*kind*/, const Point& /*point*/) const { return 0; }
  virtual bool happened(int kind, const Point& a, const Point& b) const {
    return indicator(kind, a) != indicator(kind, b);
  }
  /// Non-empty: the curve ends at its last point, for this reason (asked
  /// before every step).
  virtual std::string end(const std::vector<Point>& /*points*/) const { return {}; }
};

/// An event between points[point] and points[point + 1]: its indicator
/// changes within the arclength bracket (lo, hi] along the tangent of
/// points[point] (0 and `span` before bisection).
template <class Point>
struct ArclengthEvent {
  int kind = 0;
  Index point = 0;
  double lo = 0, hi = 0, span = 0;
  bool bisected = false;  ///< false: bisection off, or a corrector failed in it
  Point past;             ///< the corrected point nearest past the event
};

enum class ArclengthStop {
  max_points,     ///< max_points reached
  bound,          ///< the last point is on a bound of y(bounded)
  step_too_small, ///< every step down to min_step failed (`reason`: the last failure)
  ended           ///< the problem ended the curve (`reason`: its reason)
};

template <class Point>
struct ArclengthCurve {
  std::vector<Point> points;
  std::vector<ArclengthNode> nodes;  ///< one per point
  std::vector<ArclengthEvent<Point>> events;
  ArclengthStop stop = ArclengthStop::max_points;
  std::string reason;
};

namespace detail {

inline std::string number(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// The unit tangent of node k in the weights w.
inline Vector unit_tangent(const Vector& w, const Vector& tangent) {
  return tangent / w.cwiseProduct(tangent).norm();
}

template <class Point>
ArclengthCorrection<Point> correct(const ArclengthProblem<Point>& problem, const ArclengthNode& k,
                                   const Vector& guess, const Vector& border, double target) {
  ArclengthCorrection<Point> c = problem.correct(guess, border, target, k);
  if (c.tangent.size() == 0) c.tangent = c.y - k.y;
  return c;
}

// The row b of the hyperplanes across the tangent of a node in the weights
// w: <t, y - y_k>_w = b . (y - y_k), b = w.^2 .* t, t the weighted unit
// tangent.
inline Vector border_row(const Vector& w, const Vector& tangent) {
  return w.cwiseAbs2().cwiseProduct(unit_tangent(w, tangent));
}

// The corrected point at arclength sigma along the tangent of node k, whose
// border row is `border`.
template <class Point>
ArclengthCorrection<Point> at(const ArclengthProblem<Point>& problem, const ArclengthNode& k,
                              const Vector& border, double sigma, const Vector& guess) {
  return correct(problem, k, guess, border, border.dot(k.y) + sigma);
}

// Events between points k and k + 1, bracketed and (if asked) bisected.
template <class Point>
void locate_events(const ArclengthProblem<Point>& problem, const ArclengthOptions& o,
                   ArclengthCurve<Point>& curve, Index k) {
  const ArclengthNode &a = curve.nodes[k], &b = curve.nodes[k + 1];
  const Point &pa = curve.points[k], &pb = curve.points[k + 1];
  const Vector border = border_row(problem.weights(a.y), a.tangent);
  const double span = border.dot(b.y - a.y);
  for (int kind = 0; kind < problem.event_kinds(); ++kind) {
    if (!problem.happened(kind, pa, pb)) continue;
    ArclengthEvent<Point> e{kind, k, 0, span, span, o.locate_events, pb};
    const int left = problem.indicator(kind, pa);
    for (int it = 0; e.bisected && e.hi - e.lo > o.event_tolerance; ++it) {
      if (it >= o.max_bisections) {
        e.bisected = false;
        break;
      }
      const double mid = 0.5 * (e.lo + e.hi);
      try {
        ArclengthCorrection<Point> c =
            at(problem, a, border, mid, a.y + (mid / span) * (b.y - a.y));
        if (problem.indicator(kind, c.point) == left) {
          e.lo = mid;
        } else {
          e.hi = mid;
          e.past = std::move(c.point);
        }
      } catch (const NumericalError&) {
        e.bisected = false;
      }
    }
    curve.events.push_back(std::move(e));
  }
}

}  // namespace detail

/// Follows the curve from its last point (curve.points and curve.nodes hold
/// at least one, the first with its tangent) until max_points, a bound, the
/// problem's end, or a step below min_step; sets curve.stop and
/// curve.reason. Throws InputError on bad options.
template <class Point>
void continue_curve(const ArclengthProblem<Point>& problem, const ArclengthOptions& o,
                    ArclengthCurve<Point>& curve) {
  if (curve.nodes.empty() || curve.points.size() != curve.nodes.size())
    throw InputError("continuation: the curve needs a first point with its tangent");
  if (!(o.min_step > 0) || !(o.step >= o.min_step) || !(o.max_step >= o.step) ||
      !std::isfinite(o.max_step) || !(o.shrink > 1) || !(o.growth >= 1))
    throw InputError("continuation: steps must satisfy 0 < min_step <= step <= max_step < inf, "
                     "shrink > 1 and growth >= 1");
  if (!(o.max_jump >= 1) || !(o.max_turn > 0) || !(o.max_turn <= M_PI))
    throw InputError("continuation: max_jump must be >= 1 and max_turn in (0, pi]");
  if (o.max_points < 1 || !(o.event_tolerance > 0) || o.max_bisections < 0)
    throw InputError("continuation: max_points must be >= 1, event_tolerance > 0 and "
                     "max_bisections >= 0");
  if (o.bounded >= curve.nodes.front().y.size() || !(o.lower < o.upper))
    throw InputError("continuation: the bounded unknown must be one of the curve's (or -1) and "
                     "lower < upper");
  double h = o.step;
  std::string last_failure;
  while (static_cast<int>(curve.points.size()) < o.max_points) {
    if (std::string reason = problem.end(curve.points); !reason.empty()) {
      curve.stop = ArclengthStop::ended;
      curve.reason = std::move(reason);
      return;
    }
    const ArclengthNode k = curve.nodes.back();
    const Vector w = problem.weights(k.y);
    const Vector t = detail::unit_tangent(w, k.tangent);
    bool on_bound = false;
    try {
      ArclengthCorrection<Point> c =
          detail::at(problem, k, detail::border_row(w, k.tangent), h, k.y + h * t);
      const double jump = w.cwiseProduct(c.y - k.y).norm();
      if (jump > o.max_jump * h)
        throw NumericalError("the corrected point jumped " + detail::number(jump / h) +
                             " times the step (max_jump " + detail::number(o.max_jump) + ")");
      const double cosine = w.cwiseProduct(t).dot(w.cwiseProduct(detail::unit_tangent(w, c.tangent)));
      const double turn = std::acos(std::clamp(cosine, -1.0, 1.0));
      if (turn > o.max_turn)
        throw NumericalError("the tangent turned by " + detail::number(turn) +
                             " rad in one step (max_turn " + detail::number(o.max_turn) + ")");
      const Index b = o.bounded;
      if (b >= 0 && (c.y(b) < o.lower || c.y(b) > o.upper)) {
        // Land on the bound: the corrector with the border row y(b) = bound,
        // from the chord's crossing of it.
        const double bound = c.y(b) < o.lower ? o.lower : o.upper;
        const double theta = (bound - k.y(b)) / (c.y(b) - k.y(b));
        Vector row = Vector::Zero(k.y.size());
        row(b) = 1;
        c = detail::correct(problem, k, k.y + theta * (c.y - k.y), row, bound);
        on_bound = true;
      }
      const double advance = w.cwiseProduct(c.y - k.y).norm();
      curve.nodes.push_back(
          ArclengthNode{std::move(c.y), std::move(c.tangent), k.arclength + advance, h,
                        c.iterations});
      curve.points.push_back(std::move(c.point));
      detail::locate_events(problem, o, curve, static_cast<Index>(curve.points.size()) - 2);
      if (c.iterations <= o.easy_iterations) h = std::min(h * o.growth, o.max_step);
    } catch (const NumericalError& err) {
      last_failure = err.what();
      h /= o.shrink;
      if (h < o.min_step) {
        curve.stop = ArclengthStop::step_too_small;
        curve.reason = last_failure;
        return;
      }
      continue;
    }
    if (on_bound) {
      curve.stop = ArclengthStop::bound;
      return;
    }
  }
  curve.stop = ArclengthStop::max_points;
}

}  // namespace nbm
