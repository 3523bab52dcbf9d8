#include "periodic/user_forced_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "base/errors.hpp"
#include "linalg/sparse_input.hpp"
#include "periodic/forced_continuation.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/orbit_model.hpp"
#include "periodic/shooting.hpp"

namespace nbm {
namespace {

std::string number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// The harmonics of one load list (Fc or Fs) in internal coordinates,
// checked (size, finite). On the contact dofs they move the relation's
// offset e(t) (method.md §8), which the exact flow follows.
std::vector<Vector> internal_harmonics(const ContactProblem& problem,
                                       const std::vector<std::vector<double>>& list,
                                       const char* name) {
  std::vector<Vector> out;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string which = std::string(name) + " (harmonic " + std::to_string(k + 1) + ")";
    out.push_back(problem.to_internal(user_vector(list[k], problem.n_dofs(), which)));
  }
  return out;
}

// The harmonics of one gap list (gapCos or gapSin): one value per contact
// node, in the order of the problem's gaps, checked (size, finite).
std::vector<Vector> gap_harmonics(const ContactProblem& problem,
                                  const std::vector<std::vector<double>>& list, const char* name) {
  std::vector<Vector> out;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string which = std::string(name) + " (harmonic " + std::to_string(k + 1) + ")";
    const Index n = problem.n_contact();
    if (static_cast<Index>(list[k].size()) != n)
      throw InputError(which + ": size " + std::to_string(list[k].size()) + ", expected " +
                       std::to_string(n) + " (one value per contact node)");
    out.push_back(Eigen::Map<const Vector>(list[k].data(), n));
    if (!out.back().allFinite()) throw InputError(which + ": non-finite entries");
  }
  return out;
}

// The assembled damping matrix in internal coordinates, checked: size, finite,
// zero on the normal component of every contact node (the exact flow's
// reactions do not depend on the velocities, method.md §9); tangential
// components of a contact node are interior dofs and may be damped.
SparseMatrix internal_damping(const ContactProblem& problem, const CooMatrix& C) {
  const SparseMatrix user = to_sparse(C, "damping");
  const Index N = problem.n_dofs();
  if (user.rows() != N || user.cols() != N)
    throw InputError("damping: size " + std::to_string(user.rows()) + "x" +
                     std::to_string(user.cols()) + ", expected " + std::to_string(N) + "x" +
                     std::to_string(N) + " (the number of dofs)");
  Matrix x = problem.to_internal(user);
  if (!x.allFinite()) throw InputError("damping: non-finite entries");
  const double round_off = 1e-14 * x.cwiseAbs().maxCoeff();
  for (Index j = 0; j < problem.n_contact(); ++j) {
    const Index c = problem.contact_index()[j];
    const double size = std::max(x.row(c).cwiseAbs().maxCoeff(), x.col(c).cwiseAbs().maxCoeff());
    if (size > round_off)
      throw InputError("damping: non-zero on the normal component of contact node " +
                       std::to_string(j) + " (" + number(size) +
                       "); forced orbits need a damping matrix that vanishes on the contact "
                       "dofs (method.md §9)");
    x.row(c).setZero(), x.col(c).setZero();  // round-off of a rotated node
  }
  return x.sparseView();
}

void check_options(const ForcedOrbitOptions& o) {
  if (!(o.omega > 0) || !std::isfinite(o.omega))
    throw InputError("omega: expected a finite excitation frequency > 0, got " +
                     number(o.omega));
  if (o.subharmonic < 1)
    throw InputError("subharmonic: expected m >= 1 (period 2 pi m / omega), got " +
                     std::to_string(o.subharmonic));
  if (!(o.rayleigh_mass >= 0) || !std::isfinite(o.rayleigh_mass))
    throw InputError("rayleighM: " + number(o.rayleigh_mass) +
                     ", expected a finite Rayleigh coefficient >= 0");
  if (!(o.rayleigh_stiffness >= 0) || !std::isfinite(o.rayleigh_stiffness))
    throw InputError("rayleighK: " + number(o.rayleigh_stiffness) +
                     ", expected a finite Rayleigh coefficient >= 0");
  if (o.transient_periods < 0)
    throw InputError("transient: expected a number of periods >= 0, got " +
                     std::to_string(o.transient_periods));
  if (o.max_iterations < 1) throw InputError("iterations: expected >= 1");
  if (o.modes < 0)
    throw InputError("modes: " + std::to_string(o.modes) + "; expected >= 0 (0: no reduced basis)");
  if (o.method != "shooting" && o.method != "harmonic-balance")
    throw InputError("method: \"" + o.method + "\"; expected \"shooting\" or \"harmonic-balance\"");
  if (o.method == "harmonic-balance" && (o.harmonics < o.subharmonic || o.harmonics > 320))
    throw InputError("harmonics: " + std::to_string(o.harmonics) + "; expected m .. 320 (m = " +
                     std::to_string(o.subharmonic) +
                     ", the subharmonic: the load's first harmonic is the series' m-th)");
}

// The model of a forced orbit: the field of the user's F0 (on a reduced
// basis with modes > 0), the damping and the harmonic load, all checked
// (named errors): on the full model's internal coordinates, and on the
// field's (the flows' and the continuation's).
struct ForcedSetup {
  std::shared_ptr<OrbitModel> model;
  Damping damping, field_damping;
  HarmonicLoad load, field_load;
};

ForcedSetup setup(const ContactProblem& problem, const std::vector<double>& F0,
                  const std::vector<std::vector<double>>& load_cos,
                  const std::vector<std::vector<double>>& load_sin, const ForcedOrbitOptions& o) {
  const Index N = problem.n_dofs();
  const Vector FF = user_vector(F0, N, "F0");
  check_options(o);
  ForcedSetup f;
  f.load.omega = o.omega;
  f.load.cos = internal_harmonics(problem, load_cos, "Fc");
  f.load.sin = internal_harmonics(problem, load_sin, "Fs");
  f.load.gap_cos = gap_harmonics(problem, o.gap_cos, "gapCos");
  f.load.gap_sin = gap_harmonics(problem, o.gap_sin, "gapSin");
  if (f.load.harmonics() == 0)
    throw InputError("Fc, Fs, gapCos, gapSin: no harmonic; expected at least one (without "
                     "excitation the damped model's only periodic orbit is its equilibrium)");
  check_amplitude_probe(problem, o.probe);
  const Index interior = problem.size() - problem.n_contact();
  if (o.modes == 0 && interior > periodic_max_dense_dofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; without a reduced basis forced orbits accept at most " +
                     std::to_string(periodic_max_dense_dofs) +
                     " (use modes = m for a reduced basis, or a coarser mesh)");
  f.model = std::make_shared<OrbitModel>(problem);
  f.model->F = problem.to_internal(FF);
  f.model->modes = o.modes;
  if (o.modes > 0)
    f.model->basis = std::make_shared<const ReducedBasis>(problem, f.model->F, o.modes);
  else
    f.model->full = std::make_unique<ReducedField>(ReducedField::from(problem, f.model->F));
  f.model->shooting = true;
  f.damping.a_M = o.rayleigh_mass, f.damping.b_K = o.rayleigh_stiffness;
  if (!o.damping.value.empty() || o.damping.rows != 0)
    f.damping.C_user = internal_damping(problem, o.damping);
  const auto& basis = f.model->basis;
  f.field_damping = basis ? basis->reduce(f.damping) : f.damping;
  f.field_load = basis ? basis->reduce(f.load) : f.load;
  return f;
}

// The report of a forced orbit of `model` (whose `forced` flow it follows),
// on `report`'s method-specific fields.
OrbitReport forced_report(std::shared_ptr<OrbitModel> model, const PeriodicOrbit& orbit,
                          const ForcedOrbitOptions& o, double omega, int harmonics,
                          const std::string& method_line, OrbitReport report = {}) {
  std::ostringstream method;
  method.precision(12);
  method << "forced orbit: omega " << omega << ", subharmonic m = " << o.subharmonic
         << ", Rayleigh damping a_M " << o.rayleigh_mass << ", b_K " << o.rayleigh_stiffness
         << (o.damping.value.empty() ? "" : " and an assembled damping matrix") << ", "
         << harmonics << " harmonic(s) of the excitation\n"
         << method_line << "\n";
  report = describe(model, orbit, std::move(report), method.str(), o.probe);
  report.omega = omega;
  report.subharmonic = o.subharmonic;
  return report;
}

// A copy of the model of `f` following the flow of its load at parameter p
// (scaled by `factor` for the amplitude): every report keeps the flow it
// was sampled on (nbmOrbitState integrates it later).
std::shared_ptr<OrbitModel> model_at(const ForcedSetup& f, const ForcedContinuationOptions& c,
                                     double p) {
  auto m = std::make_shared<OrbitModel>(f.model->problem);
  m->F = f.model->F;
  m->modes = f.model->modes;
  m->basis = f.model->basis;
  if (!m->basis) m->full = std::make_unique<ReducedField>(f.model->field());
  m->shooting = true;
  m->force(f.damping, forced_load(f.load, c.parameter, p));
  return m;
}

// The user-level response of a curve of continue_forced on the load of `f`
// (whose amplitude factor 1 is `factor` times the user's): a row per point
// (amplitude of `probe`, or -1: the dof of largest amplitude at the first
// point), the events, the points as orbit reports.
ForcedResponse describe_curve(const ForcedSetup& f, const ForcedCurve& curve,
                              const ForcedContinuationOptions& c, const ForcedOrbitOptions& o,
                              long probe, const std::string& parameter, double factor) {
  ForcedResponse out;
  out.probe = probe;
  out.stop_reason = curve.stop_reason;
  if (c.parameter == ForcedParameter::amplitude && factor != 1.0)
    out.stop_reason += " (amplitude scales relative to the factor " + number(factor) +
                       " where the branch starts)";
  const OrbitModel& model = *f.model;
  const ExactFlow base(model.field(), f.field_damping, f.field_load);
  for (std::size_t k = 0; k < curve.points.size(); ++k) {
    const ForcedPoint& p = curve.points[k];
    const ExactFlow flow = base.with_load(forced_load(f.field_load, c.parameter, p.parameter));
    const OrbitSamples s = sample_orbit(model, flow, p.orbit);
    if (k == 0) out.probe = amplitude_probe(model.problem, s, out.probe);
    ForcedResponsePoint row;
    row.omega = p.omega, row.scale = factor * p.scale, row.arclength = p.arclength;
    row.probe_min = s.lo(out.probe), row.probe_max = s.hi(out.probe);
    row.amplitude = 0.5 * (row.probe_max - row.probe_min);
    row.energy = p.orbit.energy_start(3), row.energy_max = s.energy_max;
    row.contact_time = p.orbit.contact_time, row.min_gap = p.min_gap;
    row.periodicity_residual = p.orbit.periodicity_residual;
    row.switches = p.switches;
    for (const auto& mu : p.orbit.multipliers) row.moduli.push_back(std::abs(mu));
    row.stable = p.orbit.stable;
    out.points.push_back(std::move(row));
  }
  for (const ForcedEvent& e : curve.events) {
    ForcedResponseEvent ev;
    ev.kind = to_string(e.kind);
    ev.parameter = c.parameter == ForcedParameter::amplitude ? factor * e.parameter : e.parameter;
    ev.arclength = e.arclength;
    ev.point = static_cast<long>(e.point) + 1;
    ev.multiplier_re = e.multiplier.real(), ev.multiplier_im = e.multiplier.imag();
    ev.description = e.description;
    if (ev.point < static_cast<long>(out.points.size())) {
      std::string& tag = out.points[ev.point].events;
      tag += (tag.empty() ? "" : "+") + ev.kind;
    }
    out.events.push_back(std::move(ev));
  }
  // The points as orbits, by index: each report follows the flow of its
  // point's parameter (model_at).
  ForcedOrbitOptions lo = o;
  lo.probe = out.probe;
  lo.subharmonic = c.subharmonic;
  // The points kept for their reports, without their monodromy matrices
  // (2n x 2n each, which the reports do not read).
  std::vector<ForcedPoint> points = curve.points;
  for (ForcedPoint& p : points) p.orbit.monodromy.resize(0, 0);
  const std::size_t n = points.size();
  const double shown = factor;
  out.orbits = std::make_shared<const OrbitSequence>(
      n, [f, c, lo, parameter, shown, points = std::move(points),
          stop = curve.stop_reason](std::size_t k) {
        const ForcedPoint& p = points[k];
        std::ostringstream method;
        method.precision(12);
        method << "method pseudo-arclength continuation in " << parameter << " (point " << k
               << " of " << points.size() << ", amplitude factor " << shown * p.scale
               << "): " << stop;
        return forced_report(model_at(f, c, p.parameter), p.orbit, lo, p.omega,
                             f.load.harmonics(), method.str());
      });
  return out;
}

// Branch switching at the first period doubling of `curve` (method.md §9):
// the period-2m orbit, then its branch over the same range, heading to the
// side of the event where the orbit was found.
std::shared_ptr<const ForcedDoubling> switch_branch(const ForcedSetup& f,
                                                    const ForcedCurve& curve,
                                                    const ForcedContinuationOptions& c,
                                                    const ForcedOrbitOptions& o, long probe,
                                                    const ForcedResponseOptions& r) {
  const auto event = std::find_if(curve.events.begin(), curve.events.end(), [](const auto& e) {
    return e.kind == ForcedEventKind::period_doubling;
  });
  if (event == curve.events.end())
    throw InputError("doubling: no period doubling on the curve (" +
                     std::to_string(curve.points.size()) + " points, " +
                     std::to_string(curve.events.size()) + " events; " + curve.stop_reason +
                     "): nothing to switch at");
  const PeriodDoubledOrbit doubled =
      switch_at_period_doubling(f.model->field(), f.field_damping, f.field_load, c, curve, *event,
                                r.doubling_amplitude);
  if (doubled.parameter < c.parameter_min || doubled.parameter > c.parameter_max)
    throw NumericalError("doubling: the period-" + std::to_string(2 * c.subharmonic) +
                         " orbit was found at " + r.parameter + " = " +
                         number(doubled.parameter) + ", outside the range [" +
                         number(c.parameter_min) + ", " + number(c.parameter_max) +
                         "] (period doubling at " + number(event->parameter) +
                         "): widen the range or lower doublingAmplitude");
  auto d = std::make_shared<ForcedDoubling>();
  d->event_parameter = event->parameter, d->parameter = doubled.parameter;
  d->separation = doubled.separation;
  // The branch: the load at the orbit's parameter is its start (for the
  // amplitude, factor 1 of the continuation is the user's factor p).
  ForcedSetup g;
  g.model = f.model;
  g.damping = f.damping, g.field_damping = f.field_damping;
  g.load = forced_load(f.load, c.parameter, doubled.parameter);
  g.field_load = forced_load(f.field_load, c.parameter, doubled.parameter);
  ForcedContinuationOptions c2 = c;
  c2.subharmonic = 2 * c.subharmonic;
  c2.shooting.transient_periods = 0;
  c2.length = 0, c2.parameter_scale = 0;
  c2.direction = doubled.parameter >= event->parameter ? 1 : -1;
  const bool amplitude = c.parameter == ForcedParameter::amplitude;
  const double factor = amplitude ? doubled.parameter : 1.0;
  if (amplitude) c2.parameter_min /= factor, c2.parameter_max /= factor;
  const ForcedCurve branch = continue_forced(g.model->field(), g.field_damping, g.field_load,
                                             doubled.orbit.u0, doubled.orbit.v0, c2);
  ForcedOrbitOptions o2 = o;
  o2.omega = g.load.omega;
  d->branch = describe_curve(g, branch, c2, o2, probe, r.parameter, factor);
  o2.probe = probe;
  o2.subharmonic = c2.subharmonic;
  std::ostringstream method;
  method.precision(12);
  method << "method branch switching at the period doubling at " << r.parameter << " = "
         << event->parameter << " (separation over one period before doubling "
         << doubled.separation << ")";
  d->orbit = forced_report(model_at(g, c2, amplitude ? 1.0 : doubled.parameter),
                           doubled.orbit, o2, g.load.omega, f.load.harmonics(), method.str());
  return d;
}

}  // namespace

OrbitReport forced_orbit(const ContactProblem& problem, const std::vector<double>& F0,
                         const std::vector<std::vector<double>>& load_cos,
                         const std::vector<std::vector<double>>& load_sin,
                         const std::vector<double>& u, const std::vector<double>& v,
                         const ForcedOrbitOptions& o) {
  ForcedSetup f = setup(problem, F0, load_cos, load_sin, o);
  const Index N = problem.n_dofs();
  const Vector uu = user_vector(u, N, "u"), vv = user_vector(v, N, "v");
  f.model->force(f.damping, f.load);
  const Vector u0 = f.model->unknowns(uu), v0 = f.model->unknowns(vv);
  const PeriodicProblem forced(*f.model->forced, o.subharmonic);
  if (o.method == "harmonic-balance") {
    HarmonicBalanceOptions h;
    h.harmonics = o.harmonics;
    h.max_iterations = o.max_iterations;
    h.transient_periods = o.transient_periods;
    const HarmonicBalanceResult r = harmonic_balance(forced, u0, v0, forced.period(), h);
    f.model->shooting = false;
    OrbitReport report;
    report_series(*f.model, r, report);
    std::ostringstream line;
    line.precision(3);
    line << "method harmonic balance (period fixed by the excitation, exact integration), H = "
         << r.harmonics << " harmonics of omega / m\nGalerkin residual " << r.residual
         << ", truncation estimate " << r.truncation
         << " (the state's periodicity residual on the exact flow below measures it too)";
    return forced_report(f.model, r.orbit, o, o.omega, f.load.harmonics(), line.str(),
                         std::move(report));
  }
  ShootingOptions s;
  s.max_iterations = o.max_iterations;
  s.transient_periods = o.transient_periods;
  const PeriodicOrbit orbit = shoot(forced, u0, v0, forced.period(), s);
  return forced_report(f.model, orbit, o, o.omega, f.load.harmonics(),
                       "method shooting (period fixed by the excitation, exact flow)");
}

ForcedResponse forced_response(const ContactProblem& problem, const std::vector<double>& F0,
                               const std::vector<std::vector<double>>& load_cos,
                               const std::vector<std::vector<double>>& load_sin,
                               const std::vector<double>& u, const std::vector<double>& v,
                               const ForcedOrbitOptions& o, const ForcedResponseOptions& r) {
  ForcedSetup f = setup(problem, F0, load_cos, load_sin, o);
  const Index N = problem.n_dofs();
  const Vector uu = user_vector(u, N, "u"), vv = user_vector(v, N, "v");
  ForcedContinuationOptions c;
  if (o.method != "shooting")
    throw InputError("method: \"" + o.method + "\"; the continuation of forced orbits "
                     "corrects by shooting (expected \"shooting\")");
  if (r.parameter != "omega" && r.parameter != "amplitude")
    throw InputError("parameter: \"" + r.parameter + "\"; expected \"omega\" or \"amplitude\"");
  const bool frequency = r.parameter == "omega";
  c.parameter = frequency ? ForcedParameter::frequency : ForcedParameter::amplitude;
  const double start = frequency ? o.omega : 1.0;
  const char* what = frequency ? "omega" : "the amplitude factor";
  if (!std::isfinite(r.to) || r.to == start || (frequency && !(r.to > 0)))
    throw InputError("to: expected a finite end of the " + r.parameter + " range, other than the "
                     "start (" + std::string(what) + " = " + number(start) + ")" +
                     (frequency ? " and > 0" : "") + ", got " + number(r.to));
  const double from = std::isnan(r.from) ? start : r.from;
  if (!std::isfinite(from) || (frequency && !(from > 0)) ||
      (from - start) * (r.to - start) > 0)
    throw InputError("from: expected the other end of the " + r.parameter + " range, the start (" +
                     std::string(what) + " = " + number(start) +
                     ") between from and to, got " + number(from));
  if (!(r.step > 0) || !(r.max_step >= r.step) || !std::isfinite(r.max_step))
    throw InputError("step, maxStep: expected 0 < step <= maxStep < inf, got " +
                     number(r.step) + ", " + number(r.max_step));
  if (r.max_points < 1)
    throw InputError("points: expected >= 1, got " + std::to_string(r.max_points));
  c.parameter_min = std::min(from, r.to), c.parameter_max = std::max(from, r.to);
  c.direction = r.to > start ? 1 : -1;
  c.step = r.step, c.max_step = r.max_step, c.min_step = std::min(c.min_step, r.step);
  c.max_points = r.max_points;
  c.locate_events = r.locate_events;
  c.subharmonic = o.subharmonic;
  c.shooting.max_iterations = o.max_iterations;
  c.shooting.transient_periods = o.transient_periods;
  if (r.doubling && !(r.doubling_amplitude > 0 && std::isfinite(r.doubling_amplitude)))
    throw InputError("doublingAmplitude: expected a finite amplitude > 0 (scaled unknowns), got " +
                     number(r.doubling_amplitude));
  const ForcedCurve curve = continue_forced(f.model->field(), f.field_damping, f.field_load,
                                            f.model->unknowns(uu), f.model->unknowns(vv), c);
  ForcedResponse out = describe_curve(f, curve, c, o, o.probe, r.parameter, 1.0);
  if (r.doubling) out.doubling = switch_branch(f, curve, c, o, out.probe, r);
  return out;
}

void write_forced_response(const ForcedResponse& r, const std::string& path,
                           const std::string& argument) {
  std::ofstream f(path);
  if (!f) throw InputError(argument + ": cannot write " + path);
  f.precision(12);
  f << "point,omega,scale,arclength,amplitude,probe_min,probe_max,energy,energy_max,"
       "contact_time,switches,min_gap,max_multiplier,mu2,mu3,mu4,stable,periodicity,event\n";
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const ForcedResponsePoint& p = r.points[k];
    f << k << "," << p.omega << "," << p.scale << "," << p.arclength << "," << p.amplitude << ","
      << p.probe_min << "," << p.probe_max << "," << p.energy << "," << p.energy_max << ","
      << p.contact_time << "," << p.switches << "," << p.min_gap;
    for (std::size_t j = 0; j < 4; ++j) {
      f << ",";
      if (j < p.moduli.size()) f << p.moduli[j];
    }
    f << "," << (p.stable ? 1 : 0) << "," << p.periodicity_residual << ","
      << (p.events.empty() ? "none" : p.events) << "\n";
  }
  if (!f) throw InputError(argument + ": cannot write " + path);
}

}  // namespace nbm
