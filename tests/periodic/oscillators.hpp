// Small models with closed-form periodic orbits (benchmarks.md §E), built
// as NBM contact problems in internal coordinates.
#pragma once

#include <cctype>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "periodic/reduced_field.hpp"

namespace nbm_test {

/// A parameter value as part of a test name (letters, digits, '_' only):
/// 0.5 -> "0p5", 1e4 -> "10000", -2 -> "m2".
inline std::string name_word(double x) {
  std::ostringstream s;
  s << x;
  std::string w = s.str();
  for (char& c : w)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = c == '.' ? 'p' : c == '-' ? 'm' : '_';
  return w;
}

/// Mass m on a spring k to the ground (interior dof 0), contact node of mass
/// m_B joined to it by a spring k_c (contact dof 1), obstacle at u_1 <= g.
struct ImpactOscillator {
  double m = 1, k = 1, kc = 1, mB = 0, g = 1;

  nbm::ReducedField field() const {
    Eigen::Matrix2d M, K;
    M << m, 0, 0, mB;
    K << k + kc, -kc, -kc, kc;
    return nbm::ReducedField(M, K, Eigen::Vector2d::Zero(), {1}, Eigen::VectorXd::Constant(1, g));
  }

  /// Exact period of the orbit with free-side amplitude A (x_min = -A):
  /// free phase (m + m_B) x'' + k x = 0, contact phase m x'' + (k + k_c) x = k_c g.
  double period(double A) const {
    const double w1 = std::sqrt(k / (m + mB));
    if (A <= g) return 2 * M_PI / w1;
    const double w2 = std::sqrt((k + kc) / m), V = w1 * std::sqrt(A * A - g * g);
    const double z0 = k * g / (k + kc);
    return 2 * (M_PI - std::acos(g / A)) / w1 + (2 / w2) * std::atan(V / (w2 * z0));
  }
};

}  // namespace nbm_test
