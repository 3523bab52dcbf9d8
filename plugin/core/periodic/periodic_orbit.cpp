#include "periodic/periodic_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/QR>

#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "periodic/periodic_defaults.hpp"

namespace nbm {

std::vector<std::complex<double>> floquet_multipliers(const Matrix& monodromy, const Vector& v0,
                                                      const Vector& a0, double& trivial_residual) {
  // The vector field f = (v0, a0) at the start of an autonomous orbit is an
  // eigenvector of the monodromy with multiplier 1 (time translation). On a
  // family of orbits that multiplier is double with a Jordan block, which an
  // eigensolver splits by O(sqrt(eps)); the map induced on the quotient by
  // span(f) keeps the family's multiplier simple and accurate:
  // B = Z^T X Z with Z an orthonormal basis of f^perp.
  const Index m = monodromy.rows();
  Vector f(m);
  f << v0, a0;
  std::vector<std::complex<double>> mu;
  Matrix B = monodromy;
  trivial_residual = 0;
  if (f.norm() > 0) {
    trivial_residual = (monodromy * f - f).norm() / f.norm();
    Eigen::HouseholderQR<Matrix> qr(f);
    const Matrix Q = qr.householderQ();
    const Matrix Z = Q.rightCols(m - 1);
    B = Z.transpose() * monodromy * Z;
    mu.emplace_back(1.0);
  }
  const GeneralEigen eig = general_eigen(B, false);
  if (!eig.ok)
    throw NumericalError("Floquet multipliers: the eigenvalue solver of the monodromy failed");
  for (Index k = 0; k < eig.values.size(); ++k) mu.push_back(eig.values(k));
  std::stable_sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  return mu;
}

void analyse_orbit(const ReducedField& field, PeriodicOrbit& orbit) {
  analyse_orbit(ExactFlow(field), orbit, true);
}

double periodicity_residual(const Vector& u0, const Vector& v0, const Vector& u1,
                            const Vector& v1, double T, double length) {
  return std::max((u1 - u0).norm() / length, (v1 - v0).norm() / (length * 2 * M_PI / T));
}

void analyse_orbit(const ExactFlow& flow, PeriodicOrbit& orbit, bool autonomous) {
  const ReducedField& field = flow.field();
  const double T = orbit.period;
  constexpr int kSamples = 256;
  std::vector<double> times(kSamples);
  for (int k = 0; k < kSamples; ++k) times[k] = T * k / kSamples;
  const FlowResult r = flow.integrate(orbit.u0, orbit.v0, T, true, times);

  orbit.periodicity_residual = periodicity_residual(orbit.u0, orbit.v0, r.u, r.v, T,
                                                    std::max(orbit.u0.norm(), periodic_tiny));
  const Index n = field.size();
  double c = 0;
  for (Index k = 0; k < kSamples; ++k)
    c = std::max(c, field.complementarity_residual(r.samples.col(k).head(n),
                                                   flow.forcing().shift(times[k])));
  orbit.complementarity_residual = c;
  // Moving contacts (method.md §8) shift the relation's offset e(t).
  const FlowForcing& forcing = flow.forcing();
  orbit.energy_start =
      field.energies(orbit.u0, orbit.v0, forcing.shift(0), forcing.shift(0, 1));
  orbit.energy_end = field.energies(r.u, r.v, forcing.shift(T), forcing.shift(T, 1));
  orbit.switches = r.switches;

  // Time with a closed contact: sum over the intervals between switches.
  auto any_closed = [](const ActiveSet& s) { return std::find(s.begin(), s.end(), true) != s.end(); };
  ActiveSet current = field.active_set(orbit.u0, forcing.shift(0));
  double t_prev = 0;
  orbit.contact_time = 0;
  for (const auto& s : r.switches) {
    if (any_closed(current)) orbit.contact_time += s.t - t_prev;
    current = s.after, t_prev = s.t;
  }
  if (any_closed(current)) orbit.contact_time += T - t_prev;

  orbit.monodromy = r.monodromy;
  orbit.autonomous = autonomous;
  if (autonomous) {
    orbit.multipliers = floquet_multipliers(r.monodromy, orbit.v0, field.acceleration(orbit.u0),
                                            orbit.trivial_residual);
    orbit.stable = std::abs(orbit.multipliers.front()) <= 1 + kAutonomousStabilityMargin;
    return;
  }
  // Forced: no time shift leaves the orbit invariant, so no trivial
  // multiplier to split off.
  orbit.trivial_residual = 0;
  orbit.multipliers = floquet_multipliers(r.monodromy, Vector::Zero(n), Vector::Zero(n),
                                          orbit.trivial_residual);
  orbit.stable = std::abs(orbit.multipliers.front()) < 1;
}

std::string summary(const PeriodicOrbit& orbit) {
  std::ostringstream s;
  s.precision(12);
  s << "period " << orbit.period << "\n"
    << "energy " << orbit.energy_start(3) << " (kinetic " << orbit.energy_start(0)
    << ", elastic " << orbit.energy_start(1) << ", load " << orbit.energy_start(2) << ")\n"
    << "energy change over one period " << orbit.energy_end(3) - orbit.energy_start(3) << "\n"
    << "contact time " << orbit.contact_time << " (" << orbit.switches.size()
    << " switches per period)\n";
  s.precision(3);
  s << "periodicity residual " << orbit.periodicity_residual << "\n"
    << "complementarity residual " << orbit.complementarity_residual << "\n"
    << "trivial multiplier residual " << orbit.trivial_residual << "\n"
    << "Newton iterations " << orbit.iterations << "\n"
    << "largest Floquet multipliers";
  for (std::size_t k = 0; k < std::min<std::size_t>(6, orbit.multipliers.size()); ++k)
    s << " " << orbit.multipliers[k].real() << (orbit.multipliers[k].imag() >= 0 ? "+" : "")
      << orbit.multipliers[k].imag() << "i";
  // The verdict with the criterion that gave it: they differ for autonomous
  // and forced orbits (analyse_orbit).
  s << "\nstability ";
  if (orbit.autonomous)
    s << (orbit.stable ? "stable (autonomous orbit: every |multiplier| <= 1 + "
                       : "unstable (autonomous orbit: a |multiplier| > 1 + ")
      << kAutonomousStabilityMargin << ", the trivial multiplier 1 of the time shift included)";
  else
    s << (orbit.stable ? "stable (forced orbit: every |multiplier| < 1; no trivial multiplier)"
                       : "unstable (forced orbit: a |multiplier| >= 1; no trivial multiplier)");
  s << "\n";
  return s.str();
}

}  // namespace nbm
