#include "api/solver.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "base/errors.hpp"
#include "contact/contact_problem.hpp"
#include "contact/damping.hpp"
#include "contact/mass_redistribution.hpp"
#include "linalg/sparse_input.hpp"
#include "obstacle/rigid_obstacle.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/following_frame_stepper.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/moreau_jean_stepper.hpp"
#include "time/newmark_stepper.hpp"

namespace nbm {
namespace {

std::vector<Index> to_index(const std::vector<long>& v) { return {v.begin(), v.end()}; }

// Round-off of a penetration, relative to the displacement scale (as the
// steppers' check of an initial state).
constexpr double kReplacePenetrationTolerance = 1e-12;

Vector to_vector(const std::vector<double>& x, long n, const char* name) {
  if (static_cast<long>(x.size()) != n)
    throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n) + " (the number of dofs)");
  return Eigen::Map<const Vector>(x.data(), n);
}

// Checks the options that do not depend on the matrices, once: the scheme,
// the mass treatment and which parameters go with which.
void check_options(const SolverOptions& options) {
  const std::string& scheme = options.scheme;
  if (scheme != "newmark" && scheme != "explicit" && scheme != "moreau-jean")
    throw InputError("scheme: \"" + scheme +
                     "\", expected \"newmark\", \"explicit\" or \"moreau-jean\"");
  if (scheme != "newmark")
    for (const auto& [value, name] : {std::pair{&options.beta, "beta"}, {&options.gamma, "gamma"}})
      if (value->has_value())
        throw InputError(std::string(name) + ": given with scheme \"" + scheme + "\"" +
                         (scheme == "explicit"
                              ? ", which is central differences (beta = 0, gamma = 1/2); "
                                "Newmark parameters need scheme \"newmark\""
                              : ", whose theta = 1/2 is fixed"));
  if (options.restitution.has_value() && scheme != "moreau-jean")
    throw InputError("restitution: given with scheme \"" + scheme +
                     "\"; it is the coefficient of Newton's law of scheme \"moreau-jean\"");
  if (options.obstacle && (options.mass != "redistributed" || scheme != "newmark"))
    throw InputError("obstacle: needs mass = \"redistributed\" and scheme \"newmark\" (the "
                     "contact frame follows the body only with massless contact nodes)");
  if (options.energy) {
    const std::string& energy = *options.energy;
    if (energy != "bounded" && energy != "monotone" && energy != "none")
      throw InputError("energy: \"" + energy +
                       "\", expected \"bounded\", \"monotone\" or \"none\"");
    const bool damped = options.rayleigh_mass != 0 || options.rayleigh_stiffness != 0 ||
                        options.damping.rows != 0;
    if (energy != "none" &&
        (scheme != "newmark" || options.obstacle || options.beta.value_or(0.25) != 0.25 ||
         options.gamma.value_or(0.5) != 0.5 || options.rayleigh_stiffness != 0 ||
         (options.mass == "consistent" && damped)))
      throw InputError("energy: given without the energy-stable step it controls, which needs "
                       "scheme \"newmark\" with beta = 1/4 and gamma = 1/2, no rayleighK and "
                       "no obstacle, and with mass = \"consistent\" no damping at all "
                       "(method.md §5.1, §5.3)");
  }
  if (options.mass == "redistributed") {
    if (scheme != "newmark")
      throw InputError("mass: \"redistributed\" needs scheme \"newmark\" (the massless "
                       "boundary has no explicit or Moreau-Jean variant)");
  } else if (options.mass != "consistent") {
    throw InputError("mass: \"" + options.mass +
                     "\", expected \"consistent\" or \"redistributed\"");
  } else if (!options.positions.empty()) {
    throw InputError("positions: given with mass = \"consistent\"; they are used only by "
                     "mass = \"redistributed\"");
  }
}

TimeLaw time_law(const TimeLawDescription& d, const std::string& who) {
  if (d.harmonics.size() % 3 != 0)
    throw InputError(who + ": " + std::to_string(d.harmonics.size()) +
                     " harmonic coefficients, expected triples (omega, cos, sin)");
  TimeLaw law;
  law.offset = d.offset, law.rate = d.rate, law.accel = d.accel;
  for (std::size_t j = 0; j < d.harmonics.size(); j += 3)
    law.harmonics.push_back({d.harmonics[j], d.harmonics[j + 1], d.harmonics[j + 2]});
  return law;
}

Vector vector_of(const std::vector<double>& x) { return Eigen::Map<const Vector>(x.data(), x.size()); }

// The core's obstacle for the option `obstacle` (method.md §10).
std::shared_ptr<const RigidObstacle> make_obstacle(const ObstacleDescription& d) {
  Side side = Side::kOutside;
  if (d.side == "inside")
    side = Side::kInside;
  else if (d.side != "outside")
    throw InputError("obstacle side: \"" + d.side + "\", expected \"outside\" or \"inside\"");
  const TimeLaw move = time_law(d.translation, "obstacle translation");
  const TimeLaw grow = time_law(d.radius_change, "obstacle radius change");
  if (d.kind == "plane") {
    if (!grow.constant() || grow.offset != 0)
      throw InputError("obstacle radius change: given for a plane, which has no radius");
    return make_plane(vector_of(d.point), vector_of(d.axis), move);
  }
  if (d.kind == "circle" || d.kind == "sphere") {
    const std::size_t dim = d.kind == "circle" ? 2 : 3;
    if (d.point.size() != dim)
      throw InputError("obstacle point: " + std::to_string(d.point.size()) + " coordinates, a " +
                       d.kind + " expects " + std::to_string(dim));
    return make_ball(vector_of(d.point), d.radius, side, vector_of(d.direction), move, grow);
  }
  if (d.kind == "cylinder")
    return make_cylinder(vector_of(d.point), vector_of(d.axis), d.radius, side,
                         vector_of(d.direction), move, grow);
  throw InputError("obstacle kind: \"" + d.kind +
                   "\", expected \"plane\", \"circle\", \"sphere\" or \"cylinder\"");
}

// The node coordinates of mass = "redistributed", one row per dof.
Matrix positions_of(const SolverOptions& options, Index n) {
  const long n_pos = static_cast<long>(options.positions.size());
  if (n_pos == 0 || n_pos % n != 0 || n_pos / n > 3)
    throw InputError("positions: size " + std::to_string(n_pos) +
                     ", expected 1, 2 or 3 coordinates per dof (n_dofs = " + std::to_string(n) +
                     ") with mass = \"redistributed\"");
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      options.positions.data(), n, n_pos / n);
}

// What the energy-stable step bounds (option energy, checked): "bounded" by
// default where the step exists (method.md §5.1, §5.3).
EnergyControl energy_control(const SolverOptions& options) {
  const std::string energy = options.energy.value_or("bounded");
  return energy == "monotone" ? EnergyControl::kMonotone
         : energy == "none"   ? EnergyControl::kNone
                              : EnergyControl::kBounded;
}

// The time scheme of the options on a problem (options checked), with the
// damping in the problem's internal coordinates.
std::unique_ptr<Stepper> make_stepper(const SolverOptions& options, const ContactProblem& problem,
                                      const Damping& damping, double& critical_dt) {
  critical_dt = 0;
  const NewmarkParameters defaults;
  const double beta = options.beta.value_or(defaults.beta);
  const double gamma = options.gamma.value_or(defaults.gamma);
  if (problem.massless_boundary())
    return std::make_unique<MasslessNewmarkStepper>(problem, options.dt, beta, gamma, damping,
                                                    ContactColumns::kAuto, energy_control(options));
  if (options.scheme == "newmark") {
    NewmarkParameters parameters;
    parameters.beta = beta;
    parameters.gamma = gamma;
    parameters.energy = energy_control(options);
    return std::make_unique<NewmarkStepper>(problem, options.dt, parameters, damping);
  }
  if (options.scheme == "explicit") {
    auto cd = std::make_unique<CentralDifferenceStepper>(problem, options.dt, damping);
    critical_dt = cd->critical_dt();
    return cd;
  }
  return std::make_unique<MoreauJeanStepper>(problem, options.dt,
                                             options.restitution.value_or(0.0), damping);
}

}  // namespace

struct Solver::Impl {
  SolverOptions options;
  std::vector<long> fixed;
  // The user's matrices as given: a new contact set (replace_contacts) is
  // built on them, so that a solver constructed with it from the same
  // matrices restarts the run bit for bit (internal ones rotate back only to
  // round-off).
  SparseMatrix M_user, K_user;
  Damping damping_user;  // the damping with its matrix in user coordinates
  std::unique_ptr<ContactProblem> problem;
  std::unique_ptr<Stepper> stepper;
  double critical_dt = 0;
  long steps = 0, fallbacks = 0;
  // The user arrays as last returned: a step must start from them. a_user:
  // the acceleration in user coordinates, as acceleration() hands it out.
  std::vector<double> u_user, v_user, a_user;
  // The obstacle and the load's rates of the next call (internal coordinates).
  Obstacle obstacle;
  Vector F_rate, F_accel;

  ContactLoad load(const Vector& F) const {
    return {F, obstacle, F_rate.size() ? &F_rate : nullptr, F_accel.size() ? &F_accel : nullptr};
  }

  /// Builds the problem and the stepper for a contact description.
  void build(const SparseMatrix& M, const SparseMatrix& K, const ContactDescription& contact) {
    const Index n = K.rows();
    if (contact.gaps.empty())
      throw InputError("contact set is empty: expected at least one contact node (gaps)");
    const std::vector<Index> fixed_dofs(fixed.begin(), fixed.end());
    ContactSet contacts(n, to_index(contact.dofs), contact.normals,
                        Eigen::Map<const Vector>(contact.gaps.data(), contact.gaps.size()),
                        fixed_dofs);
    if (options.obstacle) {
      build_following(M, K, contacts);
      return;
    }
    std::unique_ptr<ContactProblem> p;
    if (options.mass == "redistributed") {
      const Matrix X = positions_of(options, n);
      p = std::make_unique<ContactProblem>(M, K, std::move(contacts), fixed_dofs, &X);
    } else {
      p = std::make_unique<ContactProblem>(M, K, std::move(contacts), fixed_dofs);
    }
    Damping damping = damping_user;
    if (damping.has_matrix()) damping.C_user = p->to_internal(damping_user.C_user);
    std::unique_ptr<Stepper> s = make_stepper(options, *p, damping, critical_dt);
    stepper = std::move(s);  // the old stepper refers to the old problem: first
    problem = std::move(p);
    obstacle = Obstacle::at_rest(problem->gaps());
  }

  /// The contact nodes of `contacts` (checked as given) in the user's axes,
  /// with the option `obstacle` followed by the contact frame (method.md §10).
  void build_following(const SparseMatrix& M, const SparseMatrix& K, const ContactSet& contacts) {
    const Index n = K.rows();
    const std::vector<Index> fixed_dofs(fixed.begin(), fixed.end());
    std::vector<Index> dofs;
    for (Index k = 0; k < contacts.size(); ++k)
      for (int j = 0; j < contacts.dim(); ++j) dofs.push_back(contacts.dof(k, j));
    auto p = std::make_unique<ContactProblem>(
        M, K, ContactSet::in_user_axes(n, std::move(dofs), contacts.dim(), fixed_dofs), fixed_dofs);
    const Matrix X = positions_of(options, n);
    if (X.cols() != contacts.dim())
      throw InputError("positions: " + std::to_string(X.cols()) + " coordinates per dof, expected " +
                       std::to_string(contacts.dim()) + " (the dofs per contact node)");
    FollowingFrameOptions frame;
    const NewmarkParameters defaults;
    frame.beta = options.beta.value_or(defaults.beta);
    frame.gamma = options.gamma.value_or(defaults.gamma);
    std::unique_ptr<Stepper> s = std::make_unique<FollowingFrameStepper>(
        *p, M, X, make_obstacle(*options.obstacle), options.dt, frame, damping_user);
    critical_dt = 0;
    stepper = std::move(s);
    problem = std::move(p);
    obstacle = Obstacle::at_rest(problem->gaps());
  }

  /// What replace_contacts() puts back if the new description fails.
  struct Saved {
    std::unique_ptr<ContactProblem> problem;
    std::unique_ptr<Stepper> stepper;
    Obstacle obstacle;
    double critical_dt;
    std::vector<double> u_user, v_user, a_user;
  };
  Saved save() {
    return {std::move(problem), std::move(stepper), obstacle, critical_dt, u_user, v_user, a_user};
  }
  void put_back(Saved& s) {
    stepper = std::move(s.stepper);
    problem = std::move(s.problem);
    obstacle = std::move(s.obstacle);
    critical_dt = s.critical_dt;
    u_user = std::move(s.u_user);
    v_user = std::move(s.v_user);
    a_user = std::move(s.a_user);
  }

  void publish(std::vector<double>& u, std::vector<double>& v) {
    const Vector uu = problem->to_user(stepper->u());
    const Vector vv = problem->to_user(stepper->v());
    const Vector aa = problem->to_user(stepper->a());
    if (!problem->exact_round_trip()) {
      // Exact restarts: the state becomes the one a restart from the user's
      // arrays rebuilds (rotated contact nodes round off in user coordinates;
      // the round trip is not idempotent, hence the user arrays are kept).
      stepper->replace_kinematics(problem->to_internal(uu), problem->to_internal(vv),
                                  problem->to_internal(aa));
    }
    u.assign(uu.data(), uu.data() + uu.size());
    v.assign(vv.data(), vv.data() + vv.size());
    u_user = u;
    v_user = v;
    a_user.assign(aa.data(), aa.data() + aa.size());
  }

  /// Starts the stepper from the user's u, v, F at time t (published back):
  /// a new state, or with `continuing` one a run reached (replace_contacts).
  void start(std::vector<double>& u, std::vector<double>& v, const std::vector<double>& F,
             double t, bool continuing) {
    const ContactProblem& p = *problem;
    const long n = p.n_dofs();
    const Vector uu = to_vector(u, n, "u"), vv = to_vector(v, n, "v"), FF = to_vector(F, n, "F");
    for (const auto& [x, name] : {std::pair{&uu, "u"}, {&vv, "v"}, {&FF, "F"}})
      if (!x->allFinite()) throw InputError(std::string(name) + ": non-finite entries");
    const Vector F_int = p.to_internal(FF);
    if (continuing)
      stepper->continue_from(p.to_internal(uu), p.to_internal(vv), load(F_int), t);
    else
      stepper->initialize(p.to_internal(uu), p.to_internal(vv), load(F_int), t);
    const Stepper& st = *stepper;  // finite data can still overflow (M^-1 F)
    if (!st.u().allFinite() || !st.v().allFinite() || !st.a().allFinite())
      throw NumericalError("initialization: the state is not finite (overflow); the data are "
                           "too badly scaled");
    publish(u, v);
  }

  /// u, v must be the arrays the last call returned.
  void check_unchanged(const std::vector<double>& u, const std::vector<double>& v) const {
    if (u.size() != u_user.size())
      throw InputError("u: size " + std::to_string(u.size()) + ", expected " +
                       std::to_string(u_user.size()) + " (resized since the last step?)");
    if (v.size() != v_user.size())
      throw InputError("v: size " + std::to_string(v.size()) + ", expected " +
                       std::to_string(v_user.size()) + " (resized since the last step?)");
    if (u != u_user || v != v_user)
      throw InputError(
          "u, v: changed since the last step; to restart from a new state, initialize again");
  }
};

void check_obstacle(const ObstacleDescription& obstacle) { make_obstacle(obstacle); }

double obstacle_distance(const ObstacleDescription& obstacle, const std::vector<double>& x,
                         double t) {
  const auto o = make_obstacle(obstacle);
  if (static_cast<int>(x.size()) != o->dim())
    throw InputError("x: " + std::to_string(x.size()) + " coordinates, expected " +
                     std::to_string(o->dim()) + " (the obstacle's dimension)");
  return o->at(x.data(), t).phi;
}

Solver::Solver(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
               const SolverOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_options(options);
  impl_->options = options;
  const SparseMatrix Ks = to_sparse(K, "K");
  const SparseMatrix Ms = to_sparse(M, "M");
  if (Ms.rows() != Ks.rows() || Ms.cols() != Ks.cols())
    throw InputError("M: size " + std::to_string(Ms.rows()) + "x" + std::to_string(Ms.cols()) +
                     " differs from the size of K, " + std::to_string(Ks.rows()) + "x" +
                     std::to_string(Ks.cols()));
  // Range errors of `fixed` are reported by ContactSet.
  std::vector<Index> fixed = to_index(options.fixed);
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  impl_->fixed.assign(fixed.begin(), fixed.end());
  Damping& damping = impl_->damping_user;
  damping.a_M = options.rayleigh_mass;
  damping.b_K = options.rayleigh_stiffness;
  if (options.damping.rows != 0 || options.damping.cols != 0 || !options.damping.value.empty())
    damping.C_user = to_sparse(options.damping, "damping matrix");
  check_damping(damping, Ks.rows());
  impl_->build(Ms, Ks, contact);
  impl_->M_user = Ms;
  impl_->K_user = Ks;
}

Solver::~Solver() = default;

long Solver::n_dofs() const { return impl_->problem->n_dofs(); }
long Solver::n_contact() const { return impl_->problem->n_contact(); }
const SolverOptions& Solver::options() const { return impl_->options; }
std::vector<long> Solver::fixed_dofs() const { return impl_->fixed; }
bool Solver::initialized() const { return impl_->stepper->initialized(); }
double Solver::time() const { return impl_->stepper->time(); }
long Solver::steps() const { return impl_->steps; }
long Solver::fallbacks() const { return impl_->fallbacks; }
const ContactProblem& Solver::problem() const { return *impl_->problem; }
double Solver::critical_dt() const { return impl_->critical_dt; }

void Solver::set_obstacle(const std::vector<double>& g, const std::vector<double>& g_rate,
                          const std::vector<double>& g_accel) {
  if (impl_->options.obstacle)
    throw InputError("obstacle: given as the option obstacle=, which moves by its own law; gaps "
                     "along fixed normals do not apply");
  const long nc = n_contact();
  Obstacle o;
  for (const auto& [x, y, name] : {std::tuple{&g, &o.g, "gaps"}, {&g_rate, &o.g_rate, "gap rates"},
                                   {&g_accel, &o.g_accel, "gap accelerations"}}) {
    if (static_cast<long>(x->size()) != nc)
      throw InputError(std::string(name) + ": size " + std::to_string(x->size()) +
                       ", expected " + std::to_string(nc) + " (one per contact node)");
    *y = Eigen::Map<const Vector>(x->data(), nc);
    if (!y->allFinite()) throw InputError(std::string(name) + ": non-finite entries");
  }
  impl_->obstacle = std::move(o);
}

void Solver::set_load_rates(const std::vector<double>& F_rate,
                            const std::vector<double>& F_accel) {
  const ContactProblem& p = *impl_->problem;
  for (const auto& [x, y, name] : {std::tuple{&F_rate, &impl_->F_rate, "load rate"},
                                   {&F_accel, &impl_->F_accel, "load acceleration"}}) {
    if (x->empty()) {
      y->resize(0);
      continue;
    }
    const Vector xx = to_vector(*x, p.n_dofs(), name);
    if (!xx.allFinite()) throw InputError(std::string(name) + ": non-finite entries");
    *y = p.to_internal(xx);
  }
}

void Solver::initialize(std::vector<double>& u, std::vector<double>& v,
                        const std::vector<double>& F, double t) {
  impl_->start(u, v, F, t, false);
  impl_->steps = impl_->fallbacks = 0;
}

void Solver::restart(std::vector<double>& u, std::vector<double>& v,
                     const std::vector<double>& F, double t, const std::vector<double>& a,
                     const std::vector<long>& active, const std::vector<double>& scheme_state) {
  const ContactProblem& p = *impl_->problem;
  const long n = p.n_dofs();
  const Vector uu = to_vector(u, n, "u"), vv = to_vector(v, n, "v"), FF = to_vector(F, n, "F");
  const Vector aa = to_vector(a, n, "a");
  for (const auto& [x, name] :
       {std::pair{&uu, "u"}, {&vv, "v"}, {&FF, "F"}, {&aa, "a"}})
    if (!x->allFinite()) throw InputError(std::string(name) + ": non-finite entries");
  if (!std::isfinite(t)) throw InputError("t: non-finite time");
  // Runs start at t = 0 (initialize) and only go forward: a saved time is >= 0.
  if (t < 0)
    throw InputError("t: " + std::to_string(t) +
                     ", expected the saved time >= 0 (runs start at t = 0; nbmTime)");
  if (static_cast<long>(active.size()) != p.n_contact())
    throw InputError("active: size " + std::to_string(active.size()) + ", expected " +
                     std::to_string(p.n_contact()) + " (one entry per contact node)");
  ActiveSet set(active.size());
  for (std::size_t k = 0; k < active.size(); ++k) {
    if (active[k] != 0 && active[k] != 1)
      throw InputError("active: entry " + std::to_string(k) + " is " +
                       std::to_string(active[k]) + ", expected 0 or 1");
    set[k] = active[k] == 1;
  }
  const Vector F_int = p.to_internal(FF);
  const Vector state = Eigen::Map<const Vector>(scheme_state.data(), scheme_state.size());
  if (!state.allFinite()) throw InputError("scheme state: non-finite entries");
  impl_->stepper->restore(p.to_internal(uu), p.to_internal(vv), p.to_internal(aa), set,
                          impl_->load(F_int), t, state);
  impl_->steps = impl_->fallbacks = 0;
  // u, v stay as given (fixed dofs zeroed): the internal state is their
  // image, exactly what the uninterrupted run holds after publish().
  for (long f : impl_->fixed) u[f] = v[f] = 0.0;
  impl_->u_user = u;
  impl_->v_user = v;
  impl_->a_user = a;
  for (long f : impl_->fixed) impl_->a_user[f] = 0.0;
}

StepInfo Solver::step(std::vector<double>& u, std::vector<double>& v,
                      const std::vector<double>& F) {
  if (!initialized()) throw InputError("step: no initial state; call the initialization first");
  const ContactProblem& p = *impl_->problem;
  const Vector FF = to_vector(F, p.n_dofs(), "F");
  if (!FF.allFinite()) throw InputError("F: non-finite entries");
  impl_->check_unchanged(u, v);
  const Vector F_int = p.to_internal(FF);
  const StepReport r = impl_->stepper->step(impl_->load(F_int));
  const Stepper& st = *impl_->stepper;  // finite data can still overflow (beta dt^2 -> 0)
  if (!st.u().allFinite() || !st.v().allFinite() || !st.a().allFinite())
    throw NumericalError("step: the new state is not finite (overflow); dt, beta or the data "
                         "are too badly scaled");
  ++impl_->steps;
  if (r.fallback) ++impl_->fallbacks;
  impl_->publish(u, v);
  return {r.active_set_iterations, r.fallback, r.crossings};
}

void Solver::replace_contacts(const ContactDescription& contact, std::vector<double>& u,
                              std::vector<double>& v, const std::vector<double>& F) {
  if (!initialized())
    throw InputError("replace contacts: no state yet; call the initialization first");
  impl_->check_unchanged(u, v);
  const double t = time();
  // Moreau-Jean's states penetrate by O(dt v) and keep it (the NBM schemes'
  // never do: start() checks them): the new description may not be
  // penetrated deeper than the last obstacle is.
  const double own_penetration = std::max(0.0, -impl_->stepper->gaps().minCoeff());
  Impl::Saved saved = impl_->save();  // kept until the new description has worked
  std::vector<double> uu = u, vv = v;
  try {
    impl_->build(impl_->M_user, impl_->K_user, contact);
    impl_->start(uu, vv, F, t, true);
    impl_->stepper->carry_over(*saved.stepper);
    if (impl_->options.scheme == "moreau-jean") {
      const Stepper& st = *impl_->stepper;
      const Vector gap = st.gaps();
      const double u_scale = st.u().cwiseAbs().maxCoeff();
      for (Index k = 0; k < gap.size(); ++k)
        if (gap(k) < -own_penetration -
                         kReplacePenetrationTolerance *
                             std::max(u_scale, std::abs(st.obstacle().g(k))))
          throw InputError("u: penetration at contact node " + std::to_string(k) +
                           " of the new contact description (gap " + std::to_string(gap(k)) +
                           " < 0), deeper than the state's own penetration of the last "
                           "obstacle (" + std::to_string(own_penetration) +
                           ", Moreau-Jean's); expected a description the body does not "
                           "penetrate");
    }
  } catch (...) {
    impl_->put_back(saved);
    throw;
  }
  u = std::move(uu);
  v = std::move(vv);
}

std::vector<double> Solver::reactions() const {
  const Vector x = impl_->stepper->reactions();
  return {x.data(), x.data() + x.size()};
}
std::vector<double> Solver::gaps() const {
  const Vector x = impl_->stepper->gaps();
  return {x.data(), x.data() + x.size()};
}
std::vector<long> Solver::active() const {
  const auto& a = impl_->stepper->active();
  return {a.begin(), a.end()};
}
std::vector<double> Solver::acceleration() const { return impl_->a_user; }
std::vector<double> Solver::scheme_state() const {
  const Vector x = impl_->stepper->scheme_state();
  return {x.data(), x.data() + x.size()};
}
std::vector<double> Solver::energies() const {
  const Energies e = impl_->stepper->energies();
  return {e.kinetic, e.elastic, e.load, e.total(), e.obstacle_work, e.dissipated, e.load_work};
}

}  // namespace nbm
