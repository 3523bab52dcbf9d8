#include "time/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Initial penetration is judged with this relative tolerance on the
// displacement scale, so that a body released exactly on the obstacle passes.
constexpr double kPenetrationTolerance = 1e-12;
// Change of a gap over one step allowed beyond what its rates reach
// (Stepper::check_obstacle_motion): a factor on the reach, and round-off
// relative to the gaps and the displacements.
constexpr double kObstacleReachMargin = 2;
constexpr double kObstacleRoundoff = 1e-12;

// (const char* names: a check on every step must not allocate.)
void check_vector(const Vector& x, Index n, const char* name, const char* expected) {
  if (x.size() != n)
    throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n) + " (" + expected + ")");
  if (!x.allFinite()) throw InputError(std::string(name) + ": non-finite entries");
}

}  // namespace

Obstacle Obstacle::at_rest(const Vector& g) {
  return {g, Vector::Zero(g.size()), Vector::Zero(g.size())};
}

Stepper::Stepper(const ContactProblem& problem, double dt, const Damping& damping)
    : problem_(problem), dt_(dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw InputError("dt: " + std::to_string(dt) + ", expected a positive finite time step");
  check_damping(damping, problem.size());
  C_ = damping_matrix(damping, problem.M(), problem.K());
}

void Stepper::check_load(const ContactLoad& load, bool whole) const {
  const Index n = problem_.size(), nc = problem_.n_contact();
  // The obstacle (n_c entries) at every call; the load's n entries only when
  // asked: at a step the front end has checked them (Solver::step,
  // set_load_rates), and a second pass over all dofs per step is waste.
  check_vector(load.obstacle.g, nc, "gaps", "one per contact node");
  check_vector(load.obstacle.g_rate, nc, "gap rates", "one per contact node");
  check_vector(load.obstacle.g_accel, nc, "gap accelerations", "one per contact node");
  const auto check = [&](const Vector& x, const char* name) {
    if (whole)
      check_vector(x, n, name, "one entry per dof");
    else if (x.size() != n)
      throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                       std::to_string(n) + " (one entry per dof)");
  };
  check(load.F, "F");
  if (load.F_rate) check(*load.F_rate, "load rate");
  if (load.F_accel) check(*load.F_accel, "load acceleration");
}

Vector Stepper::gaps(const Vector& u, const Vector& g) const {
  const auto& c = problem_.contact_index();
  Vector gap = g;
  for (std::size_t k = 0; k < c.size(); ++k) gap(k) -= u(c[k]);
  return gap;
}

void Stepper::check_penetration(const Vector& u, const Vector& g, const char* what) const {
  // Each node against its own scale: the body's displacement and its own
  // gap, never another node's (a far node's large gap must not loosen the
  // check of the nodes in contact).
  const Vector gap = gaps(u, g);
  const double u_scale = u.cwiseAbs().maxCoeff();
  for (Index k = 0; k < gap.size(); ++k)
    if (gap(k) < -kPenetrationTolerance * std::max(u_scale, std::abs(g(k))))
      throw InputError(std::string("u: ") + what + " penetration at contact node " +
                       std::to_string(k) + " (gap " + std::to_string(gap(k)) + " < 0)");
}

void Stepper::initialize(const Vector& u, const Vector& v, const Vector& F, double t) {
  const Obstacle rest = Obstacle::at_rest(problem_.gaps());
  initialize(u, v, ContactLoad{F, rest}, t);
}

void Stepper::initialize(const Vector& u, const Vector& v, const ContactLoad& load, double t) {
  begin(u, v, load, t, true);  // every scheme starts outside the obstacle
}

void Stepper::continue_from(const Vector& u, const Vector& v, const ContactLoad& load,
                            double t) {
  begin(u, v, load, t, exact_impenetrability());
}

void Stepper::begin(const Vector& u, const Vector& v, const ContactLoad& load, double t,
                    bool check) {
  const Index n = problem_.size();
  check_vector(u, n, "u", "one entry per dof");
  check_vector(v, n, "v", "one entry per dof");
  check_load(load, true);
  if (!std::isfinite(t)) throw InputError("t: non-finite initial time");
  if (check) check_penetration(u, load.obstacle.g, "initial");
  set_state(u, v, load, t);
  a_.resize(n);
  fresh_start_ = check;
  start(load);
  fresh_start_ = true;
  initialized_ = true;
}

void Stepper::restore(const Vector& u, const Vector& v, const Vector& a, const ActiveSet& active,
                      const Vector& F, double t) {
  const Obstacle rest = Obstacle::at_rest(problem_.gaps());
  restore(u, v, a, active, ContactLoad{F, rest}, t);
}

void Stepper::restore(const Vector& u, const Vector& v, const Vector& a, const ActiveSet& active,
                      const ContactLoad& load, double t, const Vector& scheme_state) {
  const Index n = problem_.size();
  check_vector(u, n, "u", "one entry per dof");
  check_vector(v, n, "v", "one entry per dof");
  check_vector(a, n, "a", "one entry per dof");
  check_load(load, true);
  if (static_cast<Index>(active.size()) != problem_.n_contact())
    throw InputError("active: size " + std::to_string(active.size()) + ", expected " +
                     std::to_string(problem_.n_contact()) + " (one entry per contact node)");
  if (!std::isfinite(t)) throw InputError("t: non-finite time");
  if (exact_impenetrability()) check_penetration(u, load.obstacle.g, "restored");
  restore_scheme_state(scheme_state);
  set_state(u, v, load, t);
  a_ = a;
  active_ = active;
  initialized_ = true;
}

void Stepper::set_state(const Vector& u, const Vector& v, const ContactLoad& load, double t) {
  u_ = u;
  v_ = v;
  F_ = load.F;
  obstacle_ = load.obstacle;
  t_ = t;
  obstacle_work_ = 0;
  load_work_ = 0;
  dissipated_ = 0;
}

void Stepper::restore_scheme_state(const Vector& state) {
  if (state.size() != 0)
    throw InputError("scheme state: size " + std::to_string(state.size()) +
                     ", expected 0 (this scheme keeps no state of its own)");
}

void Stepper::replace_kinematics(Vector u, Vector v, Vector a) {
  u_ = std::move(u);
  v_ = std::move(v);
  a_ = std::move(a);
}

StepReport Stepper::step(const ContactLoad& next) {
  if (!initialized_) throw InputError("step: the stepper has no initial state");
  check_load(next, false);  // sizes; finiteness: the front end's
  // The obstacle's work over the step, -dg . (lambda_n + lambda_{n+1}) / 2:
  // only when the obstacle moves (lambda_n taken before the state changes).
  const bool moving = next.obstacle.g != obstacle_.g;
  if (moving) check_obstacle_motion(next.obstacle);
  const bool work_here = moving && !accounts_obstacle_work();
  if (work_here) {
    reactions(lambda_old_);
    dg_ = next.obstacle.g - obstacle_.g;
  }
  if (damped()) v_mid_ = v_;
  const bool load_changes = next.F != F_;
  if (load_changes) u_before_ = u_;
  const StepReport report = advance(next);
  if (load_changes) load_work_ -= 0.5 * (next.F - F_).dot(u_before_ + u_);
  F_ = next.F;
  obstacle_ = next.obstacle;
  t_ += dt_;
  if (work_here) {
    reactions(lambda_new_);
    obstacle_work_ -= 0.5 * (dg_.dot(lambda_old_) + dg_.dot(lambda_new_));
  }
  if (damped()) {
    // D += dt v_mid^T C v_mid, v_mid = (v_n + v_{n+1}) / 2 (method.md §9).
    v_mid_ += v_;
    v_mid_ *= 0.5;
    Cv_.noalias() = C_ * v_mid_;
    dissipated_ += dt_ * v_mid_.dot(Cv_);
  }
  return report;
}

void Stepper::check_obstacle_motion(const Obstacle& next) const {
  // A gap may change over a step by what its rates at the two ends allow,
  // dt (max |g'| + dt max |g''|), with a margin of 2 for the variation of the
  // rates within the step (a harmonic motion uses at most 1 of dt (...) at
  // any phase, 0.71 at omega dt = 1; a motion starting or stopping within a
  // step, 1) and round-off of the gaps and of the displacements. Anything beyond is a
  // jump of the obstacle (method.md §8, "Jumps"): an obstacle jumping into a
  // body has no well-defined work (an impulse the schemes would take as a
  // finite force over dt), and one jumping away leaves the trapezoidal work
  // wrong by the jump times the half-reaction.
  const double u_scale = u_.cwiseAbs().maxCoeff();
  const Obstacle& o = obstacle_;
  for (Index k = 0; k < next.g.size(); ++k) {
    const double jump = next.g(k) - o.g(k);
    const double rate = std::max(std::abs(o.g_rate(k)), std::abs(next.g_rate(k)));
    const double accel = std::max(std::abs(o.g_accel(k)), std::abs(next.g_accel(k)));
    const double reach = dt_ * (rate + dt_ * accel);
    const double roundoff =
        kObstacleRoundoff * std::max({std::abs(o.g(k)), std::abs(next.g(k)), u_scale});
    if (std::abs(jump) > kObstacleReachMargin * reach + roundoff)
      throw InputError("obstacle: the gap of contact node " + std::to_string(k) + " jumps by " +
                       std::to_string(jump) + " in one step (dt = " + std::to_string(dt_) +
                       "), more than its rates allow (2 dt (|g'| + dt |g''|) = " +
                       std::to_string(kObstacleReachMargin * reach) +
                       "); expected a continuous motion: give the gap rates and accelerations "
                       "with the gaps (nbmObstacle's gdot, gddot), or move the obstacle over "
                       "more steps");
  }
}

Energies Stepper::energies() const {
  Energies e;
  e.kinetic = 0.5 * v_.dot(mass() * v_);
  e.elastic = 0.5 * u_.dot(problem_.K() * u_);
  e.load = -F_.dot(u_);
  e.obstacle_work = obstacle_work_;
  e.load_work = load_work_;
  e.dissipated = dissipated_;
  return e;
}

}  // namespace nbm
