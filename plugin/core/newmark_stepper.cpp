#include "newmark_stepper.hpp"

#include <algorithm>
#include <string>

#include "errors.hpp"

namespace nbm {

void check_newmark_parameters(double beta, double gamma) {
  if (!(beta > 0 && beta <= 0.5))
    throw InputError("beta: " + std::to_string(beta) +
                     ", expected 0 < beta <= 1/2 (beta = 0 is the explicit scheme)");
  if (!(gamma >= 0.5 && gamma <= 1))
    throw InputError("gamma: " + std::to_string(gamma) + ", expected 1/2 <= gamma <= 1");
}

NewmarkStepper::NewmarkStepper(const ContactProblem& problem, double dt,
                               NewmarkParameters parameters)
    : Stepper(problem, dt),
      parameters_(parameters),
      solver_(
          [&] {
            check_newmark_parameters(parameters.beta, parameters.gamma);
            const SparseMatrix S = problem.M() + (parameters.beta * dt * dt) * problem.K();
            return make_cholesky_inverse(S, "M + beta dt^2 K");
          }(),
          problem.constraint_basis()) {}

void NewmarkStepper::solve_acceleration(const Vector& F) {
  // Needed once per (re)start: a mass factorization used and released here.
  const ConstrainedSolver mass(make_cholesky_inverse(problem_.M(), "M"),
                               problem_.constraint_basis());
  const Vector r = F - problem_.K() * u_;
  mass.solve(active_, r, Vector::Zero(problem_.n_contact()), a_);
}

void NewmarkStepper::solve_step(const ActiveSet& active, const Vector& u_pred, const Vector& F,
                                Vector& u_next, Vector& a_next) const {
  const double bdt2 = parameters_.beta * dt_ * dt_;
  const Vector h = boundary_.displacement_constraint(active, F);
  Vector u_hat = u_pred;
  boundary_.project(u_hat, active, h);
  // S u = M u_hat + bdt2 F + G^T mu with u = u_hat + bdt2 a is
  // S a = F - K u_hat + G^T mu' and, since G u_hat = h, G a = 0.
  const Vector r = F - problem_.K() * u_hat;
  solver_.solve(active, r, Vector::Zero(problem_.n_contact()), a_next);
  // Closed contacts: a_C = 0 and u_C = g hold exactly, not only to the
  // round-off of the solve (which grows with beta dt^2 |K|).
  const auto& c = problem_.contact_index();
  for (std::size_t k = 0; k < c.size(); ++k)
    if (active[k]) a_next(c[k]) = 0.0;
  u_next = u_hat + bdt2 * a_next;
}

StepReport NewmarkStepper::step(const Vector& F_next) {
  if (!initialized_) throw InputError("step: the stepper has no initial state");
  const double dt = dt_, beta = parameters_.beta, gamma = parameters_.gamma;
  const Vector u_pred = u_ + dt * v_ + (dt * dt * (0.5 - beta)) * a_;
  const Vector v_pred = v_ + (dt * (1 - gamma)) * a_;

  // Fixed point on the active set at t_{n+1} (§5): solve with a guess, then
  // take the LCP's set at the new interior displacement until they agree.
  // Every solve is kept as a candidate for the fallback, with how far its set
  // is from being consistent (NodalBoundary::violation).
  struct Candidate {
    ActiveSet set;
    Vector u_next, a_next;
    double violation;
  };
  StepReport report;
  std::vector<Candidate> tried;
  ActiveSet guess = active_;
  Vector u_next, a_next;
  bool consistent = false;
  while (true) {
    ++report.active_set_iterations;
    solve_step(guess, u_pred, F_next, u_next, a_next);
    const double violation = boundary_.violation(u_next, F_next, guess);
    if (violation <= kConsistencyTolerance) {
      consistent = true;
      break;
    }
    tried.push_back({guess, u_next, a_next, violation});
    Vector u_lcp = u_next;
    guess = boundary_.enforce(u_lcp, F_next, guess).active;
    const bool seen = std::any_of(tried.begin(), tried.end(),
                                  [&](const Candidate& c) { return c.set == guess; });
    if (seen || report.active_set_iterations >= parameters_.max_active_set_iterations)
      break;  // cycling
  }

  ActiveSet final_set = guess;
  if (!consistent) {
    // Fallback (§5): no set is consistent at t_{n+1}. The dynamics use the
    // least inconsistent of the sets tried and of the LCP's set at the
    // predictor; u_C^{n+1} then comes from the LCP at u_O^{n+1}, so
    // impenetrability stays exact. (A contact grazed by 1e-14 thus keeps the
    // free motion instead of being held for a step.)
    report.fallback = true;
    Vector u_lcp = u_pred;
    const ActiveSet predictor_set = boundary_.enforce(u_lcp, F_next, active_).active;
    if (std::none_of(tried.begin(), tried.end(),
                     [&](const Candidate& c) { return c.set == predictor_set; })) {
      ++report.active_set_iterations;
      solve_step(predictor_set, u_pred, F_next, u_next, a_next);
      tried.push_back(
          {predictor_set, u_next, a_next, boundary_.violation(u_next, F_next, predictor_set)});
    }
    const Candidate& best = *std::min_element(
        tried.begin(), tried.end(),
        [](const Candidate& a, const Candidate& b) { return a.violation < b.violation; });
    u_next = best.u_next;
    a_next = best.a_next;
    final_set = boundary_.enforce(u_next, F_next, best.set).active;
  }

  a_ = a_next;
  v_ = v_pred + (gamma * dt) * a_;
  u_ = u_next;
  active_ = final_set;
  finish_step(F_next);
  return report;
}

}  // namespace nbm
