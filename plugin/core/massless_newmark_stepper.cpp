#include "massless_newmark_stepper.hpp"

#include <string>

#include "errors.hpp"
#include "mass_solve.hpp"

namespace nbm {
namespace {

// Y of at most this many entries (3 MB) is kept whatever its size next to L:
// its products run from the cache, cheaper than a second solve.
constexpr double kCachedColumnEntries = 1 << 18;

void check_massless(const ContactProblem& problem) {
  if (!problem.massless_boundary())
    throw InputError("the massless-boundary Newmark scheme needs M_CC = 0 and M_CO = 0 "
                     "(mass redistribution)");
}

// The massless boundary's contact dofs carry no damping of their own
// (header): an assembled damping matrix must leave them out.
const Damping& check_boundary_undamped(const ContactProblem& problem, const Damping& damping) {
  if (!damping.has_matrix()) return damping;
  std::vector<char> is_contact(problem.size(), 0);
  for (Index c : problem.contact_index()) is_contact[c] = 1;
  const SparseMatrix& C = damping.C_user;
  if (C.rows() != problem.size()) return damping;  // the Stepper reports the size
  for (Index j = 0; j < C.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C, j); it; ++it)
      if ((is_contact[it.row()] || is_contact[j]) && it.value() != 0.0)
        throw InputError("damping matrix: an entry couples a contact dof; with the massless "
                         "boundary (mass redistribution) the contact dofs carry no damping of "
                         "their own: expected C_CC = 0, C_CO = 0 (Rayleigh's b_K K is allowed)");
  return damping;
}

}  // namespace

MasslessNewmarkStepper::MasslessNewmarkStepper(const ContactProblem& problem, double dt,
                                               double beta, double gamma,
                                               const Damping& damping, ContactColumns columns)
    : NbmStepper(problem, dt, check_boundary_undamped(problem, damping)),
      iteration_((check_massless(problem), problem), dt, beta, gamma, C_),
      S_(*iteration_.S()),
      contact_row_scale_(1 + iteration_.gamma_dt() * damping.b_K / iteration_.beta_dt2()) {
  const SparseMatrix& E_C = problem.constraint_basis().rightCols(problem.n_contact());
  const double entries = S_.forward_entries(E_C);
  keep_columns_ = columns == ContactColumns::kAuto
                      ? entries <= kCachedColumnEntries || 8 * entries <= S_.factor_entries()
                      : columns == ContactColumns::kKept;
  Matrix compliance;  // W_CC
  if (keep_columns_)
    Y_ = iteration_.contact_columns(&compliance);
  else
    compliance = iteration_.contact_compliance();
  compliance *= iteration_.beta_dt2();
  lcp_ = std::make_unique<CachedLcpSolver>(std::move(compliance));
}

void MasslessNewmarkStepper::solve_acceleration(const ContactLoad& load) {
  // M + E_C E_C^T is definite and block diagonal (M_CO = 0): its solve gives
  // a_O = M_OO^-1 r_O and a_C = 0, then projected onto the nodal boundary
  // relation (v_C = A v_O differentiated).
  const Index nc = problem_.n_contact();
  const SparseMatrix& E_C = problem_.constraint_basis().rightCols(nc);
  const SparseMatrix M_reg = problem_.M() + SparseMatrix(E_C * E_C.transpose());
  Vector r = load.F - problem_.K() * u_;
  if (damped()) r -= C_ * v_;
  for (Index c : problem_.contact_index()) r(c) = 0.0;
  a_ = solve_mass(M_reg, r, "M (interior block)");
  acceleration_constraint(load, active_, h_accel_);
  boundary_.project(a_, active_, h_accel_);
}

const LcpResult& MasslessNewmarkStepper::contact_forces(const Vector& g) {
  // z = lambda, w = gap = g - u_hat_C - bdt2 (a_free_C - W_CC lambda); the
  // guess: lambda = 0 (z free) where contact is open.
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();
  q_.resize(nc);
  for (Index k = 0; k < nc; ++k) q_(k) = (g(k) - u_hat_(c[k])) - iteration_.beta_dt2() * a_C_(k);
  open_.resize(nc);
  for (Index k = 0; k < nc; ++k) open_[k] = !active_[k];
  return lcp_->solve(q_, open_);
}

const LcpResult& MasslessNewmarkStepper::accelerate(const Vector& g, Vector& a) {
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();
  a_C_.resize(nc);
  if (keep_columns_) {
    S_.forward_in_place(a);  // y
    for (Index k = 0; k < nc; ++k) a_C_(k) = Y_.col(k).dot(a);
    const LcpResult& lcp = contact_forces(g);
    for (Index k = 0; k < nc; ++k)
      if (lcp.z(k) != 0) a -= lcp.z(k) * Y_.col(k);
    S_.backward_in_place(a);
    return lcp;
  }
  S_.solve_in_place(a);
  for (Index k = 0; k < nc; ++k) a_C_(k) = a(c[k]);
  const LcpResult& lcp = contact_forces(g);
  if (!(lcp.z.array() != 0.0).any()) return lcp;  // free flight: the plain step
  correction_.setZero(a.size());
  for (Index k = 0; k < nc; ++k) correction_(c[k]) = -lcp.z(k);
  S_.solve_in_place(correction_);
  a += correction_;
  return lcp;
}

StepReport MasslessNewmarkStepper::advance_interior(const ContactLoad& next) {
  const Vector& g = next.obstacle.g;
  const double bdt2 = iteration_.beta_dt2();
  iteration_.predict(u_, v_, a_, u_hat_, v_pred_);
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();

  // In acceleration form, u = u_hat + bdt2 a (no cancellation at small dt):
  // S a = F - K u_hat - E_C lambda with lambda from the LCP (header).
  Vector& a = acceleration_;
  a = next.F;
  a.noalias() -= problem_.K() * u_hat_;
  if (damped()) {
    // Interior rows: - C v~; contact rows: s (F - K u_hat)_C (header).
    Cv_.noalias() = C_ * v_pred_;
    for (Index k = 0; k < nc; ++k) Cv_(c[k]) = (1 - contact_row_scale_) * a(c[k]);
    a -= Cv_;
  }
  const LcpResult& lcp = accelerate(g, a);

  u_ = u_hat_ + bdt2 * a;
  a_.swap(a);  // acceleration_: a workspace again from here
  iteration_.correct_velocity(v_pred_, a_, v_);
  // The LCP's z is lambda: z_k = 0 (lcp.active) where contact k is open.
  for (Index k = 0; k < nc; ++k) active_[k] = !lcp.active[k];
  // Closed contacts sit exactly on the obstacle, not only to the round-off of
  // the solves (which grows with beta dt^2 |K|).
  for (Index k = 0; k < nc; ++k)
    if (active_[k]) u_(c[k]) = g(k);
  StepReport report;
  report.active_set_iterations = 1;
  return report;
}

}  // namespace nbm
