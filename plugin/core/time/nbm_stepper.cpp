#include "time/nbm_stepper.hpp"

namespace nbm {

NbmStepper::NbmStepper(const ContactProblem& problem, double dt, const Damping& damping)
    : Stepper(problem, dt, damping), boundary_(problem) {}

void NbmStepper::start(const ContactLoad& load) {
  active_ = boundary_.enforce(u_, F_, obstacle_.g, {}).active;
  rate_constraint(load, active_, h_);
  boundary_.project(v_, active_, h_);
  solve_acceleration(load);
}

StepReport NbmStepper::advance(const ContactLoad& next) {
  const StepReport report = advance_interior(next);
  rate_constraint(next, active_, h_);
  boundary_.project(v_, active_, h_);
  acceleration_constraint(next, active_, h_);
  boundary_.project(a_, active_, h_);
  return report;
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
