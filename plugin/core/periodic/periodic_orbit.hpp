// A periodic orbit of the reduced NBM equations and its verification with
// the exact flow: periodicity and complementarity residuals, energies,
// monodromy matrix and Floquet multipliers (method.md §6).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "periodic/exact_flow.hpp"

namespace nbm {

/// The relative periodicity residual of a flow from (u0, v0) to (u1, v1)
/// over the period T: max(|u1 - u0| / length, |v1 - v0| / (length 2 pi / T)),
/// velocities on the orbit's own time scale. Every periodic solver judges
/// convergence on it; they differ only in the length.
double periodicity_residual(const Vector& u0, const Vector& v0, const Vector& u1,
                            const Vector& v1, double T, double length);

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
  /// Floquet multipliers by decreasing modulus (floquet_multipliers).
  std::vector<std::complex<double>> multipliers;
  /// |X f - f| / |f| for the vector field f at the start: how exactly the
  /// trivial multiplier 1 holds.
  double trivial_residual = 0;
  /// Which stability criterion applied (analyse_orbit): an autonomous
  /// orbit's, every |multiplier| <= 1 + kAutonomousStabilityMargin (the
  /// trivial multiplier 1 split off), or a forced orbit's, every
  /// |multiplier| < 1 (time is not free: no trivial multiplier).
  bool autonomous = true;
  bool stable = false;
};

/// Round-off allowed above 1 in the multipliers of a stable autonomous
/// orbit: undamped, its multipliers lie on the unit circle.
constexpr double kAutonomousStabilityMargin = 1e-6;

/// Eigenvalues of the monodromy X of an autonomous orbit starting at
/// (u0, v0) with acceleration a0: the trivial multiplier 1 (eigenvector
/// f = (v0, a0), residual returned in `trivial_residual`) and the
/// eigenvalues of the map X induces on the quotient by span(f).
std::vector<std::complex<double>> floquet_multipliers(const Matrix& monodromy, const Vector& v0,
                                                      const Vector& a0, double& trivial_residual);

/// Integrates one period from (orbit.u0, orbit.v0) with the exact flow and
/// fills the verification fields of `orbit`.
void analyse_orbit(const ReducedField& field, PeriodicOrbit& orbit);
/// The same along a given flow (damped, forced: exact_flow.hpp) from its
/// time 0. An autonomous orbit gets the trivial multiplier 1 and is stable
/// if all |multipliers| <= 1 + kAutonomousStabilityMargin; a forced one (time is not free,
/// method.md §9) gets the eigenvalues of the monodromy, no trivial
/// multiplier, trivial_residual 0, and is stable if all |multipliers| < 1.
void analyse_orbit(const ExactFlow& flow, PeriodicOrbit& orbit, bool autonomous);

/// A line per quantity: period, energy, contact time, residuals, multipliers,
/// and the stability verdict with the criterion it used (autonomous or forced).
std::string summary(const PeriodicOrbit& orbit);

}  // namespace nbm
