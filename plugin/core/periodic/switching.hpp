// Switching functions along an exact flow (method.md §6, §9) and the search
// for the first time one of them changes sign. Every flow of the periodic
// solvers gives its switching functions through this interface: trigonometric
// sums (trig_sum.hpp: undamped modes, harmonic-balance series) and damped,
// forced modal flows (exact_flow.hpp).
#pragma once

#include <optional>

#include "base/types.hpp"

namespace nbm {

/// A vector-valued function h(t), one row per switching function.
class SwitchingFunctions {
 public:
  virtual ~SwitchingFunctions() = default;
  virtual Index rows() const = 0;
  virtual Vector value(double t) const = 0;
  virtual Vector rate(double t) const = 0;
  virtual Vector curvature(double t) const = 0;  ///< h''(t)
  /// Per row, a bound of |h''(s)| valid for every s >= t: what makes the
  /// search rigorous. Constant for sums of sinusoids; for damped flows it
  /// decreases with t (the modal energies do), so it is asked at every step.
  virtual Vector curvature_bound(double t) const = 0;
  /// Per row, the size of the terms h is computed from over [0, span]:
  /// round-off in value() is of order 1e-16 times it.
  virtual Vector magnitude(double span) const = 0;
};

struct Crossing {
  double t;   ///< first time in (t0, t1] at which a row leaves h >= 0
  Index row;
};

/// The first time in [t0, t1] at which a row of h, non-negative on [t0, t],
/// becomes negative. Rows must be >= 0 at t0 up to round-off; a row at zero
/// with a negative rate crosses at t0. Steps are the largest ones the
/// curvature bound proves root-free (h(t + s) >= h + h' s - L s^2 / 2), so a
/// crossing is never stepped over and transversal roots are approached
/// quadratically; the crossing time is then polished by Newton's method.
/// Tangential contacts (a row reaching zero within round-off with h'' > 0,
/// whose local quadratic model does not dip below the round-off level) are
/// not crossings. Throws NumericalError if a row is negative at t0.
std::optional<Crossing> first_crossing(const SwitchingFunctions& h, double t0, double t1);

}  // namespace nbm
