// Forced periodic orbits of the damped reduced NBM equations by harmonic
// balance (method.md §9), the counterpart of shooting (forced_orbit.hpp)
// that checks it.
//
// The excitation of frequency omega (exact_flow.hpp: FlowForcing) fixes the
// period T = 2 pi m / omega and the time origin, so the series
//     u_O(t) = c_0 + sum_{h=1..H} a_h cos(h nu t) + b_h sin(h nu t),  nu = omega / m,
// has only its coefficients as unknowns: no phase or amplitude condition,
// no frequency unknown. The Galerkin residual on the same harmonics,
//     R_j = (1/pi) int_0^{2 pi} psi_j [M_S u'' + C_S u' + K_S u - f_S - F_h(t)] dtau,
// with C_S = a_M M_S + b_K K_S, is integrated exactly between the switching
// times along the series (trig_galerkin.hpp); harmonic k of the load is
// harmonic k m of the series and projects exactly onto its own basis
// functions (its cosine and sine amplitudes). Newton's method on the
// coefficients, with the switching times frozen in the Jacobian (exact
// wherever the integrand is continuous across switches: the massless
// boundary without stiffness-proportional damping).
//
// The result is checked by the exact forced flow from the series' state at
// t = 0 (analyse_orbit(flow, orbit, false)): its periodicity residual
// measures the truncation, and its Floquet multipliers (no trivial one)
// decide the stability.
#pragma once

#include "periodic/exact_flow.hpp"
#include "periodic/harmonic_balance.hpp"

namespace nbm {

struct ForcedHarmonicBalanceOptions {
  int subharmonic = 1;  ///< m: period 2 pi m / omega, harmonics in units of omega / m
  int harmonics = 20;   ///< H >= m (the load's first harmonic is the series' m-th)
  HarmonicBalanceOptions::Integration integration = HarmonicBalanceOptions::Integration::exact;
  int aft_samples = 0;       ///< samples per period for "aft"; 0: 32 H
  double tolerance = 1e-12;  ///< on the scaled Galerkin residual
  int max_iterations = periodic_max_iterations;
  /// Periods of the exact flow run from the guess before its Fourier series
  /// is taken as the initial coefficients (forced_orbit.hpp).
  int transient_periods = 0;
};

/// Harmonic balance from the guess (u0, v0) at t = 0: the initial
/// coefficients are the Fourier series of the exact forced flow from it over
/// one period. Returns the orbit (period, and the series' state at t = 0,
/// analysed on the flow), the coefficients (n x (2H + 1): c_0, a_1, b_1,
/// ...), the scaled Galerkin residual and the truncation estimate (the
/// scaled residual on harmonics H+1 .. 2H). Throws InputError on an assembled
/// damping matrix (not in the Galerkin operator: shoot instead), on a bad guess
/// or option (naming it), NumericalError if Newton does not converge.
HarmonicBalanceResult forced_harmonic_balance(const ExactFlow& flow, const Vector& u0,
                                              const Vector& v0,
                                              const ForcedHarmonicBalanceOptions& options);

}  // namespace nbm
