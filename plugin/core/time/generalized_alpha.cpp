#include "time/generalized_alpha.hpp"

#include <string>

#include "base/errors.hpp"

namespace nbm {

SchemeParameters generalized_alpha(double rho_inf) {
  if (!(rho_inf >= 0 && rho_inf <= 1))
    throw InputError("rhoInf: " + std::to_string(rho_inf) +
                     ", expected a spectral radius at infinite frequency in [0, 1]");
  SchemeParameters p;
  p.alpha_m = (2 * rho_inf - 1) / (rho_inf + 1);
  p.alpha_f = rho_inf / (rho_inf + 1);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  const double s = 1 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * s * s;
  return p;
}

SchemeParameters hht_alpha(double rho_inf) {
  if (!(rho_inf >= 0.5 && rho_inf <= 1))
    throw InputError("rhoInf: " + std::to_string(rho_inf) +
                     ", expected in [1/2, 1] for scheme \"hht-alpha\" (alpha = (1 - rhoInf) / "
                     "(1 + rhoInf) <= 1/3; \"generalized-alpha\" reaches rhoInf = 0)");
  SchemeParameters p;
  p.alpha_f = (1 - rho_inf) / (1 + rho_inf);
  p.gamma = 0.5 + p.alpha_f;
  p.beta = 0.25 * (1 + p.alpha_f) * (1 + p.alpha_f);
  return p;
}

}  // namespace nbm
