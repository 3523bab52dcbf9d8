#include "time/central_difference_stepper.hpp"

#include <cmath>
#include <sstream>

#include "base/errors.hpp"

namespace nbm {
namespace {

SparseMatrix diagonal_matrix(const Vector& d) {
  SparseMatrix D(d.size(), d.size());
  std::vector<Triplet> t;
  for (Index i = 0; i < d.size(); ++i) t.emplace_back(i, i, d(i));
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

const Damping& check_explicit_damping(const Damping& damping) {
  if (damping.b_K != 0 || damping.has_matrix())
    throw InputError("damping: the explicit scheme takes only mass-proportional damping (a_M, "
                     "on the lumped mass); stiffness-proportional (b_K) or assembled damping "
                     "would need a factorization of M + dt/2 C: use scheme \"newmark\"");
  return damping;
}

}  // namespace

double max_eigenvalue(const SparseMatrix& K, const Vector& m) {
  const Index n = m.size();
  if (n == 0) return 0;
  // Gershgorin on the symmetric form D^{-1/2} K D^{-1/2}.
  const Vector s = m.cwiseSqrt().cwiseInverse();
  Vector row = Vector::Zero(n);
  for (Index j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      row(it.row()) += std::abs(it.value()) * s(it.row()) * s(j);
  const double gershgorin = row.maxCoeff();

  // Power iteration on D^{-1} K from the most oscillating start (the highest
  // modes alternate in sign from dof to dof).
  Vector x(n);
  for (Index i = 0; i < n; ++i) x(i) = (i % 2 ? 1.0 : -1.0) * (1.0 + 1e-3 * (i % 7));
  double rayleigh = 0;
  for (int it = 0; it < 2000; ++it) {
    const Vector Kx = K * x;
    const double r = x.dot(Kx) / x.dot(m.cwiseProduct(x));
    x = Kx.cwiseQuotient(m);
    x /= x.norm();
    const bool converged = std::abs(r - rayleigh) <= 1e-10 * std::abs(r);
    rayleigh = r;
    if (converged) break;
  }
  return std::min(gershgorin, rayleigh);
}

CentralDifferenceStepper::CentralDifferenceStepper(const ContactProblem& problem, double dt,
                                                   const Damping& damping)
    : NbmStepper(problem, dt, check_explicit_damping(damping)),
      lumped_(diagonal_matrix(problem.lumped_mass())),
      solver_(make_diagonal_inverse(lumped_.diagonal(), "M (row-sum lumped)"),
              problem.constraint_basis()),
      critical_dt_(2.0 / std::sqrt(max_eigenvalue(problem.K(), lumped_.diagonal()))),
      a_M_(damping.a_M) {
  // C on the scheme's own (lumped) mass, for the step and the dissipation.
  if (damped()) C_ = a_M_ * lumped_;
  if (dt > critical_dt_) {
    std::ostringstream msg;
    msg << "dt: " << dt << " exceeds the critical time step " << critical_dt_
        << " of the explicit scheme (2/omega_max with lumped mass); reduce dt or use "
           "scheme=\"newmark\"";
    throw InputError(msg.str());
  }
}

void CentralDifferenceStepper::solve_acceleration(const ContactLoad& load) {
  solve_acceleration(load, v_, 0.0);
}

void CentralDifferenceStepper::solve_acceleration(const ContactLoad& load, const Vector& v,
                                                  double dt_c) {
  r_ = load.F;
  r_.noalias() -= problem_.K() * u_;
  if (damped()) {
    // (1 + a_M dt_c) M a = r - a_M M v + G^T mu: M's solve of the scaled r.
    r_.noalias() -= C_ * v;
    r_ /= 1 + a_M_ * dt_c;
  }
  acceleration_constraint(load, active_, h_accel_);
  solver_.solve(active_, r_, h_accel_, a_);
}

StepReport CentralDifferenceStepper::advance_interior(const ContactLoad& next) {
  StepReport report;
  report.active_set_iterations = 1;
  a_old_ = a_;
  u_ += dt_ * v_ + (0.5 * dt_ * dt_) * a_;
  active_ = boundary_.enforce(u_, next.F, next.obstacle.g, active_).active;
  if (damped()) v_tilde_ = v_ + (0.5 * dt_) * a_old_;  // the velocity the damping sees
  solve_acceleration(next, v_tilde_, 0.5 * dt_);
  v_ += (0.5 * dt_) * (a_old_ + a_);
  return report;
}

}  // namespace nbm
