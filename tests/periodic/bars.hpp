// The fixed-gap bar of benchmarks.md §C as an NBM model: P1 bar on (0, L),
// fixed at x = 0, unilateral contact at x = L (u(L) <= g), no load; and the
// continuum periodic solution it approximates.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "contact/contact_problem.hpp"
#include "contact/mass_redistribution.hpp"
#include "periodic/reduced_field.hpp"

namespace nbm_test {

struct GapBar {
  double L = 1, E = 1, rho = 1, g = 0.1;
  int N = 20;
  bool massless = false;  ///< mass redistribution (method.md §4)

  double c() const { return std::sqrt(E / rho); }
  double h() const { return L / N; }

  /// User matrices (dofs = nodes 0..N).
  void assemble(nbm::SparseMatrix& M, nbm::SparseMatrix& K) const {
    std::vector<nbm::Triplet> m, k;
    for (int e = 0; e < N; ++e)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          m.emplace_back(e + i, e + j, rho * h() / 6 * (i == j ? 2 : 1));
          k.emplace_back(e + i, e + j, E / h() * (i == j ? 1 : -1));
        }
    M.resize(N + 1, N + 1);
    K.resize(N + 1, N + 1);
    M.setFromTriplets(m.begin(), m.end());
    K.setFromTriplets(k.begin(), k.end());
  }

  /// The contact problem (tip dof N against the obstacle, dof 0 fixed),
  /// with the redistributed mass if `massless`.
  std::unique_ptr<nbm::ContactProblem> problem() const {
    nbm::SparseMatrix M, K;
    assemble(M, K);
    nbm::ContactSet contact(N + 1, {N}, {1.0}, nbm::Vector::Constant(1, g), {0});
    nbm::Matrix x(N + 1, 1);
    for (int i = 0; i <= N; ++i) x(i, 0) = i * h();
    return std::make_unique<nbm::ContactProblem>(M, K, contact, std::vector<Eigen::Index>{0},
                                                 massless ? &x : nullptr);
  }

  nbm::ReducedField field() const {
    return nbm::ReducedField::from(*problem(), nbm::Vector::Zero(N));
  }
  /// Interior unknowns are the nodes 1..N-1, in order.
  double x_of_interior(int k) const { return (k + 1) * h(); }
};

/// Continuum orbit of benchmarks.md §C with contact duration tau L/c, at the
/// middle of its free phase, where the bar is at rest (the orbit is
/// symmetric about it). From the start of a free phase, u0(x) = g min(x/l, 1),
/// v0 = -(g c/l) [x > l], l = L (1 - tau), propagated over (2 - tau) L/c by
/// d'Alembert's formula on the odd (x = 0) / even (x = L) extension.
inline double continuum_rest_profile(const GapBar& b, double tau, double x) {
  const double L = b.L, l = L * (1 - tau), c = b.c(), g = b.g;
  auto wrap = [L](double s, double& sign) {  // extension to one base interval
    s = std::fmod(s, 4 * L);
    if (s < 0) s += 4 * L;
    sign = 1;
    if (s > 2 * L) s -= 4 * L;            // (-2L, 2L]
    if (s < 0) s = -s, sign = -1;         // odd about 0
    if (s > L) s = 2 * L - s;             // even about L
    return s;
  };
  auto U0 = [&](double s) {
    double sign;
    const double y = wrap(s, sign);
    return sign * g * std::min(y / l, 1.0);
  };
  // Antiderivative of the extended v0 (odd about 0, even about L): the
  // integral of -(g c / l) [y > l] from 0 to y on the base interval.
  auto W = [&](double s) {
    const double period = 4 * L;
    const double r = s - std::floor(s / period) * period;  // in [0, 4L); integral over a period is 0
    auto base = [&](double y) { return -(g * c / l) * std::max(0.0, y - l); };
    // on [0, 2L] the extension is v0(y) for y <= L, v0(2L - y) beyond.
    auto up = [&](double y) {  // integral from 0 to y, y in [0, 2L]
      return y <= L ? base(y) : 2 * base(L) - base(2 * L - y);
    };
    return r <= 2 * L ? up(r) : up(4 * L - r);  // odd: W(4L - y) = W(y)
  };
  const double t = (2 - tau) * L / c;
  return 0.5 * (U0(x + c * t) + U0(x - c * t)) + (W(x + c * t) - W(x - c * t)) / (2 * c);
}

}  // namespace nbm_test
