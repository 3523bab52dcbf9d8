// Forced periodic orbits on the user's dofs (method.md §9): the front end of
// shoot_forced (forced_orbit.hpp) for the FreeFEM binding, reporting like the
// autonomous front end (user_orbit.hpp, OrbitReport). Free of Eigen and
// FreeFEM types.
//
// The excitation is the load
//     F(t) = F0 + sum_{k=1..H} ( Fc_k cos(k omega t) + Fs_k sin(k omega t) )
// on a damped model C = a_M M + b_K K (M the problem's mass: redistributed
// with the massless boundary). The orbit has the period 2 pi m / omega and
// no phase condition (the excitation fixes the time origin). Full interior
// only: no reduced basis (its reduction residual would have to carry the
// damping and the harmonic load).
#pragma once

#include <limits>
#include <vector>

#include "periodic_defaults.hpp"
#include "user_orbit.hpp"

namespace nbm {

struct ForcedOrbitOptions {
  double omega = std::numeric_limits<double>::quiet_NaN();  ///< > 0, required
  int subharmonic = 1;                                       ///< m >= 1
  double rayleigh_mass = 0, rayleigh_stiffness = 0;          ///< a_M, b_K >= 0
  /// User dof whose amplitude is reported (any dof that is not fixed);
  /// -1: the dof of largest amplitude along the orbit.
  long probe = -1;
  /// Periods of the exact flow run from the guess before Newton (a stable
  /// orbit's basin; forced_orbit.hpp).
  int transient_periods = 0;
  int max_iterations = periodic_max_iterations;
};

/// The forced orbit from the guess (u, v) at t = 0 (user vectors). F0 and
/// every harmonic are user vectors (size n_dofs); `load_cos[k]`,
/// `load_sin[k]` are the harmonic k + 1, either list may be shorter (zero
/// harmonics) but not both empty; the harmonics must vanish on the normal
/// components of the contact nodes (the exact flow does not model a
/// time-varying offset of the nodal boundary relation, method.md §9).
/// Throws InputError naming the argument (F0, Fc, Fs, u, v, omega,
/// subharmonic, rayleighM, rayleighK, probe, transient, iterations),
/// NumericalError if Newton does not converge or an undamped mode is in
/// resonance with a harmonic.
OrbitReport forced_orbit(const ContactProblem& problem, const std::vector<double>& F0,
                         const std::vector<std::vector<double>>& load_cos,
                         const std::vector<std::vector<double>>& load_sin,
                         const std::vector<double>& u, const std::vector<double>& v,
                         const ForcedOrbitOptions& options);

}  // namespace nbm
