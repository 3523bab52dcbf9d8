#include "periodic/switching.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Rows within this fraction of their magnitude of zero count as zero: a few
// hundred ulps of the sum they are computed from.
constexpr double kEventZeroTolerance = 1e-13;
// The search advances at least this fraction of the span per step, so that a
// tangential contact (h = 0, h' = 0) cannot stall it.
constexpr double kMinimumStep = 1e-13;
// Safety bound on the number of steps of one search.
constexpr long kMaxSteps = 50'000'000;

}  // namespace

std::optional<Crossing> first_crossing(const SwitchingFunctions& h, double t0, double t1) {
  const Index rows = h.rows();
  if (rows == 0 || t1 <= t0) return std::nullopt;
  const double span = t1 - t0;
  const Vector tol = kEventZeroTolerance * h.magnitude(std::max(std::abs(t0), std::abs(t1)));
  const double min_step = kMinimumStep * span;

  double t = t0;
  for (long step = 0; step < kMaxSteps; ++step) {
    const Vector v = h.value(t), r = h.rate(t), L = h.curvature_bound(t);
    double s = std::numeric_limits<double>::infinity();
    Index hit = -1;
    for (Index j = 0; j < rows; ++j) {
      if (v(j) < -tol(j)) {
        if (t == t0)
          throw NumericalError("switching function " + std::to_string(j) +
                               " is negative at the start of a search");
        hit = j;  // a steeply crossing row passed between two safe points
        break;
      }
      if (v(j) <= tol(j) && r(j) < 0) {
        // At zero and decreasing: a crossing (the earliest, since every row
        // was proven positive up to here), unless the row is turning back
        // without going below round-off (a tangential contact): then step
        // over its minimum.
        const double k = h.curvature(t)(j);
        if (k > 0 && v(j) - r(j) * r(j) / (2 * k) >= -tol(j)) {
          s = std::min(s, -2 * r(j) / k);
          continue;
        }
        if (hit < 0 || r(j) < r(hit)) hit = j;
        continue;
      }
      // h(t + s) >= h + h' s - L s^2 / 2 > 0 for s below the positive root.
      const double hj = std::max(v(j), 0.0), rj = r(j);
      const double sj = L(j) > 0 ? (rj + std::sqrt(rj * rj + 2 * L(j) * hj)) / L(j)
                                 : (rj < 0 ? hj / -rj : std::numeric_limits<double>::infinity());
      s = std::min(s, sj);
    }
    if (hit >= 0) {
      // Newton polish of the crossing time of row `hit`.
      double tc = t;
      for (int it = 0; it < 4; ++it) {
        const double rj = h.rate(tc)(hit);
        if (rj >= 0) break;
        const double dt = -h.value(tc)(hit) / rj;
        if (!std::isfinite(dt) || std::abs(dt) > span) break;
        tc += dt;
      }
      return Crossing{std::clamp(tc, t0, t1), hit};
    }
    s = std::max(s, min_step);
    if (t + s >= t1) return std::nullopt;
    t += s;
  }
  throw NumericalError("switching-time search did not terminate");
}

}  // namespace nbm
