#include "api/solver.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "api/model_data.hpp"
#include "base/errors.hpp"
#include "periodic/reduced_basis.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/following_frame_stepper.hpp"
#include "time/generalized_alpha.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/moreau_jean_stepper.hpp"
#include "time/newmark_stepper.hpp"

namespace nbm {
namespace {

// Round-off of a penetration, relative to the displacement scale (as the
// steppers' check of an initial state).
constexpr double kReplacePenetrationTolerance = 1e-12;
// How far the expansion of a restart's reduced state may be from the u, v
// given with it, relative to their size (the same computation: round-off).
constexpr double kReducedStateTolerance = 1e-12;

Vector to_vector(const std::vector<double>& x, long n, const char* name) {
  if (static_cast<long>(x.size()) != n)
    throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n) + " (the number of dofs)");
  return Eigen::Map<const Vector>(x.data(), n);
}

// The implicit NBM schemes of Newmark's family (implicit_scheme.hpp).
bool implicit_nbm(TimeScheme scheme) {
  return scheme == TimeScheme::kNewmark || scheme == TimeScheme::kGeneralizedAlpha ||
         scheme == TimeScheme::kHhtAlpha;
}

std::string quoted(const char* name) { return std::string("\"") + name + "\""; }

// Checks the scheme's options and how they go with the model's.
void check_options(const SchemeOptions& options, const ModelOptions& model) {
  const TimeScheme scheme = options.scheme;
  const std::string with_scheme = "given with scheme " + quoted(name(scheme));
  const bool alpha = scheme == TimeScheme::kGeneralizedAlpha || scheme == TimeScheme::kHhtAlpha;
  if (scheme != TimeScheme::kNewmark)
    for (const auto& [value, option] : {std::pair{&options.beta, "beta"}, {&options.gamma, "gamma"}})
      if (value->has_value())
        throw InputError(std::string(option) + ": " + with_scheme +
                         (scheme == TimeScheme::kExplicit
                              ? ", which is central differences (beta = 0, gamma = 1/2); "
                                "Newmark parameters need scheme \"newmark\""
                          : scheme == TimeScheme::kMoreauJean
                              ? ", whose theta = 1/2 is fixed"
                              : ", whose parameters follow from rhoInf (method.md §5.4)"));
  if (options.rho_inf.has_value() && !alpha)
    throw InputError("rhoInf: " + with_scheme +
                     "; it is the spectral radius at infinity of schemes "
                     "\"generalized-alpha\" and \"hht-alpha\"");
  if (options.restitution.has_value() && scheme != TimeScheme::kMoreauJean)
    throw InputError("restitution: " + with_scheme +
                     "; it is the coefficient of Newton's law of scheme \"moreau-jean\"");
  if (model.obstacle && scheme != TimeScheme::kNewmark)
    throw InputError("obstacle: needs mass = \"redistributed\" and scheme \"newmark\" (the "
                     "contact frame follows the body only with massless contact nodes, and "
                     "with Newmark's scheme)");
  if (options.energy && *options.energy != EnergyControl::kNone &&
      (scheme != TimeScheme::kNewmark || model.obstacle || options.beta.value_or(0.25) != 0.25 ||
       options.gamma.value_or(0.5) != 0.5 || model.rayleigh_stiffness != 0 ||
       (model.mass == MassTreatment::kConsistent && model.damped())))
    throw InputError("energy: given without the energy-stable step it controls, which needs "
                     "scheme \"newmark\" with beta = 1/4 and gamma = 1/2, no rayleighK and "
                     "no obstacle, and with mass = \"consistent\" no damping at all "
                     "(method.md §5.1, §5.3)");
  if (options.modes.has_value() && (!implicit_nbm(scheme) || model.obstacle))
    throw InputError("modes: " + (model.obstacle ? std::string("given with obstacle=, whose "
                                                               "frame follows every component "
                                                               "of the contact nodes")
                                                 : with_scheme) +
                     "; the reduced model (method.md §6) is integrated by the implicit NBM "
                     "schemes \"newmark\", \"generalized-alpha\" and \"hht-alpha\" on a "
                     "model without obstacle=");
  if (model.mass == MassTreatment::kRedistributed && !implicit_nbm(scheme))
    throw InputError("mass: \"redistributed\" needs scheme \"newmark\", "
                     "\"generalized-alpha\" or \"hht-alpha\" (the massless boundary has no "
                     "explicit or Moreau-Jean variant)");
}

// The implicit scheme's parameters (options checked).
SchemeParameters scheme_parameters(const SchemeOptions& options) {
  constexpr double kDefaultRhoInf = 0.8;
  if (options.scheme == TimeScheme::kGeneralizedAlpha)
    return generalized_alpha(options.rho_inf.value_or(kDefaultRhoInf));
  if (options.scheme == TimeScheme::kHhtAlpha)
    return hht_alpha(options.rho_inf.value_or(kDefaultRhoInf));
  const SchemeParameters defaults;
  return SchemeParameters::newmark(options.beta.value_or(defaults.beta),
                                   options.gamma.value_or(defaults.gamma));
}

// What the energy-stable step bounds (option energy, checked): kBounded by
// default where the step exists (method.md §5.1, §5.3).
EnergyControl energy_control(const SchemeOptions& options) {
  return options.energy.value_or(EnergyControl::kBounded);
}

// The time scheme of the options on `problem`, the model's own or its
// reduction, with `damping` in the problem's coordinates (options checked).
std::unique_ptr<Stepper> make_stepper(const SchemeOptions& options, const Model::Data& model,
                                      const ContactProblem& problem, const Damping& damping,
                                      double& critical_dt) {
  critical_dt = 0;
  const SchemeParameters scheme = scheme_parameters(options);
  if (model.obstacle) {
    FollowingFrameOptions frame;
    frame.beta = scheme.beta;
    frame.gamma = scheme.gamma;
    return std::make_unique<FollowingFrameStepper>(problem, model.M_user, model.positions,
                                                   model.obstacle, options.dt, frame,
                                                   model.damping_user);
  }
  if (problem.massless_boundary())
    return std::make_unique<MasslessNewmarkStepper>(problem, options.dt, scheme, damping,
                                                    ContactColumns::kAuto,
                                                    energy_control(options));
  if (implicit_nbm(options.scheme)) {
    NewmarkParameters parameters;
    parameters.scheme = scheme;
    parameters.energy = energy_control(options);
    return std::make_unique<NewmarkStepper>(problem, options.dt, parameters, damping);
  }
  if (options.scheme == TimeScheme::kExplicit) {
    auto cd = std::make_unique<CentralDifferenceStepper>(problem, options.dt, damping);
    critical_dt = cd->critical_dt();
    return cd;
  }
  return std::make_unique<MoreauJeanStepper>(problem, options.dt,
                                             options.restitution.value_or(0.0), damping);
}

}  // namespace

const char* name(TimeScheme scheme) {
  switch (scheme) {
    case TimeScheme::kNewmark: return "newmark";
    case TimeScheme::kGeneralizedAlpha: return "generalized-alpha";
    case TimeScheme::kHhtAlpha: return "hht-alpha";
    case TimeScheme::kExplicit: return "explicit";
    case TimeScheme::kMoreauJean: return "moreau-jean";
  }
  return "?";
}

struct Solver::Impl {
  SolverOptions options;  // the model's and the scheme's
  std::shared_ptr<const Model> model;
  const ContactProblem* problem = nullptr;  // the model's
  // Option modes: the model's reduction and its contact problem, which the
  // stepper integrates (null without it).
  std::unique_ptr<ReducedBasis> basis;
  std::unique_ptr<ContactProblem> reduced;
  std::unique_ptr<Stepper> stepper;
  double critical_dt = 0;
  long steps = 0, fallbacks = 0;
  // The user arrays as last returned: a step must start from them. a_user:
  // the acceleration in user coordinates, as acceleration() hands it out.
  std::vector<double> u_user, v_user, a_user;
  // With the option modes: the last load, full internal coordinates (for
  // reduction_residual).
  Vector F_full;
  // The obstacle and the load's rates of the next call (internal coordinates).
  Obstacle obstacle;
  Vector F_rate, F_accel;

  ContactLoad load(const Vector& F) const {
    return {F, obstacle, F_rate.size() ? &F_rate : nullptr, F_accel.size() ? &F_accel : nullptr};
  }

  /// Integrates `m` from now on: its stepper (options checked), on its
  /// reduction with the option modes.
  void build(std::shared_ptr<const Model> m) {
    const Model::Data& data = m->data();
    if (options.modes) {
      basis = std::make_unique<ReducedBasis>(*data.problem,
                                             Vector::Zero(data.problem->size()), *options.modes);
      // Small and dense: factored by CHOLMOD in every process, whatever
      // factors the full model.
      reduced = std::make_unique<ContactProblem>(basis->contact_problem());
      stepper = make_stepper(options, data, *reduced, basis->reduce(data.damping), critical_dt);
    } else {
      std::unique_ptr<Stepper> s =
          make_stepper(options, data, *data.problem, data.damping, critical_dt);
      stepper = std::move(s);  // the old stepper refers to the old model: first
    }
    model = std::move(m);
    problem = &model->problem();
    obstacle = Obstacle::at_rest(problem->gaps());
  }

  /// The stepper's coordinates of a user vector (a state or a rate of it):
  /// internal, then reduced with the option modes (the M-orthogonal
  /// projection of the interior); up() goes back.
  Vector down(const Vector& x_user) const {
    const Vector x = problem->to_internal(x_user);
    return basis ? basis->reduce_state(x) : x;
  }
  Vector up(const Vector& y) const { return problem->to_user(basis ? basis->expand_state(y) : y); }
  /// The stepper's coordinates of a load or of its rates: T^T F with the
  /// option modes. `current`: the load of the state the call reaches, kept
  /// (F_full).
  Vector load_down(const Vector& F_user, bool current) {
    Vector F = problem->to_internal(F_user);
    if (!basis) return F;
    Vector F_reduced = basis->reduce_load(F);
    if (current) F_full = std::move(F);
    return F_reduced;
  }

  /// What replace_contacts() puts back if the new description fails.
  struct Saved {
    std::shared_ptr<const Model> model;
    std::unique_ptr<Stepper> stepper;
    Obstacle obstacle;
    double critical_dt;
    std::vector<double> u_user, v_user, a_user;
  };
  Saved save() {
    return {model, std::move(stepper), obstacle, critical_dt, u_user, v_user, a_user};
  }
  void put_back(Saved& s) {
    stepper = std::move(s.stepper);
    model = std::move(s.model);
    problem = &model->problem();
    obstacle = std::move(s.obstacle);
    critical_dt = s.critical_dt;
    u_user = std::move(s.u_user);
    v_user = std::move(s.v_user);
    a_user = std::move(s.a_user);
  }

  void publish(std::vector<double>& u, std::vector<double>& v) {
    if (basis) {
      // One pass over the basis for u and v; the acceleration only when
      // asked for (acceleration_user). Restarts take the reduced state from
      // the scheme state, so there is no round trip to make.
      Matrix Y(reduced->size(), 2);
      Y << stepper->u(), stepper->v();
      const Matrix X = basis->expand_states(Y);
      const Vector uu = problem->to_user(X.col(0)), vv = problem->to_user(X.col(1));
      u.assign(uu.data(), uu.data() + uu.size());
      v.assign(vv.data(), vv.data() + vv.size());
      u_user = u;
      v_user = v;
      a_user.clear();
      return;
    }
    const Vector uu = up(stepper->u());
    const Vector vv = up(stepper->v());
    const Vector aa = up(stepper->a());
    if (!problem->exact_round_trip()) {
      // Exact restarts: the state becomes the one a restart from the user's
      // arrays rebuilds (rotated contact nodes round off in user coordinates;
      // the round trip is not idempotent, hence the user arrays are kept).
      stepper->replace_kinematics(down(uu), down(vv), down(aa));
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
    const Vector F_int = load_down(FF, true);
    if (continuing)
      stepper->continue_from(down(uu), down(vv), load(F_int), t);
    else
      stepper->initialize(down(uu), down(vv), load(F_int), t);
    const Stepper& st = *stepper;  // finite data can still overflow (M^-1 F)
    if (!st.u().allFinite() || !st.v().allFinite() || !st.a().allFinite())
      throw NumericalError("initialization: the state is not finite (overflow); the data are "
                           "too badly scaled");
    publish(u, v);
  }

  /// The acceleration on the user's dofs (expanded on demand on a reduced
  /// model).
  std::vector<double> acceleration_user() const {
    if (!basis) return a_user;
    const Vector a = up(stepper->a());
    return {a.data(), a.data() + a.size()};
  }

  /// With the option modes the scheme state ends with the reduced state
  /// (y_u, y_v, y_a), so that a restart goes on from the very coordinates
  /// the run had (their expansion is u, v; projecting u, v back would round).
  Index reduced_state_size() const { return basis ? 3 * reduced->size() : 0; }

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

Solver::Solver(std::shared_ptr<const Model> model, const SchemeOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (!model) throw InputError("model: none given");
  check_options(options, model->options());
  static_cast<ModelOptions&>(impl_->options) = model->options();
  static_cast<SchemeOptions&>(impl_->options) = options;
  impl_->build(std::move(model));
}

Solver::Solver(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
               const SolverOptions& options)
    : Solver((check_options(options, options),
              std::make_shared<const Model>(M, K, contact, options)),
             options) {}

Solver::~Solver() = default;

long Solver::n_dofs() const { return impl_->problem->n_dofs(); }
long Solver::n_contact() const { return impl_->problem->n_contact(); }
const SolverOptions& Solver::options() const { return impl_->options; }
std::vector<long> Solver::fixed_dofs() const { return impl_->model->fixed_dofs(); }
const std::shared_ptr<const Model>& Solver::model() const { return impl_->model; }
bool Solver::initialized() const { return impl_->stepper->initialized(); }
double Solver::time() const { return impl_->stepper->time(); }
long Solver::steps() const { return impl_->steps; }
long Solver::fallbacks() const { return impl_->fallbacks; }
double Solver::critical_dt() const { return impl_->critical_dt; }

double Solver::reduction_residual() const {
  const Impl& m = *impl_;
  if (!m.basis)
    throw InputError("reduction residual: the solver integrates the full model; it is the "
                     "reduction error of a reduced one (modes=)");
  if (!m.stepper->initialized())
    throw InputError("reduction residual: no state yet; call the initialization first");
  Matrix Y(m.reduced->size(), 3);
  Y << m.stepper->u(), m.stepper->v(), m.stepper->a();
  const Matrix X = m.basis->expand_states(Y);
  return m.basis->equation_residual(X.col(0), X.col(1), X.col(2), m.F_full,
                                    m.model->data().damping, m.stepper->active());
}

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
    *y = impl_->load_down(xx, false);
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
  const Vector F_int = impl_->load_down(FF, true);
  const Vector state = Eigen::Map<const Vector>(scheme_state.data(), scheme_state.size());
  if (!state.allFinite()) throw InputError("scheme state: non-finite entries");
  const Index R = impl_->reduced_state_size();
  if (R == 0) {
    impl_->stepper->restore(impl_->down(uu), impl_->down(vv), impl_->down(aa), set,
                            impl_->load(F_int), t, state);
  } else {
    // A reduced model: the reduced state saved at the end of the scheme state.
    if (state.size() < R)
      throw InputError("scheme state: size " + std::to_string(state.size()) + ", expected " +
                       "at least " + std::to_string(R) + " (it ends with the reduced state of " +
                       "modes=, 3 x " + std::to_string(R / 3) + " entries: save it with u, v)");
    const Index r = R / 3;
    const Vector own = state.head(state.size() - R);
    const Vector yu = state.segment(state.size() - R, r), yv = state.segment(state.size() - 2 * r, r),
                 ya = state.tail(r);
    for (const auto& [y, x, name] : {std::tuple{&yu, &uu, "u"}, {&yv, &vv, "v"}}) {
      const Vector expanded = impl_->up(*y);
      const double scale = std::max(x->cwiseAbs().maxCoeff(), expanded.cwiseAbs().maxCoeff());
      if ((expanded - *x).cwiseAbs().maxCoeff() > kReducedStateTolerance * scale)
        throw InputError(std::string("scheme state: its reduced state does not expand to ") +
                         name + " (" + std::to_string((expanded - *x).cwiseAbs().maxCoeff()) +
                         " apart); expected the scheme state saved with this " + name);
    }
    impl_->stepper->restore(yu, yv, ya, set, impl_->load(F_int), t, own);
  }
  impl_->steps = impl_->fallbacks = 0;
  // u, v stay as given (fixed dofs zeroed): the internal state is their
  // image, exactly what the uninterrupted run holds after publish().
  for (long f : impl_->model->fixed_dofs()) u[f] = v[f] = 0.0;
  impl_->u_user = u;
  impl_->v_user = v;
  impl_->a_user = a;
  for (long f : impl_->model->fixed_dofs()) impl_->a_user[f] = 0.0;
}

StepInfo Solver::step(std::vector<double>& u, std::vector<double>& v,
                      const std::vector<double>& F) {
  if (!initialized()) throw InputError("step: no initial state; call the initialization first");
  const ContactProblem& p = *impl_->problem;
  const Vector FF = to_vector(F, p.n_dofs(), "F");
  if (!FF.allFinite()) throw InputError("F: non-finite entries");
  impl_->check_unchanged(u, v);
  const Vector F_int = impl_->load_down(FF, true);
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
  if (impl_->basis)
    throw InputError("replace contacts: the solver integrates a reduced model (modes=), whose "
                     "basis is built on its contact nodes; build a new one on the new contact "
                     "description");
  impl_->check_unchanged(u, v);
  const double t = time();
  // Moreau-Jean's states penetrate by O(dt v) and keep it (the NBM schemes'
  // never do: start() checks them): the new description may not be
  // penetrated deeper than the last obstacle is.
  const double own_penetration = std::max(0.0, -impl_->stepper->gaps().minCoeff());
  Impl::Saved saved = impl_->save();  // kept until the new description has worked
  std::vector<double> uu = u, vv = v;
  try {
    impl_->build(saved.model->with_contacts(contact));
    impl_->start(uu, vv, F, t, true);
    impl_->stepper->carry_over(*saved.stepper);
    if (impl_->options.scheme == TimeScheme::kMoreauJean) {
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
std::vector<double> Solver::acceleration() const { return impl_->acceleration_user(); }
std::vector<double> Solver::scheme_state() const {
  const Stepper& st = *impl_->stepper;
  const Vector x = st.scheme_state();
  std::vector<double> state(x.data(), x.data() + x.size());
  if (impl_->basis)
    for (const Vector* y : {&st.u(), &st.v(), &st.a()}) state.insert(state.end(), y->data(), y->data() + y->size());
  return state;
}
std::vector<double> Solver::energies() const {
  const Energies e = impl_->stepper->energies();
  return {e.kinetic, e.elastic, e.load, e.total(), e.obstacle_work, e.dissipated, e.load_work};
}

}  // namespace nbm
