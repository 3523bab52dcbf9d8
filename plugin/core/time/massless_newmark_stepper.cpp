#include "time/massless_newmark_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"
#include "linalg/mass_solve.hpp"

namespace nbm {
namespace {

// The interior mass is solved with on every step the energy-stable step
// balances (return_to_relation): conjugate gradients take a few tens of
// products with it (48 on the plate of bench/energy_cost.cpp), a factor one
// substitution pair. It is factored after this many solves, if S's factor
// (about the size of the mass's) has at most kFactoredMassEntries entries
// (256 MB): beside the 15 GB factor of the 1e6-dof 3D block a second one
// would not fit, and the iterations stay.
constexpr int kFactorMassAfter = 8;
constexpr double kFactoredMassEntries = 1 << 25;

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
                                               const SchemeParameters& scheme,
                                               const Damping& damping, ContactColumns columns,
                                               EnergyControl energy)
    : NbmStepper(problem, dt, check_boundary_undamped(problem, damping), energy,
                 scheme.average_acceleration() && damping.b_K == 0),
      iteration_((check_massless(problem), problem), dt, scheme, C_),
      S_(*iteration_.S()),
      contact_row_scale_(1 + iteration_.gamma_dt() * damping.b_K / iteration_.beta_dt2()) {
  const SparseMatrix& E_C = problem.constraint_basis().rightCols(problem.n_contact());
  // M + E_C E_C' is definite and block diagonal (M_CO = 0): its solves give
  // M_OO^-1 r_O and leave the contact rows at r_C.
  interior_mass_ = problem.M() + SparseMatrix(E_C * E_C.transpose());
  mass_solver_ = std::make_unique<MassSolver>(
      interior_mass_, "M (interior block)",
      S_.factor_entries() <= kFactoredMassEntries ? kFactorMassAfter : 0);
  keep_columns_ = nbm::keeps_contact_columns(columns, S_, E_C);
  Matrix compliance;  // W_CC
  if (keep_columns_)
    Y_ = iteration_.contact_columns(&compliance);
  else
    compliance = iteration_.contact_compliance();
  compliance *= iteration_.beta_dt2();
  lcp_ = std::make_unique<CachedLcpSolver>(std::move(compliance));
  uses_scheme(iteration_);
}

void MasslessNewmarkStepper::solve_acceleration(const ContactLoad& load) {
  // a_O = M_OO^-1 r_O and a_C = 0, then projected onto the nodal boundary
  // relation (v_C = A v_O differentiated).
  Vector r = load.F - problem_.K() * u_;
  if (damped()) r -= C_ * v_;
  for (Index c : problem_.contact_index()) r(c) = 0.0;
  mass_solver_->solve(r, a_);
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

void MasslessNewmarkStepper::return_to_relation(const Vector& F, const Vector& g) {
  // u_C of a step (5.2) is admissible (gap >= 0) but satisfies the relation
  // at the step's middle; the relation's u_C minimizes the elastic energy
  // over the admissible u_C at this u_O, so moving there only lowers the
  // energy (method.md §5.1). a_O then changes by -M_OO^-1 K_OC du_C.
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();
  u_C_before_.resize(nc);
  for (Index k = 0; k < nc; ++k) u_C_before_(k) = u_(c[k]);
  const LcpResult& relation = boundary_.enforce(u_, F, g, active_);
  for (Index k = 0; k < nc; ++k) active_[k] = relation.active[k];
  stiffness_change_.setZero(u_.size());
  for (Index k = 0; k < nc; ++k) {
    const double du = u_(c[k]) - u_C_before_(k);
    if (du != 0) stiffness_change_ += du * problem_.K().col(c[k]);
  }
  for (Index k = 0; k < nc; ++k) stiffness_change_(c[k]) = 0.0;
  mass_solver_->solve(stiffness_change_, correction_);
  a_ -= correction_;
}

void MasslessNewmarkStepper::prepare_blend(const Vector& F) {
  // Along the way from (5.2) (mid_) to the trapezoidal step (trap_),
  // u_lin = u_mid + theta du and v = v_mid + theta dv are affine in theta,
  // and the return to the relation moves u_C only: u = u_lin + E_C delta.
  // Every term of the balance of u_lin and v is a quadratic in theta,
  // formed here once with four products with K and M (six with damping).
  du_ = u_trap_ - u_mid_;
  dv_ = v_trap_ - v_mid_;
  Ku_mid_.noalias() = problem_.K() * u_mid_;
  Kdu_.noalias() = problem_.K() * du_;
  Mv_.noalias() = problem_.M() * v_mid_;
  Mdv_.noalias() = problem_.M() * dv_;
  // -F.u plus the load's change (balance()) is -F_mean.u + const.
  load_mean_ = F;
  double constant = 0;
  if (F != F_) {
    load_mean_ = 0.5 * (F + F_);
    constant = 0.5 * (F - F_).dot(u_start_);
  }
  blend_[0] = 0.5 * v_mid_.dot(Mv_) + 0.5 * u_mid_.dot(Ku_mid_) - load_mean_.dot(u_mid_) + constant -
              work_mid_;
  blend_[1] = v_mid_.dot(Mdv_) + u_mid_.dot(Kdu_) - load_mean_.dot(du_) - (work_trap_ - work_mid_);
  blend_[2] = 0.5 * dv_.dot(Mdv_) + 0.5 * du_.dot(Kdu_);
  if (damped()) {  // dt v_mean' C v_mean, v_mean = (v_start + v_mid) / 2 + theta dv / 2
    v_mean_ = 0.5 * (v_start_ + v_mid_);
    Mv_.noalias() = C_ * v_mean_;
    Mdv_.noalias() = C_ * dv_;
    blend_[0] += dt_ * v_mean_.dot(Mv_);
    blend_[1] += dt_ * v_mean_.dot(Mdv_);
    blend_[2] += 0.25 * dt_ * dv_.dot(Mdv_);
  }
}

double MasslessNewmarkStepper::blend(double theta, const ContactLoad& next) {
  // The state theta of the way from (5.2) to the trapezoidal step, returned
  // to the relation; its balance: prepare_blend()'s quadratic for u_lin plus
  // the return's delta = u_C - u_lin_C, 1/2 u'Ku = 1/2 u_lin'K u_lin +
  // 1/2 delta.((K u_lin)_C + (K u)_C), and -F_mean_C.delta (work on the
  // contact set only; delta is small, so nothing large cancels).
  u_ = u_mid_ + theta * du_;
  v_ = v_mid_ + theta * dv_;
  const auto& c = problem_.contact_index();
  const Index nc = static_cast<Index>(c.size());
  u_C_before_.resize(nc);
  for (Index k = 0; k < nc; ++k) u_C_before_(k) = u_(c[k]);
  boundary_.enforce(u_, next.F, next.obstacle.g, active_);
  boundary_.reactions(u_, next.F, reactions_);  // F_C - (K u)_C
  double b = blend_[0] + theta * (blend_[1] + theta * blend_[2]);
  for (Index k = 0; k < nc; ++k) {
    const double delta = u_(c[k]) - u_C_before_(k);
    if (delta == 0) continue;
    const double Ku_lin = Ku_mid_(c[k]) + theta * Kdu_(c[k]);
    b += 0.5 * delta * (Ku_lin + next.F(c[k]) - reactions_(k)) - load_mean_(c[k]) * delta;
  }
  return b;
}

StepReport MasslessNewmarkStepper::advance_interior(const ContactLoad& next) {
  const Vector& g = next.obstacle.g;
  const double bdt2 = iteration_.beta_dt2();
  iteration_.predict(u_, v_, a_, u_hat_, v_pred_);
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();

  // In acceleration form, u = u_hat + bdt2 a (no cancellation at small dt):
  // S a = F - K u_hat - E_C lambda with lambda from the LCP (header).
  rhs_ = next.F;
  rhs_.noalias() -= problem_.K() * u_hat_;
  if (damped()) {
    // Interior rows: - C v~; contact rows: s (F - K u_hat)_C (header).
    Cv_.noalias() = C_ * v_pred_;
    for (Index k = 0; k < nc; ++k) Cv_(c[k]) = (1 - contact_row_scale_) * rhs_(c[k]);
    rhs_ -= Cv_;
  }
  if (energy_stable_) {
    boundary_.reactions(u_, F_, lambda_start_);
    u_start_ = u_;
    v_start_ = v_;
  }
  Vector& a = acceleration_;
  a = rhs_;
  const LcpResult& lcp = accelerate(g, a);
  u_ = u_hat_ + bdt2 * a;
  a_.swap(a);  // acceleration_: a workspace again from here
  iteration_.correct_velocity(v_pred_, a_, v_);
  // The LCP's z is lambda_{n+1}: z_k = 0 (lcp.active) where contact k is open.
  bool switched = false;
  for (Index k = 0; k < nc; ++k) {
    switched = switched || active_[k] == lcp.active[k];
    active_[k] = !lcp.active[k];
  }
  // Closed contacts sit exactly on the obstacle, not only to the round-off of
  // the solves (which grows with beta dt^2 |K|).
  for (Index k = 0; k < nc; ++k)
    if (active_[k]) u_(c[k]) = g(k);
  StepReport report;
  report.active_set_iterations = 1;
  if (!energy_stable_) return report;

  // The trapezoidal step's obstacle work, -(lambda_n + lambda_{n+1}) / 2 . dg.
  work_trap_ = 0;
  for (Index k = 0; k < nc; ++k)
    work_trap_ -= 0.5 * (lambda_start_(k) + lcp.z(k)) * (g(k) - obstacle_.g(k));
  if (!switched) {
    add_obstacle_work(work_trap_);
    return report;
  }
  double tolerance;  // the round-off of the energies
  energy_start_ = start_energy(&tolerance);
  // Measured from what the step may reach: the start plus what it may return.
  energy_start_ += budget_.returnable();
  const double gain_trap = balance(u_, v_, work_trap_, next.F) - energy_start_;
  if (gain_trap <= tolerance) {
    budget_.keep(-gain_trap);
    add_obstacle_work(work_trap_);
    return report;
  }
  budget_.count_balanced();

  // It would gain more than allowed (5.1): the step (5.2), whose force mu / 2
  // is complementary to the end gap (the LCP's z = mu for the contact rows
  // r_C + lambda_n), returned to the relation, gains nothing. The step taken
  // is the one of the way between the two whose balance is the allowed one.
  u_trap_ = u_;
  v_trap_ = v_;
  a_trap_ = a_;
  a = rhs_;
  for (Index k = 0; k < nc; ++k) a(c[k]) += lambda_start_(k);
  const LcpResult& mid = accelerate(g, a);
  work_mid_ = 0;
  for (Index k = 0; k < nc; ++k) work_mid_ -= 0.5 * mid.z(k) * (g(k) - obstacle_.g(k));
  for (Index k = 0; k < nc; ++k) active_[k] = !mid.active[k];
  u_mid_ = u_hat_ + bdt2 * a;
  iteration_.correct_velocity(v_pred_, a, v_mid_);
  a_mid_ = a;
  // The largest fraction of the way found whose balance is not above the
  // allowed one (f(0) <= 0 < f(1) = gain_trap), once it is within round-off
  // of it (energy conserved to round-off).
  prepare_blend(next.F);
  const auto excess = [&](double theta) { return blend(theta, next) - energy_start_; };
  const double theta = largest_allowed_fraction(excess, excess(0), gain_trap, tolerance);
  u_ = u_mid_ + theta * (u_trap_ - u_mid_);
  v_ = v_mid_ + theta * (v_trap_ - v_mid_);
  a_ = a_mid_ + theta * (a_trap_ - a_mid_);
  const double work = work_mid_ + theta * (work_trap_ - work_mid_);
  add_obstacle_work(work);
  return_to_relation(next.F, g);
  // What the step reached, evaluated as the start was (not from
  // blend()'s expansion), so that round-off does not accumulate over steps.
  budget_.keep(energy_start_ - balance(u_, v_, work, next.F));
  return report;
}

}  // namespace nbm
