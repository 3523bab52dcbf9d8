#include "periodic/user_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/errors.hpp"
#include "periodic/continuation.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/orbit_model.hpp"

namespace nbm {
namespace {

ShootingOptions::Amplitude condition_of(const std::string& c) {
  if (c == "displacement") return ShootingOptions::Amplitude::displacement;
  if (c == "energy") return ShootingOptions::Amplitude::energy;
  if (c == "period") return ShootingOptions::Amplitude::period;
  throw InputError("condition: \"" + c + "\"; expected \"displacement\", \"energy\" or \"period\"");
}

}  // namespace

Vector user_vector(const std::vector<double>& x, Index n, const std::string& name) {
  if (static_cast<Index>(x.size()) != n)
    throw InputError(name + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n) + " (the number of dofs)");
  Vector y = Eigen::Map<const Vector>(x.data(), n);
  if (!y.allFinite()) throw InputError(name + ": non-finite entries");
  return y;
}

std::vector<double> to_std(const Vector& x) { return {x.data(), x.data() + x.size()}; }

Index find_interior(const ContactProblem& p, const ReducedField& field, long dof) {
  const Index internal = dof >= 0 && dof < p.n_dofs() ? p.internal_index(dof) : -1;
  if (internal < 0) return -1;
  const auto& in = field.interior();
  const auto it = std::lower_bound(in.begin(), in.end(), internal);
  return it != in.end() && *it == internal ? it - in.begin() : -1;
}

Index interior_position(const ContactProblem& p, const ReducedField& field, long dof,
                        const std::string& name) {
  if (dof < 0 || dof >= p.n_dofs())
    throw InputError(name + ": dof " + std::to_string(dof) + " out of range [0, " +
                     std::to_string(p.n_dofs()) + ")");
  const Index position = find_interior(p, field, dof);
  if (position < 0)
    throw InputError(name + ": dof " + std::to_string(dof) +
                     " is fixed or the normal component of a contact node; choose an interior "
                     "dof");
  return position;
}

OrbitSamples sample_orbit(const OrbitModel& model, const ExactFlow& flow,
                          const PeriodicOrbit& orbit) {
  constexpr int kSamples = 512;
  std::vector<double> times;
  for (int k = 0; k < kSamples; ++k) times.push_back(orbit.period * k / kSamples);
  for (const SwitchEvent& e : orbit.switches) times.push_back(e.t);
  std::sort(times.begin(), times.end());
  const ReducedField& field = model.field();
  const FlowResult r = flow.integrate(orbit.u0, orbit.v0, orbit.period, false, times);
  const Index n = field.size(), N = model.problem.n_dofs();
  OrbitSamples s;
  s.lo = Vector::Constant(N, INFINITY), s.hi = Vector::Constant(N, -INFINITY);
  for (Index k = 0; k < r.samples.cols(); ++k) {
    const Vector uk = r.samples.col(k).head(n), vk = r.samples.col(k).tail(n);
    // Moving contacts (method.md §8): the contact dofs and the energy at t.
    const double t = times[static_cast<std::size_t>(k)];
    const Vector user = model.user(uk, nullptr, t, &flow);
    s.lo = s.lo.cwiseMin(user), s.hi = s.hi.cwiseMax(user);
    s.energy_max = std::max(s.energy_max, field.energies(uk, vk, flow.forcing().shift(t),
                                                         flow.forcing().shift(t, 1))(3));
  }
  return s;
}

void check_amplitude_probe(const ContactProblem& problem, long probe) {
  if (probe == -1) return;  // the dof of largest amplitude
  if (probe < 0 || probe >= problem.n_dofs())
    throw InputError("probe: dof " + std::to_string(probe) + " out of range [0, " +
                     std::to_string(problem.n_dofs()) + ")");
  if (problem.internal_index(probe) < 0)
    throw InputError("probe: dof " + std::to_string(probe) + " is fixed");
}

long amplitude_probe(const ContactProblem& problem, const OrbitSamples& s, long probe) {
  if (probe >= 0) return probe;
  double best = -1;
  for (Index i = 0; i < problem.n_dofs(); ++i)
    if (problem.internal_index(i) >= 0 && s.hi(i) - s.lo(i) > best)
      best = s.hi(i) - s.lo(i), probe = i;
  return probe;
}

OrbitModel::OrbitModel(const ContactProblem& p) : problem(p) {
  std::vector<char> is_contact(p.size(), 0);
  for (Index c : p.contact_index()) is_contact[c] = 1;
  for (Index i = 0; i < p.size(); ++i)
    if (!is_contact[i]) interior.push_back(i);
}

ExactFlow OrbitModel::forced_flow(const Damping& d, const HarmonicLoad& e) const {
  return basis ? ExactFlow(field(), basis->reduce(d), basis->reduce(e)) : ExactFlow(field(), d, e);
}

void OrbitModel::force(const Damping& d, const HarmonicLoad& e) {
  damping = d, excitation = e;
  forced = std::make_unique<ExactFlow>(forced_flow(d, e));
}

Vector OrbitModel::unknowns(const Vector& user) const {
  const Vector x = problem.to_internal(user);
  return basis ? basis->reduce(x(interior)) : full->restrict(x);
}

Vector OrbitModel::internal(const Vector& interior_values) const {
  Vector x = Vector::Zero(problem.size());
  x(interior) = interior_values;
  return x;
}

Vector OrbitModel::user(const Vector& u, const Vector* v, double t,
                        const ExactFlow* flow) const {
  const ReducedField& f = field();
  if (!flow) flow = forced.get();
  const ContactShift shift = flow ? flow->forcing().shift(t) : ContactShift{};
  const ContactShift rate = flow ? flow->forcing().shift(t, 1) : ContactShift{};
  const Vector y = v ? f.expand_velocity(u, *v, shift, rate) : f.expand(u, shift);
  if (!basis) return problem.to_user(y);
  const Index r = basis->size();
  Vector x = internal(basis->expand(y.head(r)));
  x(problem.contact_index()) = y.tail(problem.n_contact());
  return problem.to_user(x);
}

OrbitReport periodic_orbit(const ContactProblem& problem, const std::vector<double>& F,
                           const std::vector<double>& u, const std::vector<double>& v, double T,
                           const OrbitOptions& o) {
  const Index N = problem.n_dofs();
  const Vector FF = user_vector(F, N, "F"), uu = user_vector(u, N, "u"),
               vv = user_vector(v, N, "v");
  if (!(T > 0) || !std::isfinite(T))
    throw InputError("T: the period guess must be finite and > 0, got " + std::to_string(T));
  if (o.method != "shooting" && o.method != "harmonic-balance")
    throw InputError("method: \"" + o.method +
                     "\"; expected \"shooting\" or \"harmonic-balance\"");
  if (o.integration != "exact" && o.integration != "aft")
    throw InputError("integration: \"" + o.integration + "\"; expected \"exact\" or \"aft\"");
  if (o.harmonics < 1 || o.harmonics > 320)
    throw InputError("harmonics: " + std::to_string(o.harmonics) + "; expected 1 .. 320");
  if (o.max_iterations < 1) throw InputError("iterations: expected >= 1");
  if (!(o.truncation_tolerance > 0)) throw InputError("truncation: expected > 0");
  const auto kind = condition_of(o.condition);
  const Index interior = problem.size() - problem.n_contact();
  if (o.modes < 0) throw InputError("modes: expected >= 0");
  if (o.modes == 0 && interior > periodic_max_dense_dofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; without a reduced basis the periodic-orbit solvers accept "
                     "at most " + std::to_string(periodic_max_dense_dofs) +
                     " (use modes = m for a reduced basis, or a coarser mesh)");
  if (o.modes > 0 && o.phase != -1)
    throw InputError("phase: not available with modes > 0 (the phase and displacement "
                     "conditions then use the reduced coordinate of largest amplitude)");
  check_amplitude_probe(problem, o.probe);

  auto model = std::make_shared<OrbitModel>(problem);
  model->F = problem.to_internal(FF);
  model->modes = o.modes;
  if (o.modes > 0)
    model->basis = std::make_shared<const ReducedBasis>(problem, model->F, o.modes);
  else
    model->full = std::make_unique<ReducedField>(ReducedField::from(problem, model->F));
  const ReducedField& field = model->field();
  const Vector u0 = model->unknowns(uu), v0 = model->unknowns(vv);
  // The dof of the phase and displacement conditions: phase, else the
  // probe when it is interior (a contact dof's normal component is slaved,
  // fixed by the interior, and cannot carry a condition), else the largest.
  Index probe = -1;
  if (o.phase != -1)
    probe = interior_position(problem, field, o.phase, "phase");
  else if (o.probe >= 0 && o.modes == 0)
    probe = find_interior(problem, field, o.probe);
  if (probe < 0) u0.cwiseAbs().maxCoeff(&probe);

  OrbitReport report;
  PeriodicOrbit orbit;
  std::ostringstream extra;
  ShootingOptions& s = model->conditions;
  s.probe = probe, s.kind = kind, s.amplitude = o.amplitude;
  s.half_period = o.half_period, s.max_iterations = o.max_iterations;
  model->shooting = o.method == "shooting";
  if (model->shooting) {
    orbit = shoot(field, u0, v0, T, s);
    extra << "method shooting (" << (o.half_period ? "half period" : "full period")
          << ", exact flow)\n";
  } else {
    HarmonicBalanceOptions h;
    h.harmonics = o.harmonics, h.cosine_only = o.cosine_only;
    h.integration = o.integration == "exact" ? HarmonicBalanceOptions::Integration::exact
                                             : HarmonicBalanceOptions::Integration::aft;
    h.probe = probe, h.kind = kind, h.amplitude = o.amplitude;
    h.adaptive = o.adaptive, h.truncation_tolerance = o.truncation_tolerance;
    h.max_iterations = o.max_iterations;
    const HarmonicBalanceResult r = harmonic_balance(field, u0, v0, T, h);
    orbit = r.orbit;
    report_series(*model, r, report);
    extra << "method harmonic balance (" << (o.cosine_only ? "cosine only" : "cosine and sine")
          << ", " << o.integration << " integration), H = " << r.harmonics << "\n"
          << "Galerkin residual " << r.residual << ", truncation estimate " << r.truncation << "\n";
  }
  return describe(std::move(model), orbit, std::move(report), extra.str(), o.probe);
}

void report_series(const OrbitModel& model, const HarmonicBalanceResult& r, OrbitReport& report) {
  report.harmonics = r.harmonics;
  report.balance_residual = r.residual;
  report.truncation = r.truncation;
  // Coefficients of the interior unknowns in user coordinates (contact
  // normal components, which are slaved, left at zero).
  const Index N = model.problem.n_dofs(), cols = r.coefficients.cols();
  report.coefficients.assign(static_cast<std::size_t>(N * cols), 0.0);
  for (Index k = 0; k < cols; ++k) {
    const Vector ck = r.coefficients.col(k);
    const Vector user =
        model.problem.to_user(model.internal(model.basis ? model.basis->expand(ck) : ck));
    for (Index i = 0; i < N; ++i) report.coefficients[i * cols + k] = user(i);
  }
}

OrbitReport describe(std::shared_ptr<const OrbitModel> model, const PeriodicOrbit& orbit,
                     OrbitReport report, const std::string& method, long probe) {
  const ReducedField& field = model->field();
  const ContactProblem& problem = model->problem;
  std::ostringstream extra;
  extra << method;
  const OrbitSamples samples = sample_orbit(*model, model->flow(), orbit);
  report.probe = amplitude_probe(problem, samples, probe);
  report.probe_min = samples.lo(report.probe), report.probe_max = samples.hi(report.probe);
  report.amplitude = 0.5 * (report.probe_max - report.probe_min);
  report.energy_max = samples.energy_max;
  std::ostringstream amplitude;
  amplitude.precision(12);
  amplitude << "probe dof " << report.probe << ": amplitude " << report.amplitude << " (min "
            << report.probe_min << ", max " << report.probe_max << ")\n"
            << "largest total energy over the period " << report.energy_max << "\n";
  report.period = orbit.period;
  report.u0 = to_std(model->user(orbit.u0));
  report.v0 = to_std(model->user(orbit.u0, &orbit.v0));
  if (model->basis) {
    // Reduction error: the full model's residual along the orbit (with a
    // forced orbit's damping and excitation).
    std::vector<double> times(64);
    for (int k = 0; k < 64; ++k) times[k] = orbit.period * k / 64;
    const ExactFlow flow = model->flow();
    const FlowResult r = flow.integrate(orbit.u0, orbit.v0, orbit.period, false, times);
    const Index n = field.size();
    for (Index k = 0; k < r.samples.cols(); ++k) {
      const Vector q = r.samples.col(k).head(n), v = r.samples.col(k).tail(n);
      const double t = times[static_cast<std::size_t>(k)];
      const auto region = field.region(field.active_set(q, flow.forcing().shift(t)));
      const Vector a = flow.acceleration(*region, q, v, t);
      report.reduction_residual =
          std::max(report.reduction_residual,
                   model->basis->full_residual(q, v, a, t, flow, model->damping, model->excitation));
    }
    report.cutoff_ratio = model->basis->cutoff_frequency() * orbit.period / (2 * M_PI);
    extra << "reduced basis: " << model->modes << " fixed-interface modes + " << problem.n_contact()
          << " contact shapes (" << n << " unknowns), cutoff frequency " << report.cutoff_ratio
          << " x the orbit's, full-model residual along the orbit " << report.reduction_residual
          << "\n";
  }
  report.energies = {orbit.energy_start(0), orbit.energy_start(1), orbit.energy_start(2),
                     orbit.energy_start(3)};
  report.energy_change = orbit.energy_end(3) - orbit.energy_start(3);
  report.contact_time = orbit.contact_time;
  report.switches = static_cast<long>(orbit.switches.size());
  report.periodicity_residual = orbit.periodicity_residual;
  report.complementarity_residual = orbit.complementarity_residual;
  report.trivial_residual = orbit.trivial_residual;
  for (const auto& mu : orbit.multipliers) {
    report.multipliers_re.push_back(mu.real());
    report.multipliers_im.push_back(mu.imag());
  }
  report.stable = orbit.stable;
  report.iterations = orbit.iterations;
  report.summary = extra.str() + "boundary mass " +
                   (field.massless_boundary() ? "redistributed (massless boundary)"
                                              : "consistent (paper NBM)") +
                   "\n" + summary(orbit) + amplitude.str();
  report.model = std::move(model);
  return report;
}

OrbitReport continue_orbit(const OrbitReport& previous, const OrbitReport& last, double step) {
  if (!previous.model || !last.model) throw InputError("orbit: no periodic orbit");
  const OrbitModel& m = *last.model;
  const OrbitModel& p = *previous.model;
  if (!m.shooting || !p.shooting)
    throw InputError("continuation follows orbits computed by shooting, not by harmonic balance");
  if (m.forced || p.forced)
    throw InputError("continuation follows autonomous orbits (nbmPeriodicOrbit); a forced orbit "
                     "is continued in its excitation frequency or amplitude instead");
  if (&p.problem != &m.problem || p.F.size() != m.F.size() || p.F != m.F ||
      p.modes != m.modes ||
      p.conditions.half_period != m.conditions.half_period)
    throw InputError("the two orbits were computed on different problems, loads, reduced bases "
                     "or with different half-period settings: they are not one family");
  if (!(step > 0) || !std::isfinite(step))
    throw InputError("step: expected a finite step > 0, got " + std::to_string(step));
  const Index N = m.problem.n_dofs();
  auto orbit_of = [&](const OrbitReport& r) {
    PeriodicOrbit o;
    o.u0 = m.unknowns(user_vector(r.u0, N, "u0"));
    o.v0 = m.unknowns(user_vector(r.v0, N, "v0"));
    o.period = r.period;
    return o;
  };
  const PeriodicOrbit before = orbit_of(previous), after = orbit_of(last);
  ContinuationOptions c;
  c.length = std::max(after.u0.cwiseAbs().maxCoeff(), 1e-300);
  c.time = after.period;
  c.velocity = c.length * 2 * M_PI / c.time;
  c.step = step;
  const PeriodicOrbit next =
      shortening_continuation_step(m.field(), before, after, m.conditions, c, c.step);
  std::ostringstream method;
  method << "method pseudo-arclength continuation, step " << c.step << " (shooting, "
         << (m.conditions.half_period ? "half period" : "full period") << ", exact flow)\n";
  return describe(last.model, next, OrbitReport{}, method.str(), last.probe);
}

OrbitReport OrbitSequence::report(std::size_t k) const {
  if (k >= size_)
    throw InputError("point: " + std::to_string(k) + " out of range [0, " +
                     std::to_string(size_) + ") (the points of the last curve)");
  return reporter_(k);
}

void orbit_states(const OrbitReport& orbit, const std::vector<double>& times,
                  std::vector<std::vector<double>>& u, std::vector<std::vector<double>>& v) {
  if (!orbit.model) throw InputError("orbit: no periodic orbit");
  for (std::size_t k = 0; k < times.size(); ++k)
    if (!(times[k] >= 0) || (k > 0 && times[k] < times[k - 1]))
      throw InputError("times: expected sorted non-negative times");
  const OrbitModel& m = *orbit.model;
  const ReducedField& field = m.field();
  const Index N = m.problem.n_dofs();
  const Vector u0 = m.unknowns(user_vector(orbit.u0, N, "u0"));
  const Vector v0 = m.unknowns(user_vector(orbit.v0, N, "v0"));
  const Index n = field.size();
  const double end = times.empty() ? 0 : times.back();
  const FlowResult r = m.flow().integrate(u0, v0, end, false, times);
  u.clear(), v.clear();
  for (Index k = 0; k < r.samples.cols(); ++k) {
    const Vector uk = r.samples.col(k).head(n), vk = r.samples.col(k).tail(n);
    u.push_back(to_std(m.user(uk, nullptr, times[k])));
    v.push_back(to_std(m.user(uk, &vk, times[k])));
  }
}

}  // namespace nbm
