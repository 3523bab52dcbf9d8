#include "time/energy_budget.hpp"

#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace nbm {

void EnergyBudget::restore(const Vector& state, const char* what) {
  if (state.size() == 0) {  // saved without it (an older file): nothing kept
    returnable_ = 0;
    return;
  }
  if (state.size() != 1)
    throw InputError("scheme state: size " + std::to_string(state.size()) + ", expected 1 (" +
                     what + "'s returnable loss)");
  if (!std::isfinite(state(0))) throw InputError("scheme state: non-finite entries");
  returnable_ = state(0);
}

double largest_allowed_fraction(const std::function<double(double)>& excess, double at_0,
                                double at_1, double tolerance) {
  double lo = 0, hi = 1, f_lo = at_0;
  double w_lo = at_0, w_hi = at_1;  // the secant's values, halved on a repeated side
  int side = 0;
  for (int it = 0; it < 60 && f_lo < -tolerance && hi - lo > 1e-15; ++it) {
    const double theta = (lo * w_hi - hi * w_lo) / (w_hi - w_lo);
    const double f = excess(theta);
    if (f <= 0) {
      lo = theta, f_lo = w_lo = f;
      if (side == -1) w_hi /= 2;
      side = -1;
    } else {
      hi = theta, w_hi = f;
      if (side == 1) w_lo /= 2;
      side = 1;
    }
  }
  return lo;
}

}  // namespace nbm
