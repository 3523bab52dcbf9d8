// Viscous damping C = a_M M + b_K K + C_user (docs/method.md §9): Rayleigh
// coefficients and/or a matrix assembled by FreeFEM like M and K. Shared by
// the time steppers and the periodic-orbit solvers, so that both read the
// same description.
#pragma once

#include "types.hpp"

namespace nbm {

struct Damping {
  double a_M = 0;       ///< mass-proportional Rayleigh coefficient (1/s)
  double b_K = 0;       ///< stiffness-proportional Rayleigh coefficient (s)
  SparseMatrix C_user;  ///< assembled damping matrix, 0 x 0 when there is none

  bool has_matrix() const { return C_user.size() != 0; }
  bool is_rayleigh() const { return !has_matrix(); }
  bool none() const { return a_M == 0 && b_K == 0 && !has_matrix(); }
};

}  // namespace nbm
