#include "user_forced_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "errors.hpp"
#include "forced_continuation.hpp"
#include "forced_orbit.hpp"
#include "orbit_model.hpp"

namespace nbm {
namespace {

constexpr int kAmplitudeSamples = 512;

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
}

// The model of a forced orbit: the field of the user's F0, the damping and
// the harmonic load, all checked (named errors).
struct ForcedSetup {
  std::shared_ptr<OrbitModel> model;
  Damping damping;
  HarmonicLoad load;
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
  if (o.probe >= 0) {
    if (o.probe >= N)
      throw InputError("probe: dof " + std::to_string(o.probe) + " out of range [0, " +
                       std::to_string(N) + ")");
    if (problem.internal_index(o.probe) < 0)
      throw InputError("probe: dof " + std::to_string(o.probe) + " is fixed");
  }
  const Index interior = problem.size() - problem.n_contact();
  if (interior > periodic_max_dense_dofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; forced orbits accept at most " +
                     std::to_string(periodic_max_dense_dofs) +
                     " (no reduced basis for them yet: use a coarser mesh)");
  f.model = std::make_shared<OrbitModel>(problem);
  f.model->F = problem.to_internal(FF);
  f.model->full = std::make_unique<ReducedField>(ReducedField::from(problem, f.model->F));
  f.model->shooting = true;
  f.damping.a_M = o.rayleigh_mass, f.damping.b_K = o.rayleigh_stiffness;
  return f;
}

// The orbit sampled over one period along `flow`, uniformly and at every
// switch (where a contact closes or opens the motion has its kinks): the
// extremes of every user dof and the largest total energy.
struct Samples {
  Vector lo, hi;
  double energy_max = 0;
};

Samples sample(const OrbitModel& model, const ExactFlow& flow, const PeriodicOrbit& orbit) {
  std::vector<double> times;
  for (int k = 0; k < kAmplitudeSamples; ++k) times.push_back(orbit.period * k / kAmplitudeSamples);
  for (const SwitchEvent& e : orbit.switches) times.push_back(e.t);
  std::sort(times.begin(), times.end());
  const ReducedField& field = model.field();
  const FlowResult r = flow.integrate(orbit.u0, orbit.v0, orbit.period, false, times);
  const Index n = field.size(), N = model.problem.n_dofs();
  Samples s;
  s.lo = Vector::Constant(N, INFINITY), s.hi = Vector::Constant(N, -INFINITY);
  for (Index k = 0; k < r.samples.cols(); ++k) {
    const Vector uk = r.samples.col(k).head(n), vk = r.samples.col(k).tail(n);
    const ContactShift shift = flow.forcing().shift(times[k]);
    const Vector user = model.user(uk, nullptr, times[k], &flow);
    s.lo = s.lo.cwiseMin(user), s.hi = s.hi.cwiseMax(user);
    s.energy_max = std::max(
        s.energy_max, field.energies(uk, vk, shift, flow.forcing().shift(times[k], true))(3));
  }
  return s;
}

// The probe: the one asked for, or the (not fixed) dof of largest amplitude.
long probe_of(const ContactProblem& problem, const Samples& s, long probe) {
  if (probe >= 0) return probe;
  double best = -1;
  for (Index i = 0; i < problem.n_dofs(); ++i)
    if (problem.internal_index(i) >= 0 && s.hi(i) - s.lo(i) > best)
      best = s.hi(i) - s.lo(i), probe = i;
  return probe;
}

// The report of a forced orbit of `model` (whose `forced` flow it follows).
OrbitReport forced_report(std::shared_ptr<OrbitModel> model, const PeriodicOrbit& orbit,
                          const ForcedOrbitOptions& o, double omega, int harmonics,
                          const std::string& method_line) {
  std::ostringstream method;
  method.precision(12);
  method << "forced orbit: omega " << omega << ", subharmonic m = " << o.subharmonic
         << ", Rayleigh damping a_M " << o.rayleigh_mass << ", b_K " << o.rayleigh_stiffness
         << ", " << harmonics << " harmonic(s) of the excitation\n"
         << method_line << "\n";
  const Samples s = sample(*model, *model->forced, orbit);
  OrbitReport report = describe(model, orbit, OrbitReport{}, method.str());
  report.omega = omega;
  report.subharmonic = o.subharmonic;
  report.energy_max = s.energy_max;
  report.probe = probe_of(model->problem, s, o.probe);
  report.probe_min = s.lo(report.probe), report.probe_max = s.hi(report.probe);
  report.amplitude = 0.5 * (report.probe_max - report.probe_min);
  std::ostringstream probe;
  probe.precision(12);
  probe << "probe dof " << report.probe << ": amplitude " << report.amplitude << " (min "
        << report.probe_min << ", max " << report.probe_max << ")\n"
        << "largest total energy over the period " << report.energy_max << "\n";
  report.summary += probe.str();
  return report;
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
  f.model->forced = std::make_unique<ExactFlow>(f.model->field(), f.damping, f.load);
  ForcedShootingOptions s;
  s.subharmonic = o.subharmonic;
  s.max_iterations = o.max_iterations;
  s.transient_periods = o.transient_periods;
  const PeriodicOrbit orbit =
      shoot_forced(*f.model->forced, f.model->unknowns(uu), f.model->unknowns(vv), s);
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
  c.shooting.subharmonic = o.subharmonic;
  c.shooting.max_iterations = o.max_iterations;
  c.shooting.transient_periods = o.transient_periods;
  const ForcedCurve curve = continue_forced(f.model->field(), f.damping, f.load,
                                            f.model->unknowns(uu), f.model->unknowns(vv), c);

  ForcedResponse out;
  out.stop_reason = curve.stop_reason;
  const OrbitModel& model = *f.model;
  for (std::size_t k = 0; k < curve.points.size(); ++k) {
    const ForcedPoint& p = curve.points[k];
    const ExactFlow flow(model.field(), f.damping, forced_load(f.load, c.parameter, p.parameter));
    const Samples s = sample(model, flow, p.orbit);
    if (k == 0) out.probe = probe_of(problem, s, o.probe);
    ForcedResponsePoint row;
    row.omega = p.omega, row.scale = p.scale, row.arclength = p.arclength;
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
    ev.parameter = e.parameter, ev.arclength = e.arclength;
    ev.point = static_cast<long>(e.point) + 1;
    ev.multiplier_re = e.multiplier.real(), ev.multiplier_im = e.multiplier.imag();
    ev.description = e.description;
    if (ev.point < static_cast<long>(out.points.size())) {
      std::string& tag = out.points[ev.point].events;
      tag += (tag.empty() ? "" : "+") + ev.kind;
    }
    out.events.push_back(std::move(ev));
  }
  // The last point as the orbit report (its flow: the last parameter).
  const ForcedPoint& last = curve.points.back();
  f.model->forced = std::make_unique<ExactFlow>(
      f.model->field(), f.damping, forced_load(f.load, c.parameter, last.parameter));
  ForcedOrbitOptions lo = o;
  lo.probe = out.probe;
  std::ostringstream method;
  method.precision(12);
  method << "method pseudo-arclength continuation in " << r.parameter << " (last of "
         << curve.points.size() << " points, amplitude factor " << last.scale
         << "): " << curve.stop_reason;
  out.last = forced_report(f.model, last.orbit, lo, last.omega, f.load.harmonics(), method.str());
  return out;
}

void write_forced_response(const ForcedResponse& r, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError("file: cannot write " + path);
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
  if (!f) throw InputError("file: cannot write " + path);
}

}  // namespace nbm
