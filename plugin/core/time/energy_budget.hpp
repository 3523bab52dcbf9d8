// The energy bound of the massless boundary's energy-stable step (method.md
// §5.1, "What is bounded"): what a step may still gain, kept from step to
// step and across restarts, and the search for the fraction of a step's way
// that gains no more. Apart from the stepper, so that the bookkeeping can be
// read and tested alone.
#pragma once

#include <algorithm>
#include <functional>

#include "base/types.hpp"
#include "time/energy_control.hpp"

namespace nbm {

/// The returnable loss R of method.md §5.1: B + R never rises in a step (B
/// the balance E + D - W); R = 0 with kMonotone. Exact-restart state.
class EnergyBudget {
 public:
  explicit EnergyBudget(EnergyControl control) : bounded_(control == EnergyControl::kBounded) {}

  /// What a step may still gain (negative by round-off, see keep()).
  double returnable() const { return returnable_; }
  /// Steps since the start whose balance had to be brought down.
  long balanced_steps() const { return balanced_steps_; }

  /// A new run: nothing to return, no step balanced.
  void reset() { returnable_ = 0, balanced_steps_ = 0; }
  /// After a switching step that ended `unreached` below the balance it
  /// could reach (start + returnable()): kept as what may be returned
  /// (kBounded). A rise by round-off (unreached < 0) is kept with either
  /// control, so that the next steps take it back instead of adding it up.
  void keep(double unreached) { returnable_ = bounded_ ? unreached : std::min(0.0, unreached); }
  void count_balanced() { ++balanced_steps_; }
  /// [returnable()], for scheme_state().
  Vector state() const { return Vector::Constant(1, returnable_); }
  /// From state() (empty: nothing kept); throws InputError naming `what` if
  /// it does not fit.
  void restore(const Vector& state, const char* what);
  /// The returnable loss of a previous run (a global budget: it outlives the
  /// contact set).
  void take_over(const EnergyBudget& previous) { returnable_ = previous.returnable_; }

 private:
  bool bounded_;
  double returnable_ = 0;
  long balanced_steps_ = 0;
};

/// The largest theta in [0, 1] found with excess(theta) <= 0, given
/// excess(0) = at_0 and excess(1) = at_1 > 0: regula falsi (Illinois), which
/// stops once the excess is within `tolerance` below 0 (the bound reached to
/// round-off). excess need not be continuous: the side kept is always one
/// where it does not exceed (at worst theta = 0).
double largest_allowed_fraction(const std::function<double(double)>& excess, double at_0,
                                double at_1, double tolerance);

}  // namespace nbm
