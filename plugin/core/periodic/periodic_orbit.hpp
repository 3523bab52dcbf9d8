// A periodic orbit of the reduced NBM equations and its verification with
// the exact flow: periodicity and complementarity residuals, energies,
// monodromy matrix and Floquet multipliers (method.md §6).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "exact_flow.hpp"

namespace nbm {

struct PeriodicOrbit {
  Vector u0, v0;       ///< interior state at t = 0
  double period = 0;
  int iterations = 0;  ///< Newton iterations of the solver that found it
  std::vector<double> residual_history;

  // Filled by analyse_orbit, with the exact flow over one period:
  /// max(|u(T) - u0| / |u0|, |v(T) - v0| / (|u0| 2 pi / T)).
  double periodicity_residual = 0;
  /// max over the switch times and 256 samples of the complementarity
  /// residual of the nodal boundary relation (reduced_field.hpp).
  double complementarity_residual = 0;
  Eigen::Vector4d energy_start, energy_end;  ///< kinetic, elastic, load, total
  double contact_time = 0;        ///< time with at least one contact closed
  std::vector<SwitchEvent> switches;
  Matrix monodromy;               ///< 2n x 2n
  std::vector<std::complex<double>> multipliers;  ///< by decreasing modulus
  bool stable = false;            ///< all |multipliers| <= 1 + 1e-6
};

/// Integrates one period from (orbit.u0, orbit.v0) with the exact flow and
/// fills the verification fields of `orbit`.
void analyse_orbit(const ReducedField& field, PeriodicOrbit& orbit);

/// A line per quantity: period, energy, contact time, residuals, multipliers.
std::string summary(const PeriodicOrbit& orbit);

}  // namespace nbm
