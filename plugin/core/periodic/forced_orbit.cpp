#include "periodic/forced_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace nbm {

double forced_period(const ExactFlow& flow, int subharmonic) {
  if (flow.forcing().Omega.empty())
    throw InputError("forced orbit: the flow has no harmonic load (no excitation frequency)");
  if (subharmonic < 1)
    throw InputError("forced orbit: the subharmonic order m must be >= 1, got " +
                     std::to_string(subharmonic));
  return 2 * M_PI * subharmonic / flow.forcing().Omega.front();
}

PeriodicOrbit shoot_forced(const ExactFlow& flow, const Vector& u0, const Vector& v0,
                           const ForcedShootingOptions& o) {
  const Index n = flow.field().size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("forced orbit: initial state of size " + std::to_string(u0.size()) + " and " +
                     std::to_string(v0.size()) + ", expected " + std::to_string(n) +
                     " interior dofs");
  if (!u0.allFinite() || !v0.allFinite())
    throw InputError("forced orbit: non-finite initial state");
  if (!(o.tolerance > 0)) throw InputError("forced orbit: tolerance must be > 0");
  if (o.transient_periods < 0)
    throw InputError("forced orbit: transient_periods must be >= 0, got " +
                     std::to_string(o.transient_periods));
  const double T = forced_period(flow, o.subharmonic);
  Vector u_start = u0, v_start = v0;
  if (o.transient_periods > 0) {
    const FlowResult settled = flow.integrate(u0, v0, o.transient_periods * T, false);
    u_start = settled.u, v_start = settled.v;
  }

  // Rows scaled as the periodicity residual (displacements by a length,
  // velocities by that length times 2 pi / T). The length is fixed from the
  // guess so that the line search compares like with like; it is the larger
  // of |u0| and |u(T)|, non-zero from a guess at rest.
  const FlowResult first = flow.integrate(u_start, v_start, T, false);
  const double us = std::max({u_start.norm(), first.u.norm(), periodic_tiny});
  const double vs = us * 2 * M_PI / T;
  Vector weight(2 * n);
  weight.head(n).setConstant(1 / us);
  weight.tail(n).setConstant(1 / vs);

  auto evaluate = [&](const Vector& y, bool jacobian) {
    GaussNewtonEvaluation e;
    const Vector u = y.head(n), v = y.tail(n);
    if (!y.allFinite()) return e;
    const FlowResult r = flow.integrate(u, v, T, jacobian);
    e.R.resize(2 * n);
    e.R << r.u - u, r.v - v;
    const double ls = std::max({u.norm(), r.u.norm(), periodic_tiny});
    e.merit = periodicity_residual(u, v, r.u, r.v, T, ls);
    e.R = weight.cwiseProduct(e.R);
    e.size = e.R.norm();
    if (jacobian)
      e.J = weight.asDiagonal() * (r.monodromy - Matrix::Identity(2 * n, 2 * n));
    return e;
  };

  Vector y(2 * n);
  y << u_start, v_start;
  GaussNewtonOptions gn;
  gn.period_index = -1;  // the period is fixed: no trust region on it
  gn.tolerance = o.tolerance;
  gn.max_iterations = o.max_iterations;
  gn.solver = GaussNewtonOptions::Solver::householder;  // square: LU
  gn.name = "forced orbit";
  gn.context = "at omega = " + std::to_string(flow.forcing().Omega.front()) + " ";
  const GaussNewtonResult solution = gauss_newton(evaluate, y, gn);

  PeriodicOrbit orbit;
  orbit.u0 = solution.y.head(n);
  orbit.v0 = solution.y.tail(n);
  orbit.period = T;
  orbit.iterations = solution.iterations;
  orbit.residual_history = solution.merits;
  analyse_orbit(flow, orbit, false);
  return orbit;
}

}  // namespace nbm
