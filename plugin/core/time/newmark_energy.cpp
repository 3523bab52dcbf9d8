// The energy-stable step of the paper's NBM (method.md §5.3): the paper's
// step where its balance is allowed, else the state between it and a
// dissipative candidate whose balance is.
#include "time/newmark_stepper.hpp"

#include <algorithm>

namespace nbm {

void NewmarkStepper::backward_euler_half_step(Vector& u, Vector& v, const Vector& F,
                                              const Vector& g) {
  // M (v1 - v0) / h = F - K u1 - E_C lambda, u1 = u0 + h v1, h = dt / 2, with
  // lambda >= 0 complementary to the gap g - u1_C: in acceleration form
  // (M + h^2 K) a = F - K (u0 + h v0) - E_C lambda, and M + h^2 K is S
  // (beta = 1/4). Its balance falls by |dv|_M^2 / 2 + |du|_K^2 / 2 +
  // lambda . (g - u0_C) >= 0 (method.md §5.3).
  const double h = 0.5 * dt_, h2 = h * h;
  const auto& c = problem_.contact_index();
  const Index nc = problem_.n_contact();
  const CholeskyInverse& S = *iteration_.S();
  u.noalias() += h * v;
  rhs_ = F;
  rhs_.noalias() -= problem_.K() * u;
  S.solve_in_place(rhs_);
  q_.resize(nc);
  open_.resize(nc);
  for (Index k = 0; k < nc; ++k) {
    q_(k) = (g(k) - u(c[k])) - h2 * rhs_(c[k]);
    open_[k] = !start_set_[k];
  }
  const LcpResult& lcp = half_lcp_->solve(q_, open_);
  if ((lcp.z.array() != 0.0).any()) {
    correction_.setZero(u.size());
    for (Index k = 0; k < nc; ++k) correction_(c[k]) = -lcp.z(k);
    S.solve_in_place(correction_);
    rhs_ += correction_;
  }
  u.noalias() += h2 * rhs_;
  v.noalias() += h * rhs_;
  for (Index k = 0; k < nc; ++k)
    if (!lcp.active[k]) u(c[k]) = g(k);  // on the obstacle, not only to round-off
}

double NewmarkStepper::blend(double theta, const ContactLoad& next) {
  u_ = u_dissipative_ + theta * (u_paper_ - u_dissipative_);
  v_ = v_dissipative_ + theta * (v_paper_ - v_dissipative_);
  // u_C onto the relation at u_O lowers u'Ku/2 - F.u; v onto the relation's
  // velocities in M's norm lowers v'Mv/2 (h = 0 for a fixed obstacle and a
  // constant load).
  // Guessed from the paper's set, never from the last blend: a node at zero
  // gap and zero force is closed or open by the guess, and its velocity with
  // it, so that blend() is a function of theta alone.
  blend_set_ = boundary_.enforce(u_, next.F, next.obstacle.g, active_).active;
  rate_constraint(next, blend_set_, h_rate_);
  Mv_.noalias() = problem_.M() * v_;
  mass_->solve(blend_set_, Mv_, h_rate_, v_);
  return balance(u_, v_, 0.0, next.F) - allowed_;
}

void NewmarkStepper::limit_energy(const ContactLoad& next) {
  const Vector& g = next.obstacle.g;
  // v_C of the new set, as NbmStepper::advance completes it, so that the
  // balance is the one the step reports.
  rate_constraint(next, active_, h_rate_);
  boundary_.project(v_, active_, h_rate_);
  // Every step is checked, not only switching ones: a step that keeps its
  // set conserves the balance only from a state whose acceleration is the
  // set's own, which a fallback's is not (method.md §5.3). A moving
  // obstacle's work is not bounded here.
  if (g != obstacle_.g) return;
  double tolerance;  // the round-off of the energies
  allowed_ = start_energy(&tolerance) + budget_.returnable();
  const double gain = balance(u_, v_, 0.0, next.F) - allowed_;
  if (gain <= tolerance) {
    budget_.keep(-gain);
    return;
  }
  budget_.count_balanced();
  if (!mass_) {
    // Built at the first step that needs them: a run whose steps all keep
    // their balance pays nothing for them.
    mass_ = std::make_unique<ConstrainedSolver>(
        problem_.factorizer().factor(problem_.M(), "M", problem_.constraint_basis()),
        problem_.constraint_basis());
    const double half = 0.5 * dt_;
    half_lcp_ =
        std::make_unique<CachedLcpSolver>(Matrix(half * half * iteration_.contact_compliance()));
  }
  u_paper_ = u_;
  v_paper_ = v_;
  // The dissipative candidate: two backward-Euler half steps under the
  // step's mean load (whose balance is the trapezoidal one, method.md §5.1).
  load_mean_ = 0.5 * (F_ + next.F);
  u_dissipative_ = u_start_;
  v_dissipative_ = v_start_;
  backward_euler_half_step(u_dissipative_, v_dissipative_, load_mean_, g);
  backward_euler_half_step(u_dissipative_, v_dissipative_, load_mean_, g);
  // The state of the largest allowed theta met is kept, not evaluated again.
  double best = -1, best_excess = 0;
  const auto excess = [&](double theta) {
    const double e = blend(theta, next);
    if (e <= 0 && theta > best) {
      best = theta, best_excess = e;
      u_best_ = u_, v_best_ = v_, best_set_ = blend_set_;
    }
    return e;
  };
  const double at_0 = excess(0);
  // The search stops within a thousandth of the energy between the two ends
  // of the way: what it leaves unreached is kept as returnable with
  // "bounded", and is at most that with "monotone".
  const double close_enough = std::max(tolerance, 1e-3 * (gain - at_0));
  const double theta = largest_allowed_fraction(excess, at_0, gain, close_enough);
  double reached;
  if (theta == best) {
    u_.swap(u_best_), v_.swap(v_best_), blend_set_.swap(best_set_);
    reached = best_excess;
  } else {  // theta = 0 above the bound by round-off
    reached = blend(theta, next);
  }
  active_ = blend_set_;
  rhs_ = next.F;
  rhs_.noalias() -= problem_.K() * u_;
  acceleration_constraint(next, active_, h_rate_);
  mass_->solve(active_, rhs_, h_rate_, a_);
  budget_.keep(-reached);
}

}  // namespace nbm
