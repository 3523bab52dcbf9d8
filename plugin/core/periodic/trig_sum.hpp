// Vector-valued sums of sinusoids and a quadratic,
//
//     h(t) = c + p t + q t^2 + sum_k ( a_k cos(nu_k t) + b_k sin(nu_k t) ),
//
// the form every switching function takes along an exact modal flow (nu_k
// the circular frequencies of a region) and along a harmonic-balance
// trajectory (nu_k = k omega), and the search for the first time one of
// them changes sign.
#pragma once

#include <optional>

#include "types.hpp"

namespace nbm {

struct TrigSum {
  Vector c, p, q;  ///< one entry per row (switching function)
  Matrix a, b;     ///< rows x terms
  Vector nu;       ///< one frequency per term, > 0

  Vector value(double t) const;
  Vector rate(double t) const;
  Vector curvature(double t) const;  ///< h''(t)
  /// Per row, a bound of |h''| valid for all t.
  Vector curvature_bound() const;
  /// Per row, the size of the terms (|c| + sum |a_k| + |b_k| + ...) over a
  /// time span: round-off in value() is of order 1e-16 times it.
  Vector magnitude(double span) const;
};

struct Crossing {
  double t;   ///< first time in (t0, t1] at which a row leaves h >= 0
  Index row;
};

/// The first time in [t0, t1] at which a row of h, non-negative on [t0, t],
/// becomes negative. Rows must be >= 0 at t0 up to round-off; a row at zero
/// with a negative rate crosses at t0. Steps are the largest ones the
/// curvature bound proves root-free, so a crossing is never stepped over and
/// transversal roots are approached quadratically; the crossing time is then
/// polished by Newton's method. Tangential contacts (a row reaching zero
/// within round-off with h'' > 0, whose local quadratic model does not dip
/// below the round-off level) are not crossings. Throws NumericalError if a row is negative at t0.
std::optional<Crossing> first_crossing(const TrigSum& h, double t0, double t1);

}  // namespace nbm
