// What the energy-stable steps bound (method.md §5.1, §5.3). Free of Eigen,
// for the solver's options (api/solver.hpp).
#pragma once

namespace nbm {

/// What an energy-controlled step bounds.
enum class EnergyControl {
  /// E_n + D_n - W_n never above its start: a step may return what earlier
  /// switching steps lost, no more.
  kBounded,
  /// E_{n+1} + D_{n+1} - W_{n+1} <= E_n + D_n - W_n in every step.
  kMonotone,
  /// Nothing bounded: the scheme's own step (the trapezoidal contact forces).
  kNone,
};

/// The name front ends and messages use: "bounded", "monotone", "none".
inline const char* name(EnergyControl control) {
  return control == EnergyControl::kMonotone ? "monotone"
         : control == EnergyControl::kNone   ? "none"
                                             : "bounded";
}

}  // namespace nbm
