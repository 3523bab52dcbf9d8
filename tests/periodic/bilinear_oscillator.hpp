// The forced bilinear oscillator of the forced-orbit tests (method.md §9),
// with its brute-force reference: classical RK4 of its first-order field to
// steady state, independent of the exact flow.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "contact/damping.hpp"
#include "oscillators.hpp"
#include "periodic/harmonic_load.hpp"
#include "rk4.hpp"

namespace nbm_test {

// The forced bilinear oscillator: mass m on a spring k, massless contact dof
// joined by kc, obstacle at g; u'' = F cos(w t) - a_M u' - k u - kc [u - g]_+.
struct Bilinear {
  double k = 1, kc = 4, g = 0.5, a_M = 0.1, F = 0.3, w = 0.8;

  nbm_test::ImpactOscillator oscillator() const {
    nbm_test::ImpactOscillator osc;
    osc.k = k, osc.kc = kc, osc.g = g, osc.mB = 0;
    return osc;
  }
  nbm::Damping damping() const {
    nbm::Damping d;
    d.a_M = a_M;
    return d;
  }
  /// F cos(w t) on the interior dof (internal vector: interior, contact).
  nbm::HarmonicLoad load() const {
    nbm::HarmonicLoad l;
    l.omega = w;
    l.cos = {Eigen::Vector2d(F, 0)};
    return l;
  }
  Eigen::Vector2d field(double t, const Eigen::Vector2d& x) const {
    return {x(1), F * std::cos(w * t) - a_M * x(1) - k * x(0) - kc * std::max(x(0) - g, 0.0)};
  }
  /// Classical RK4 over `periods` forcing periods from t = 0, `steps` per
  /// period (the field is only Lipschitz at u = g: the kink costs order).
  Eigen::Vector2d integrate(Eigen::Vector2d x, int periods, int steps = 40000) const {
    return rk4_periods([this](double t, const Eigen::Vector2d& y) { return field(t, y); }, x,
                       2 * M_PI / w, periods, steps);
  }
  /// Steady state at t = 0 mod T from x: periods integrated until a period changes
  /// the state by less than 1e-13.
  Eigen::Vector2d steady_state(Eigen::Vector2d x = Eigen::Vector2d::Zero()) const {
    for (int p = 0; p < 2000; ++p) {
      const Eigen::Vector2d next = integrate(x, 1);
      if ((next - x).norm() < 1e-13) return next;
      x = next;
    }
    ADD_FAILURE() << "no steady state in 2000 periods";
    return x;
  }
};

}  // namespace nbm_test
