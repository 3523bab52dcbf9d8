// Classical fourth-order Runge-Kutta, the brute-force time integration the
// forced-orbit tests compare the exact flow with (independent of it).
#pragma once

namespace nbm_test {

/// x' = f(t, x) over `periods` periods T, `steps` steps per period, from
/// t = 0 (times p T + s h, as the forcing's phase wants them exact at the
/// start of each period).
template <class State, class Field>
State rk4_periods(const Field& f, State x, double T, int periods, int steps) {
  const double h = T / steps;
  for (int p = 0; p < periods; ++p)
    for (int s = 0; s < steps; ++s) {
      const double t = p * T + s * h;
      const State k1 = f(t, x), k2 = f(t + h / 2, State(x + h / 2 * k1)),
                  k3 = f(t + h / 2, State(x + h / 2 * k2)), k4 = f(t + h, State(x + h * k3));
      x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
  return x;
}

}  // namespace nbm_test
