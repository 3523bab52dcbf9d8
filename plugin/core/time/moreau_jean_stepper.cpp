#include "time/moreau_jean_stepper.hpp"

#include <string>
#include <vector>

#include "base/errors.hpp"
#include "linalg/lcp.hpp"

namespace nbm {

MoreauJeanStepper::MoreauJeanStepper(const ContactProblem& problem, double dt,
                                     double restitution, const Damping& damping)
    : Stepper(problem, dt, damping),
      restitution_(restitution),
      iteration_(problem, dt, SchemeParameters::newmark(0.25, 0.5), C_),
      S_(*iteration_.S()),
      W_CC_(iteration_.contact_compliance()),
      impulse_(Vector::Zero(problem.n_contact())) {
  if (!(restitution >= 0 && restitution <= 1))
    throw InputError("restitution: " + std::to_string(restitution) +
                     ", expected a coefficient in [0, 1]");
}

void MoreauJeanStepper::start(const ContactLoad& load) {
  const Vector gap = gaps();
  active_.assign(problem_.n_contact(), false);
  for (Index k = 0; k < gap.size(); ++k) active_[k] = gap(k) <= 0;
  impulse_.setZero();
  solve_acceleration(load.F);
}

void MoreauJeanStepper::restore_scheme_state(const Vector& state) {
  if (state.size() == 0) {  // a state saved without it: no impulse reported
    impulse_.setZero();
    return;
  }
  if (state.size() != problem_.n_contact())
    throw InputError("scheme state: size " + std::to_string(state.size()) + ", expected " +
                     std::to_string(problem_.n_contact()) +
                     " (Moreau-Jean's last impulse, one per contact node)");
  if (!state.allFinite() || (state.array() < 0).any())
    throw InputError("scheme state: expected finite impulses >= 0");
  impulse_ = state;
}

void MoreauJeanStepper::solve_acceleration(const Vector& F) {
  a_ = F - problem_.K() * u_;
  if (damped()) a_ -= C_ * v_;
  problem_.factorizer().factor(problem_.M(), "M")->solve_in_place(a_);
}

StepReport MoreauJeanStepper::advance(const ContactLoad& next) {
  const Vector& F_next = next.F;
  const Vector& g_rate = obstacle_.g_rate;            // at t_n
  const Vector& g_rate_next = next.obstacle.g_rate;  // at t_{n+1}
  const double dt = dt_;
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();
  // Free velocity (theta = 1/2, load at the midpoint).
  Vector v_free = problem_.M() * v_ + dt * (0.5 * (F_ + F_next) - problem_.K() * u_) -
                  (0.25 * dt * dt) * (problem_.K() * v_);
  if (damped()) v_free -= (0.5 * dt) * (C_ * v_);
  S_.solve_in_place(v_free);

  // Contacts predicted closed at mid-step (the gap rate is g' - v_C), and
  // Newton's law on them in the separation velocities w = g' - v_C.
  const Vector gap = gaps();
  std::vector<Index> closed;
  for (Index k = 0; k < nc; ++k)
    if (gap(k) + 0.5 * dt * (g_rate(k) - v_(c[k])) <= 0) closed.push_back(k);
  impulse_.setZero();
  Vector v_next = v_free;
  if (!closed.empty()) {
    const Index m = static_cast<Index>(closed.size());
    Matrix W(m, m);
    Vector q(m);
    for (Index a = 0; a < m; ++a) {
      // w+ + e w = (g'_{n+1} - v_free_C + W p) + e (g'_n - v_C)
      const Index k = closed[a];
      q(a) = (g_rate_next(k) - v_free(c[k])) + restitution_ * (g_rate(k) - v_(c[k]));
      for (Index b = 0; b < m; ++b) W(a, b) = W_CC_(closed[a], closed[b]);
    }
    const LcpResult lcp = LcpSolver::solve(W, q);
    Vector correction = Vector::Zero(v_.size());
    for (Index a = 0; a < m; ++a) {
      impulse_(closed[a]) = lcp.z(a);
      correction(c[closed[a]]) = -lcp.z(a);
    }
    S_.solve_in_place(correction);
    v_next += correction;
  }
  u_ += (0.5 * dt) * (v_ + v_next);
  a_ = (v_next - v_) / dt;
  v_ = v_next;
  const Vector gap_next = gaps(u_, next.obstacle.g);
  for (Index k = 0; k < nc; ++k) active_[k] = impulse_(k) > 0 || gap_next(k) <= 0;
  StepReport report;
  report.active_set_iterations = 1;
  return report;
}

}  // namespace nbm
