#include "periodic/shooting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Gradient of the total energy with respect to (u_O, v_O): the reduced
// internal force minus load and the reduced momentum, on the region of u_O.
Vector energy_gradient(const ReducedField& field, const Vector& u, const Vector& v) {
  const auto r_held = field.region(field.active_set(u));
  const Region& r = *r_held;
  Vector g(2 * u.size());
  g << r.K * u - r.f, r.M * v;
  return g;
}

double amplitude_value(const ReducedField& field, const ShootingOptions& o, const Vector& u,
                       const Vector& v, double period) {
  if (o.arclength) {
    const Vector& t = o.arclength->tangent;
    const Vector& y = o.arclength->anchor;
    const Index n = u.size();
    return t.head(n).dot(u - y.head(n)) + t.segment(n, n).dot(v - y.segment(n, n)) +
           t(2 * n) * (period - y(2 * n));
  }
  return amplitude_value(field, o.kind, o.probe, u, v, period);
}

// The guess and the options, checked (InputError naming them).
void check(const PeriodicProblem& problem, const Vector& u0, const Vector& v0, double T,
           const ShootingOptions& o, const std::string& name) {
  problem.check_guess(u0, v0, T, name);
  const Index n = problem.field().size();
  if (!(o.tolerance > 0)) throw InputError(name + ": tolerance must be > 0");
  if (o.transient_periods < 0)
    throw InputError(name + ": transient_periods must be >= 0, got " +
                     std::to_string(o.transient_periods));
  if (problem.forced()) {
    if (o.half_period || o.arclength || !std::isnan(o.amplitude))
      throw InputError(name + ": half_period, amplitude and arclength conditions are an "
                       "autonomous orbit's (the excitation fixes a forced orbit's period and "
                       "time origin)");
  } else {
    if (o.probe < 0 || o.probe >= n)
      throw InputError("shooting: probe " + std::to_string(o.probe) + " out of range [0, " +
                       std::to_string(n) + ")");
    if (o.arclength) {
      const auto& a = *o.arclength;
      if (a.tangent.size() != 2 * n + 1 || a.anchor.size() != 2 * n + 1 ||
          !a.tangent.allFinite() || !a.anchor.allFinite() || a.tangent.norm() == 0)
        throw InputError("shooting: the arclength condition needs a non-zero finite tangent and "
                         "a finite anchor of " + std::to_string(2 * n + 1) + " entries");
    }
  }
}

}  // namespace

double amplitude_value(const ReducedField& field, ShootingOptions::Amplitude kind, Index probe,
                       const Vector& u, const Vector& v, double period) {
  switch (kind) {
    case ShootingOptions::Amplitude::displacement: return u(probe);
    case ShootingOptions::Amplitude::energy: return field.energies(u, v)(3);
    case ShootingOptions::Amplitude::period: break;
  }
  return period;
}

Vector amplitude_gradient(const ReducedField& field, ShootingOptions::Amplitude kind,
                          Index probe, const Vector& u, const Vector& v) {
  const Index n = u.size();
  Vector grad = Vector::Zero(2 * n + 1);
  switch (kind) {
    case ShootingOptions::Amplitude::displacement: grad(probe) = 1; break;
    case ShootingOptions::Amplitude::energy: grad.head(2 * n) = energy_gradient(field, u, v); break;
    case ShootingOptions::Amplitude::period: grad(2 * n) = 1; break;
  }
  return grad;
}

PeriodicOrbit shoot(const PeriodicProblem& problem, const Vector& u0, const Vector& v0, double T,
                    const ShootingOptions& o) {
  const ReducedField& field = problem.field();
  const ExactFlow& flow = problem.flow();
  const bool forced = problem.forced();
  const std::string name = forced ? "forced orbit" : "shooting";
  check(problem, u0, v0, T, o, name);
  const Index n = field.size();
  Vector u_start = u0, v_start = v0;
  if (o.transient_periods > 0) {
    const FlowResult settled = flow.integrate(u0, v0, o.transient_periods * T, false);
    u_start = settled.u, v_start = settled.v;
  }

  const bool half = o.half_period;
  // The conditions of an autonomous orbit: the phase v0[probe] = 0 (implied
  // by v0 = 0 with half-period shooting) and the amplitude condition, judged
  // relative to its target (the arclength condition: to |tangent| |anchor|).
  const double target = forced || o.arclength ? 0
                         : std::isnan(o.amplitude)
                             ? amplitude_value(field, o, u_start, half ? 0 * v_start : v_start, T)
                             : o.amplitude;
  const double amp_scale =
      o.arclength ? o.arclength->tangent.norm() * std::max(o.arclength->anchor.norm(), periodic_tiny)
                  : std::max(std::abs(target), periodic_tiny);
  // A forced orbit's rows are scaled by a length fixed from the guess (the
  // larger of |u0| and |u(T)|, non-zero from a guess at rest), so that the
  // line search compares like with like; an autonomous orbit's by its own
  // |u0|, which the amplitude condition keeps from vanishing.
  double fixed_length = 0;
  if (forced) {
    const FlowResult first = flow.integrate(u_start, v_start, T, false);
    fixed_length = std::max({u_start.norm(), first.u.norm(), periodic_tiny});
  }

  // Unknowns y = (u0, v0) (forced), (u0, v0, T) or, for half-period
  // shooting, (u0, T/2).
  Vector y(forced ? 2 * n : half ? n + 1 : 2 * n + 1);
  if (forced)
    y << u_start, v_start;
  else if (half)
    y << u_start, 0.5 * T;
  else
    y << u_start, v_start, T;
  auto unpack = [&](const Vector& y, Vector& u, Vector& v, double& period) {
    u = y.head(n);
    v = half ? Vector::Zero(n) : Vector(y.segment(n, n));
    period = forced ? T : half ? 2 * y(n) : y(2 * n);
  };

  // Residual R (and Jacobian J) at y, rows scaled like the periodicity
  // residual (displacements by a length, velocities by that length times
  // 2 pi / T, the amplitude condition by its target), so that the
  // least-squares steps minimise what convergence is judged on: `merit`,
  // the largest scaled entry; `size`, the 2-norm the line search decreases.
  auto evaluate = [&](const Vector& y, bool jacobian) {
    GaussNewtonEvaluation e;
    Vector u, v;
    double period;
    unpack(y, u, v, period);
    if (!(period > 0) || !u.allFinite() || !v.allFinite()) return e;
    const FlowResult r = flow.integrate(u, v, half ? 0.5 * period : period, jacobian);
    const double us = forced ? fixed_length : std::max(u.norm(), periodic_tiny);
    const double vs = us * 2 * M_PI / period;
    const Index rows = forced ? 2 * n : half ? n + 1 : 2 * n + 2;
    Vector weight = Vector::Constant(rows, 1 / vs);
    double amp = 0;
    e.R.resize(rows);
    if (half) {
      amp = amplitude_value(field, o, u, v, period) - target;
      e.R << r.v, amp;
      e.merit = std::max(r.v.norm() / vs, std::abs(amp) / amp_scale);
    } else {
      weight.head(n).setConstant(1 / us);
      e.R.head(2 * n) << r.u - u, r.v - v;
      // Convergence is judged on the orbit's own size (for a forced orbit
      // the larger of |u0| and |u(T)|, floored), the scaling on `us`.
      const double length =
          forced ? std::max({u.norm(), r.u.norm(), periodic_tiny}) : us;
      e.merit = periodicity_residual(u, v, r.u, r.v, period, length);
      if (!forced) {
        amp = amplitude_value(field, o, u, v, period) - target;
        e.R.tail(2) << v(o.probe), amp;
        e.merit = std::max({e.merit, std::abs(v(o.probe)) / vs, std::abs(amp) / amp_scale});
      }
    }
    if (!forced) weight(rows - 1) = 1 / amp_scale;
    e.R = weight.cwiseProduct(e.R);
    e.size = e.R.norm();
    if (!jacobian) return e;
    // Gradient of the amplitude condition in (u0, v0, T).
    const Vector grad = forced ? Vector()
                        : o.arclength ? o.arclength->tangent
                                      : amplitude_gradient(field, o.kind, o.probe, u, v);
    if (half) {
      // d v(T/2) / d(u0, T/2) = (monodromy_vu, a(T/2)).
      e.J = Matrix::Zero(n + 1, n + 1);
      e.J.topLeftCorner(n, n) = r.monodromy.bottomLeftCorner(n, n);
      e.J.topRightCorner(n, 1) = r.a;
      e.J.bottomLeftCorner(1, n) = grad.head(n).transpose();
      e.J(n, n) = 2 * grad(2 * n);
    } else {
      e.J = Matrix::Zero(rows, y.size());
      e.J.topLeftCorner(2 * n, 2 * n) = r.monodromy - Matrix::Identity(2 * n, 2 * n);
      if (!forced) {
        e.J.block(0, 2 * n, n, 1) = r.v;
        e.J.block(n, 2 * n, n, 1) = r.a;
        e.J(2 * n, n + o.probe) = 1;
        e.J.row(2 * n + 1) = grad.transpose();
      }
    }
    e.J = weight.asDiagonal() * e.J;
    return e;
  };

  // Damped Gauss-Newton (gauss_newton.hpp): the period map is only
  // piecewise smooth, and a full step from a rough guess can jump to
  // another branch (a multiple of the period). An autonomous system is
  // overdetermined by one consistent equation (least squares, a trust
  // region on the period); a forced one is square (LU).
  GaussNewtonOptions gn;
  gn.period_index = forced ? -1 : y.size() - 1;
  gn.tolerance = o.tolerance;
  gn.max_iterations = o.max_iterations;
  gn.solver = forced ? GaussNewtonOptions::Solver::householder
                     : GaussNewtonOptions::Solver::orthogonal;
  gn.name = name;
  if (forced) gn.context = "at omega = " + std::to_string(flow.forcing().Omega.front()) + " ";
  const GaussNewtonResult solution = gauss_newton(evaluate, y, gn);
  PeriodicOrbit orbit;
  orbit.residual_history = solution.merits;
  orbit.iterations = solution.iterations;
  unpack(solution.y, orbit.u0, orbit.v0, orbit.period);
  analyse_orbit(flow, orbit, !forced);
  return orbit;
}

}  // namespace nbm
