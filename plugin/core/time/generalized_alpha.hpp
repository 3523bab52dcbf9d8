// Generalized-alpha (Chung and Hulbert [CH93]; method.md §5.4): the
// parameters of the implicit scheme (implicit_scheme.hpp) from the spectral
// radius at infinite frequency rho_inf, the one knob of the family: rho_inf = 1
// dissipates nothing, rho_inf = 0 annihilates the highest modes in one step,
// and the low modes are damped least among second-order schemes of that
// rho_inf. HHT-alpha [HHT77] is the member with alpha_m = 0.
#pragma once

#include "time/implicit_scheme.hpp"

namespace nbm {

/// Chung-Hulbert's set: alpha_m = (2 rho - 1) / (rho + 1),
/// alpha_f = rho / (rho + 1), gamma = 1/2 - alpha_m + alpha_f,
/// beta = (1 - alpha_m + alpha_f)^2 / 4. Throws InputError unless
/// 0 <= rho_inf <= 1.
SchemeParameters generalized_alpha(double rho_inf);

/// Hilber-Hughes-Taylor's set: alpha_m = 0, alpha_f = (1 - rho) / (1 + rho),
/// gamma = 1/2 + alpha_f, beta = (1 + alpha_f)^2 / 4. Throws InputError
/// unless 1/2 <= rho_inf <= 1 (alpha_f <= 1/3).
SchemeParameters hht_alpha(double rho_inf);

}  // namespace nbm
