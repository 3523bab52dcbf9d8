// Defaults shared by the periodic-orbit solvers (shooting, harmonic balance,
// the user front end). Free of Eigen and FreeFEM types, like user_orbit.hpp.
#pragma once

namespace nbm {

/// Floor of the scales that divide residuals (|u0|, |target|, ...): keeps
/// the scaled equations finite at a zero scale. The one "zero" tolerance of
/// the periodic solvers.
inline constexpr double periodic_tiny = 1e-300;

/// Newton iterations of the periodic solvers (shooting, harmonic balance,
/// user orbits). 50: the larger of the former defaults (shooting 40, harmonic
/// balance 50), so every orbit that converged before converges identically
/// (same iterates; only the cap moved); converged runs take far fewer
/// (quadratic convergence), the cap only bounds a failing run.
inline constexpr int periodic_max_iterations = 50;

/// Interior dofs the dense periodic solvers accept without a reduced basis
/// (user orbits, backbones): beyond, their dense matrices cost too much.
inline constexpr long periodic_max_dense_dofs = 3000;

}  // namespace nbm
