// Vector-valued sums of sinusoids and a quadratic,
//
//     h(t) = c + p t + q t^2 + sum_k ( a_k cos(nu_k t) + b_k sin(nu_k t) ),
//
// the form every switching function takes along a harmonic-balance
// trajectory (nu_k = k omega). The search for the first time one of them
// changes sign is switching.hpp's.
#pragma once

#include "periodic/switching.hpp"

namespace nbm {

struct TrigSum : SwitchingFunctions {
  Vector c, p, q;  ///< one entry per row (switching function)
  Matrix a, b;     ///< rows x terms
  Vector nu;       ///< one frequency per term, > 0

  Index rows() const override { return c.size(); }
  Vector value(double t) const override;
  Vector rate(double t) const override;
  Vector curvature(double t) const override;  ///< h''(t)
  /// Per row, a bound of |h''| valid for all t (the argument is unused).
  Vector curvature_bound(double t) const override;
  /// Per row, |c| + span |p| + span^2 |q| + sum |a_k| + |b_k|.
  Vector magnitude(double span) const override;
};

}  // namespace nbm
