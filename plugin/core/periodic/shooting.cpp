#include "periodic/shooting.hpp"

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

PeriodicOrbit shoot(const ReducedField& field, const Vector& u0, const Vector& v0, double T,
                    const ShootingOptions& o) {
  const Index n = field.size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("shooting: initial state of size " + std::to_string(u0.size()) +
                     ", expected " + std::to_string(n) + " interior dofs");
  if (!u0.allFinite() || !v0.allFinite()) throw InputError("shooting: non-finite initial state");
  if (!(T > 0) || !std::isfinite(T)) throw InputError("shooting: the period guess must be > 0");
  if (o.probe < 0 || o.probe >= n)
    throw InputError("shooting: probe " + std::to_string(o.probe) + " out of range [0, " +
                     std::to_string(n) + ")");
  if (!(o.tolerance > 0)) throw InputError("shooting: tolerance must be > 0");
  if (o.arclength) {
    const auto& a = *o.arclength;
    if (a.tangent.size() != 2 * n + 1 || a.anchor.size() != 2 * n + 1 || !a.tangent.allFinite() ||
        !a.anchor.allFinite() || a.tangent.norm() == 0)
      throw InputError("shooting: the arclength condition needs a non-zero finite tangent and a "
                       "finite anchor of " + std::to_string(2 * n + 1) + " entries");
  }

  const ExactFlow flow(field);
  // The arclength condition is judged relative to |tangent| |anchor|.
  const double target = o.arclength ? 0
                        : std::isnan(o.amplitude)
                            ? amplitude_value(field, o, u0, o.half_period ? 0 * v0 : v0, T)
                            : o.amplitude;
  const double amp_scale =
      o.arclength ? o.arclength->tangent.norm() * std::max(o.arclength->anchor.norm(), periodic_tiny)
                  : std::max(std::abs(target), periodic_tiny);
  const bool half = o.half_period;

  // Unknowns y = (u0, v0, T) or, for half-period shooting, (u0, T/2).
  Vector y(half ? n + 1 : 2 * n + 1);
  if (half)
    y << u0, 0.5 * T;
  else
    y << u0, v0, T;
  auto unpack = [&](const Vector& y, Vector& u, Vector& v, double& period) {
    u = y.head(n);
    v = half ? Vector::Zero(n) : Vector(y.segment(n, n));
    period = half ? 2 * y(n) : y(2 * n);
  };

  // Residual R (and Jacobian J) at y, rows scaled like the periodicity
  // residual (displacements by |u0|, velocities by |u0| 2 pi / T, the
  // amplitude condition by its target), so that the least-squares steps
  // minimise what convergence is judged on: `merit`, the largest scaled
  // entry; `size`, the 2-norm the line search decreases.
  using Evaluation = GaussNewtonEvaluation;
  auto evaluate = [&](const Vector& y, bool jacobian) {
    Evaluation e;
    Vector u, v;
    double period;
    unpack(y, u, v, period);
    if (!(period > 0) || !u.allFinite() || !v.allFinite()) return e;
    const FlowResult r = flow.integrate(u, v, half ? 0.5 * period : period, jacobian);
    const double amp = amplitude_value(field, o, u, v, period) - target;
    const double us = std::max(u.norm(), periodic_tiny), vs = us * 2 * M_PI / period;
    Vector weight;
    if (half) {
      e.R.resize(n + 1);
      e.R << r.v, amp;
      weight = Vector::Constant(n + 1, 1 / vs);
      e.merit = std::max(r.v.norm() / vs, std::abs(amp) / amp_scale);
    } else {
      e.R.resize(2 * n + 2);
      e.R << r.u - u, r.v - v, v(o.probe), amp;
      weight = Vector::Constant(2 * n + 2, 1 / vs);
      weight.head(n).setConstant(1 / us);
      e.merit = std::max({periodicity_residual(u, v, r.u, r.v, period, us),
                          std::abs(v(o.probe)) / vs,
                          std::abs(amp) / amp_scale});
    }
    weight(weight.size() - 1) = 1 / amp_scale;
    e.R = weight.cwiseProduct(e.R);
    e.size = e.R.norm();
    if (!jacobian) return e;
    // Gradient of the amplitude condition in (u0, v0, T).
    const Vector grad =
        o.arclength ? o.arclength->tangent : amplitude_gradient(field, o.kind, o.probe, u, v);
    if (half) {
      // d v(T/2) / d(u0, T/2) = (monodromy_vu, a(T/2)).
      e.J = Matrix::Zero(n + 1, n + 1);
      e.J.topLeftCorner(n, n) = r.monodromy.bottomLeftCorner(n, n);
      e.J.topRightCorner(n, 1) = r.a;
      e.J.bottomLeftCorner(1, n) = grad.head(n).transpose();
      e.J(n, n) = 2 * grad(2 * n);
    } else {
      e.J = Matrix::Zero(2 * n + 2, 2 * n + 1);
      e.J.topLeftCorner(2 * n, 2 * n) = r.monodromy - Matrix::Identity(2 * n, 2 * n);
      e.J.block(0, 2 * n, n, 1) = r.v;
      e.J.block(n, 2 * n, n, 1) = r.a;
      e.J(2 * n, n + o.probe) = 1;
      e.J.row(2 * n + 1) = grad.transpose();
    }
    e.J = weight.asDiagonal() * e.J;
    return e;
  };

  // Damped Gauss-Newton (gauss_newton.hpp): the period map is only
  // piecewise smooth, and a full step from a rough guess can jump to
  // another branch (a multiple of the period).
  GaussNewtonOptions gn;
  gn.period_index = y.size() - 1;
  gn.tolerance = o.tolerance;
  gn.max_iterations = o.max_iterations;
  gn.solver = GaussNewtonOptions::Solver::orthogonal;
  gn.name = "shooting";
  const GaussNewtonResult solution = gauss_newton(evaluate, y, gn);
  PeriodicOrbit orbit;
  orbit.residual_history = solution.merits;
  orbit.iterations = solution.iterations;
  y = solution.y;
  unpack(y, orbit.u0, orbit.v0, orbit.period);
  analyse_orbit(field, orbit);
  return orbit;
}

}  // namespace nbm
