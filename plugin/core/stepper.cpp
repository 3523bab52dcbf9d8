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

void Stepper::check_penetration(const Vector& u, const char* what) const {
  const Vector gap = boundary_.gaps(u);
  const double scale = std::max(u.cwiseAbs().maxCoeff(), problem_.gaps().cwiseAbs().maxCoeff());
  for (Index k = 0; k < gap.size(); ++k)
    if (gap(k) < -kPenetrationTolerance * scale)
      throw InputError(std::string("u: ") + what + " penetration at contact node " +
                       std::to_string(k) + " (gap " + std::to_string(gap(k)) + " < 0)");
}

void Stepper::initialize(const Vector& u, const Vector& v, const Vector& F, double t) {
  const Index n = problem_.size();
  check_size(u, n, "u");
  check_size(v, n, "v");
  check_size(F, n, "F");
  if (!std::isfinite(t)) throw InputError("t: non-finite initial time");
  check_penetration(u, "initial");
  u_ = u;
  v_ = v;
  F_ = F;
  t_ = t;
  a_.resize(n);
  start();
  initialized_ = true;
}

void Stepper::restore(const Vector& u, const Vector& v, const Vector& a, const ActiveSet& active,
                      const Vector& F, double t) {
  const Index n = problem_.size();
  check_size(u, n, "u");
  check_size(v, n, "v");
  check_size(a, n, "a");
  check_size(F, n, "F");
  if (static_cast<Index>(active.size()) != problem_.n_contact())
    throw InputError("active: size " + std::to_string(active.size()) + ", expected " +
                     std::to_string(problem_.n_contact()) + " (one entry per contact node)");
  if (!std::isfinite(t)) throw InputError("t: non-finite time");
  if (exact_impenetrability()) check_penetration(u, "restored");
  u_ = u;
  v_ = v;
  a_ = a;
  active_ = active;
  F_ = F;
  t_ = t;
  restored();
  initialized_ = true;
}

void Stepper::replace_kinematics(Vector u, Vector v, Vector a) {
  u_ = std::move(u);
  v_ = std::move(v);
  a_ = std::move(a);
}

void Stepper::start() {
  active_ = boundary_.enforce(u_, F_, {}).active;
  boundary_.project(v_, active_);
  solve_acceleration(F_);
}

void Stepper::finish_step(const Vector& F_next) {
  boundary_.project(v_, active_);
  boundary_.project(a_, active_);
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
