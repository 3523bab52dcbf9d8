// Harmonic balance for periodic orbits of the reduced NBM equations (the
// paper's method for its Figure 3; method.md §6, §9), for either kind of
// periodic problem (periodic_problem.hpp); the counterpart of shooting
// (shooting.hpp) that checks it.
//
// u_O(t) = c_0 + sum_{h=1..H} a_h cos(h tau) + b_h sin(h tau), tau = omega t,
// and the Galerkin residual of the reduced equations on one period,
//
//     R_j = (1/pi) int_0^{2 pi} psi_j(tau) [M_S u'' + K_S u - f_S] dtau,
//
// with the region S = S(u_O(tau)) of the nodal boundary relation. The
// residual is piecewise polynomial in the trigonometric unknowns: between two
// switching times (roots of the switching functions along the series) the
// integrals are computed exactly ("exact"), or by sampling with the region
// decided at every sample ("aft", alternating frequency-time, as a fallback
// and cross-check). Newton's method uses the Jacobian with the switching
// times frozen: exact almost everywhere, and exact wherever the integrand is
// continuous across switches (the massless boundary).
//
// Autonomous orbits: the unknowns are the coefficients and omega; the phase
// (v_O[probe](0) = 0; implied by the cosine-only option for orbits even in
// time, i.e. through a state at rest at t = 0) and the amplitude condition
// of shooting.hpp close the system.
//
// Forced orbits: the excitation fixes the period T = 2 pi m / omega and the
// time origin, so the series (tau = nu t, nu = omega / m) has only its
// coefficients as unknowns, and the residual carries the Rayleigh damping
// and the harmonic load,
//     R_j = (1/pi) int_0^{2 pi} psi_j [M_S u'' + C_S u' + K_S u - f_S - F_h(t)] dtau,
// with C_S = a_M M_S + b_K K_S; harmonic k of the load is harmonic k m of
// the series and projects exactly onto its own basis functions. The result
// is checked by the exact forced flow from the series' state at t = 0: its
// periodicity residual measures the truncation, its Floquet multipliers (no
// trivial one) decide the stability.
//
// The Galerkin machinery (basis, exact weights, residual, Jacobian) is
// trig_galerkin.hpp's.
#pragma once

#include "periodic/periodic_orbit.hpp"
#include "periodic/periodic_problem.hpp"
#include "periodic/shooting.hpp"

namespace nbm {

/// The options of both kinds of problem; the conditions (probe, kind,
/// amplitude) and cosine_only are an autonomous problem's.
struct HarmonicBalanceOptions {
  /// H (of omega / m for a forced problem, H >= m: the load's first
  /// harmonic is the series' m-th)
  int harmonics = 20;
  bool cosine_only = false;  ///< orbits even in time (at rest at t = 0)
  enum class Integration { exact, aft };
  Integration integration = Integration::exact;
  int aft_samples = 0;  ///< samples per period for "aft"; 0: 32 H
  Index probe = 0;      ///< interior dof of the phase and amplitude conditions
  ShootingOptions::Amplitude kind = ShootingOptions::Amplitude::displacement;
  double amplitude = std::numeric_limits<double>::quiet_NaN();  ///< NaN: from the guess
  double tolerance = 1e-12;  ///< on the scaled Galerkin residual
  int max_iterations = periodic_max_iterations;
  /// Adaptive number of harmonics: H is doubled (up to max_harmonics) until
  /// the truncation estimate is below truncation_tolerance.
  bool adaptive = false;
  double truncation_tolerance = 1e-6;
  int max_harmonics = 320;
  /// Periods of the exact flow run from the guess before its Fourier series
  /// is taken as the initial coefficients (shooting.hpp).
  int transient_periods = 0;
};

struct HarmonicBalanceResult {
  /// u0, v0 and period from the series, verified with the exact flow
  /// (analyse_orbit): its periodicity residual measures the truncation error.
  PeriodicOrbit orbit;
  int harmonics = 0;
  /// n x (2H + 1): columns c_0, a_1, b_1, a_2, b_2, ... (b_h = 0 if cosine-only)
  Matrix coefficients;
  double residual = 0;  ///< scaled Galerkin residual at the solution
  /// Scaled Galerkin residual of the solution on harmonics H+1 .. 2H: what
  /// the truncation leaves unbalanced.
  double truncation = 0;
  std::vector<int> harmonics_tried;  ///< with `adaptive`
};

/// Harmonic balance from the guess (u0, v0, T) (T: a forced problem's
/// period()): the initial coefficients are the Fourier series of the exact
/// flow from (u0, v0) over [0, T]. Throws NumericalError if Newton does not
/// converge, InputError on a bad guess or option (naming it), and for a
/// forced problem on an assembled damping matrix or moving contacts (not in
/// the Galerkin operator: shoot instead).
HarmonicBalanceResult harmonic_balance(const PeriodicProblem& problem, const Vector& u0,
                                       const Vector& v0, double T,
                                       const HarmonicBalanceOptions& options);

}  // namespace nbm
