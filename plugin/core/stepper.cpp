#include "stepper.hpp"

#include <cmath>
#include <string>

#include "errors.hpp"

namespace nbm {
namespace {

// Initial penetration is judged with this relative tolerance on the
// displacement scale, so that a body released exactly on the obstacle passes.
constexpr double kPenetrationTolerance = 1e-12;

void check_size(const Vector& x, Index n, const char* name) {
  if (x.size() != n)
    throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n));
  if (!x.allFinite()) throw InputError(std::string(name) + ": non-finite entries");
}

}  // namespace

Stepper::Stepper(const ContactProblem& problem, double dt)
    : problem_(problem), boundary_(problem), dt_(dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw InputError("dt: " + std::to_string(dt) + ", expected a positive finite time step");
}

void Stepper::initialize(const Vector& u, const Vector& v, const Vector& F, double t) {
  const Index n = problem_.size();
  check_size(u, n, "u");
  check_size(v, n, "v");
  check_size(F, n, "F");
  if (!std::isfinite(t)) throw InputError("t: non-finite initial time");
  const Vector gap = boundary_.gaps(u);
  const double scale = std::max(u.cwiseAbs().maxCoeff(), problem_.gaps().cwiseAbs().maxCoeff());
  for (Index k = 0; k < gap.size(); ++k)
    if (gap(k) < -kPenetrationTolerance * scale)
      throw InputError("u: initial penetration at contact node " + std::to_string(k) +
                       " (gap " + std::to_string(gap(k)) + " < 0)");
  u_ = u;
  v_ = v;
  F_ = F;
  t_ = t;
  a_.resize(n);
  start();
  initialized_ = true;
}

void Stepper::start() {
  active_ = boundary_.enforce(u_, F_, {}).active;
  boundary_.project(v_, active_, Vector::Zero(problem_.n_contact()));
  solve_acceleration(F_);
}

void Stepper::finish_step(const Vector& F_next) {
  const Vector zero = Vector::Zero(problem_.n_contact());
  boundary_.project(v_, active_, zero);
  boundary_.project(a_, active_, zero);
  F_ = F_next;
  t_ += dt_;
}

Energies Stepper::energies() const {
  Energies e;
  e.kinetic = 0.5 * v_.dot(mass() * v_);
  e.elastic = 0.5 * u_.dot(problem_.K() * u_);
  e.load = -F_.dot(u_);
  return e;
}

}  // namespace nbm
