// Viscous damping C = a_M M + b_K K + C_user (docs/method.md §9): Rayleigh
// coefficients and/or a matrix assembled by FreeFEM like M and K. Shared by
// the time steppers and the periodic-orbit solvers, so that both read the
// same description.
#pragma once

#include "base/types.hpp"

namespace nbm {

struct Damping {
  double a_M = 0;       ///< mass-proportional Rayleigh coefficient (1/s)
  double b_K = 0;       ///< stiffness-proportional Rayleigh coefficient (s)
  SparseMatrix C_user;  ///< assembled damping matrix, 0 x 0 when there is none

  bool has_matrix() const { return C_user.size() != 0; }
  bool is_rayleigh() const { return !has_matrix(); }
  bool none() const { return a_M == 0 && b_K == 0 && !has_matrix(); }
};

/// Throws InputError naming the faulty part unless a_M, b_K are finite and
/// >= 0 and C_user (if any) is n x n, finite, symmetric and has a
/// nonnegative diagonal (a cheap necessary condition of positive
/// semidefiniteness; an indefinite C that makes the iteration matrix
/// indefinite is caught by its factorization).
void check_damping(const Damping& damping, Index n);

/// C = a_M M + b_K K + C_user, all in the same coordinates; 0 x 0 when the
/// damping is none() (the schemes then skip every damping term).
SparseMatrix damping_matrix(const Damping& damping, const SparseMatrix& M, const SparseMatrix& K);

}  // namespace nbm
