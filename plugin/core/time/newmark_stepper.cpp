#include "time/newmark_stepper.hpp"

#include <algorithm>
#include <string>

#include "base/errors.hpp"

namespace nbm {

NewmarkStepper::NewmarkStepper(const ContactProblem& problem, double dt,
                               NewmarkParameters parameters, const Damping& damping)
    : NbmStepper(problem, dt, damping, parameters.energy,
                 parameters.scheme.average_acceleration() && damping.none()),
      parameters_(parameters),
      iteration_(problem, dt, parameters.scheme, C_),
      solver_(iteration_.S(), problem.constraint_basis()) {
  uses_scheme(iteration_);
}

void NewmarkStepper::solve_acceleration(const ContactLoad& load) {
  // Needed once per (re)start: a mass factorization used and released here.
  const auto mass = problem_.factorizer().factor(problem_.M(), "M", problem_.constraint_basis());
  Vector r = load.F - problem_.K() * u_;
  if (damped()) r.noalias() -= C_ * v_;  // v_ on the relation already (start())
  acceleration_constraint(load, active_, h_accel_);
  solve_constrained_once(*mass, problem_.constraint_basis(), active_, r, h_accel_, a_);
}

void NewmarkStepper::solve_step(const ActiveSet& active, const ContactLoad& next,
                                Vector& u_next, Vector& a_next) {
  const double bdt2 = iteration_.beta_dt2();
  displacement_constraint(next, active, h_);  // h
  acceleration_constraint(next, active, h_accel_);
  u_hat_ = u_pred_;
  h_ -= bdt2 * h_accel_;  // G u_hat, so that G (u_hat + bdt2 a) = h
  boundary_.project(u_hat_, active, h_);
  // S u = M u_hat + bdt2 F + G^T mu with u = u_hat + bdt2 a is
  // S a = F - K u_hat + G^T mu', G a = h''.
  r_ = next.F;
  r_.noalias() -= problem_.K() * u_hat_;
  if (damped()) r_.noalias() -= C_ * v_pred_;  // v = v~ + gamma dt a (§9)
  solver_.solve(active, r_, h_accel_, a_next);
  u_next = u_hat_ + bdt2 * a_next;
  // Closed contacts: a_C = g'' and u_C = g hold exactly, not only to the
  // round-off of the solve (which grows with beta dt^2 |K|).
  const auto& c = problem_.contact_index();
  for (std::size_t k = 0; k < c.size(); ++k)
    if (active[k]) {
      a_next(c[k]) = next.obstacle.g_accel(k);
      u_next(c[k]) = next.obstacle.g(k);
    }
}

NewmarkStepper::Candidate& NewmarkStepper::add_candidate() {
  if (n_tried_ == tried_.size()) tried_.emplace_back();
  return tried_[n_tried_++];
}

StepReport NewmarkStepper::advance_interior(const ContactLoad& next) {
  const Vector& g = next.obstacle.g;
  if (energy_stable_) {
    u_start_ = u_;
    v_start_ = v_;
    start_set_ = active_;
  }
  iteration_.predict(u_, v_, a_, u_pred_, v_pred_);

  // Fixed point on the active set at t_{n+1} (§5): solve with a guess, then
  // take the LCP's set at the new interior displacement until they agree.
  // Every solve is kept as a candidate for the fallback.
  StepReport report;
  n_tried_ = 0;
  guess_ = active_;
  bool consistent = false;
  while (true) {
    ++report.active_set_iterations;
    solve_step(guess_, next, u_next_, a_next_);
    const double violation = boundary_.violation(u_next_, next.F, g, guess_);
    if (violation <= kConsistencyTolerance) {
      consistent = true;
      break;
    }
    Candidate& tried = add_candidate();
    tried.set = guess_;
    tried.u_next = u_next_;
    tried.a_next = a_next_;
    tried.violation = violation;
    u_lcp_ = u_next_;
    guess_ = boundary_.enforce(u_lcp_, next.F, g, guess_).active;
    const bool seen = std::any_of(tried_.begin(), tried_.begin() + n_tried_,
                                  [&](const Candidate& c) { return c.set == guess_; });
    if (seen || report.active_set_iterations >= parameters_.max_active_set_iterations)
      break;  // cycling
  }
  if (consistent)
    active_ = guess_;
  else
    fall_back(next, report);

  a_.swap(a_next_);  // a_next_, u_next_: workspaces again from here
  iteration_.correct_velocity(v_pred_, a_, v_);
  u_.swap(u_next_);
  if (energy_stable_) limit_energy(next);
  return report;
}

void NewmarkStepper::fall_back(const ContactLoad& next, StepReport& report) {
  const Vector& g = next.obstacle.g;
  // No set is consistent at t_{n+1} (§5). The dynamics use the least
  // inconsistent of the sets tried and of the LCP's set at the predictor;
  // u_C^{n+1} then comes from the LCP at u_O^{n+1}, so impenetrability stays
  // exact. (A contact grazed by 1e-14 thus keeps the free motion instead of
  // being held for a step.)
  report.fallback = true;
  u_lcp_ = u_pred_;
  predictor_set_ = boundary_.enforce(u_lcp_, next.F, g, active_).active;
  const auto tried_end = tried_.begin() + n_tried_;
  if (std::none_of(tried_.begin(), tried_end,
                   [&](const Candidate& c) { return c.set == predictor_set_; })) {
    ++report.active_set_iterations;
    solve_step(predictor_set_, next, u_next_, a_next_);
    Candidate& tried = add_candidate();
    tried.set = predictor_set_;
    tried.u_next = u_next_;
    tried.a_next = a_next_;
    tried.violation = boundary_.violation(u_next_, next.F, g, predictor_set_);
  }
  const Candidate& best = *std::min_element(
      tried_.begin(), tried_.begin() + n_tried_,
      [](const Candidate& a, const Candidate& b) { return a.violation < b.violation; });
  u_next_ = best.u_next;
  a_next_ = best.a_next;
  active_ = boundary_.enforce(u_next_, next.F, g, best.set).active;
}

}  // namespace nbm
