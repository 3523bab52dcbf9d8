#include "time/nbm_stepper.hpp"

#include <cmath>
#include <limits>

namespace nbm {

NbmStepper::NbmStepper(const ContactProblem& problem, double dt, const Damping& damping,
                       EnergyControl energy, bool has_energy_step)
    : Stepper(problem, dt, damping),
      boundary_(problem),
      energy_stable_(has_energy_step && energy != EnergyControl::kNone),
      budget_(energy) {}

Vector NbmStepper::scheme_state() const {
  // The energy-stable step exists only for average acceleration, which has
  // no state of its own: at most one of the two is not empty.
  if (energy_stable_) return budget_.state();
  return scheme_ ? scheme_->state() : Vector();
}

void NbmStepper::carry_over(const Stepper& previous) {
  const auto* nbm = dynamic_cast<const NbmStepper*>(&previous);
  if (energy_stable_ && nbm && nbm->energy_stable_) budget_.take_over(nbm->budget_);
}

void NbmStepper::restore_scheme_state(const Vector& state) {
  if (energy_stable_)
    budget_.restore(state, "the energy-stable step");
  else if (scheme_ && scheme_->parameters().weighted())
    scheme_->restore_state(state);
  else
    Stepper::restore_scheme_state(state);
}

void NbmStepper::start(const ContactLoad& load) {
  budget_.reset();
  active_ = boundary_.enforce(u_, F_, obstacle_.g, {}).active;
  rate_constraint(load, active_, h_);
  boundary_.project(v_, active_, h_);
  solve_acceleration(load);
  if (scheme_) scheme_->start(a_);
}

StepReport NbmStepper::advance(const ContactLoad& next) {
  const StepReport report = advance_interior(next);
  rate_constraint(next, active_, h_);
  boundary_.project(v_, active_, h_);
  acceleration_constraint(next, active_, h_);
  boundary_.project(a_, active_, h_);
  if (scheme_) scheme_->finish(a_);
  return report;
}

double NbmStepper::energy(const Vector& u, const Vector& v, const Vector& F) {
  Ku_.noalias() = problem_.K() * u;
  Mv_.noalias() = mass() * v;
  return 0.5 * v.dot(Mv_) + 0.5 * u.dot(Ku_) - F.dot(u);
}

double NbmStepper::balance(const Vector& u, const Vector& v, double work, const Vector& F) {
  double b = energy(u, v, F) - work;
  // A load that changes over the step changes the potential -F.u by itself:
  // the trapezoidal rule's work of the load is (F_n + F_{n+1}) / 2 . du, so
  // its balance carries + (F_{n+1} - F_n) . (u_n + u_{n+1}) / 2.
  if (F != F_) b += 0.5 * (F - F_).dot(u_start_ + u);
  if (damped()) {
    mean_velocity_ = 0.5 * (v_start_ + v);
    Mv_.noalias() = C_ * mean_velocity_;
    b += dt_ * mean_velocity_.dot(Mv_);
  }
  return b;
}

double NbmStepper::start_energy(double* roundoff) {
  const double e = energy(u_start_, v_start_, F_);
  *roundoff = 64 * std::numeric_limits<double>::epsilon() *
              (0.5 * std::abs(v_start_.dot(Mv_)) + 0.5 * std::abs(u_start_.dot(Ku_)) +
               std::abs(F_.dot(u_start_)));
  return e;
}

void NbmStepper::constraint(const Vector& closed, const Vector* open, const ActiveSet& active,
                            Vector& h) const {
  const auto& c = problem_.contact_index();
  h.resize(static_cast<Index>(c.size()));
  for (std::size_t k = 0; k < c.size(); ++k)
    h(k) = active[k] ? closed(k) : (open ? (*open)(c[k]) : 0.0);
}

void NbmStepper::displacement_constraint(const ContactLoad& load, const ActiveSet& active,
                                         Vector& h) const {
  constraint(load.obstacle.g, &load.F, active, h);
}

void NbmStepper::rate_constraint(const ContactLoad& load, const ActiveSet& active,
                                 Vector& h) const {
  constraint(load.obstacle.g_rate, load.F_rate, active, h);
}

void NbmStepper::acceleration_constraint(const ContactLoad& load, const ActiveSet& active,
                                         Vector& h) const {
  constraint(load.obstacle.g_accel, load.F_accel, active, h);
}

}  // namespace nbm
