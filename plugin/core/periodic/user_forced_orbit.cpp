#include "user_forced_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "errors.hpp"
#include "forced_orbit.hpp"
#include "orbit_model.hpp"

namespace nbm {
namespace {

constexpr int kAmplitudeSamples = 512;

// The harmonics of one list (Fc or Fs) in internal coordinates, checked:
// size, finite, zero on the normal component of every contact node. A
// rotated contact node rounds (ContactProblem::exact_round_trip): a load
// that is tangential there keeps a round-off normal part, which is dropped.
std::vector<Vector> internal_harmonics(const ContactProblem& problem,
                                       const std::vector<std::vector<double>>& list,
                                       const char* name) {
  std::vector<Vector> out;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string which =
        std::string(name) + " (harmonic " + std::to_string(k + 1) + ")";
    const Vector x = problem.to_internal(user_vector(list[k], problem.n_dofs(), which));
    const double round_off = 1e-14 * x.cwiseAbs().maxCoeff();
    Vector y = x;
    for (Index j = 0; j < problem.n_contact(); ++j) {
      const Index c = problem.contact_index()[j];
      if (std::abs(x(c)) > round_off)
        throw InputError(which + ": non-zero on the normal component of contact node " +
                         std::to_string(j) + " (" + std::to_string(x(c)) +
                         "); the load harmonics must vanish on the contact dofs (a time-varying "
                         "load there moves the nodal boundary relation, which the exact flow "
                         "does not model yet, method.md §9)");
      y(c) = 0;
    }
    out.push_back(std::move(y));
  }
  return out;
}

void check_options(const ForcedOrbitOptions& o) {
  if (!(o.omega > 0) || !std::isfinite(o.omega))
    throw InputError("omega: expected a finite excitation frequency > 0, got " +
                     std::to_string(o.omega));
  if (o.subharmonic < 1)
    throw InputError("subharmonic: expected m >= 1 (period 2 pi m / omega), got " +
                     std::to_string(o.subharmonic));
  if (!(o.rayleigh_mass >= 0) || !std::isfinite(o.rayleigh_mass))
    throw InputError("rayleighM: " + std::to_string(o.rayleigh_mass) +
                     ", expected a finite Rayleigh coefficient >= 0");
  if (!(o.rayleigh_stiffness >= 0) || !std::isfinite(o.rayleigh_stiffness))
    throw InputError("rayleighK: " + std::to_string(o.rayleigh_stiffness) +
                     ", expected a finite Rayleigh coefficient >= 0");
  if (o.transient_periods < 0)
    throw InputError("transient: expected a number of periods >= 0, got " +
                     std::to_string(o.transient_periods));
  if (o.max_iterations < 1) throw InputError("iterations: expected >= 1");
}

}  // namespace

OrbitReport forced_orbit(const ContactProblem& problem, const std::vector<double>& F0,
                         const std::vector<std::vector<double>>& load_cos,
                         const std::vector<std::vector<double>>& load_sin,
                         const std::vector<double>& u, const std::vector<double>& v,
                         const ForcedOrbitOptions& o) {
  const Index N = problem.n_dofs();
  const Vector FF = user_vector(F0, N, "F0"), uu = user_vector(u, N, "u"),
               vv = user_vector(v, N, "v");
  check_options(o);
  HarmonicLoad load;
  load.omega = o.omega;
  load.cos = internal_harmonics(problem, load_cos, "Fc");
  load.sin = internal_harmonics(problem, load_sin, "Fs");
  if (load.harmonics() == 0)
    throw InputError("Fc, Fs: no load harmonic; expected at least one (without excitation the "
                     "damped model's only periodic orbit is its equilibrium)");
  if (o.probe >= 0) {
    if (o.probe >= N)
      throw InputError("probe: dof " + std::to_string(o.probe) + " out of range [0, " +
                       std::to_string(N) + ")");
    if (problem.internal_index(o.probe) < 0)
      throw InputError("probe: dof " + std::to_string(o.probe) + " is fixed");
  }
  const Index interior = problem.size() - problem.n_contact();
  if (interior > orbit_max_interior_dofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; forced orbits accept at most " +
                     std::to_string(orbit_max_interior_dofs) +
                     " (no reduced basis for them yet: use a coarser mesh)");

  auto model = std::make_shared<OrbitModel>(problem);
  model->F = problem.to_internal(FF);
  model->full = std::make_unique<ReducedField>(ReducedField::from(problem, model->F));
  Damping damping;
  damping.a_M = o.rayleigh_mass, damping.b_K = o.rayleigh_stiffness;
  model->forced = std::make_unique<ExactFlow>(*model->full, damping, load);
  model->shooting = true;

  ForcedShootingOptions s;
  s.subharmonic = o.subharmonic;
  s.max_iterations = o.max_iterations;
  s.transient_periods = o.transient_periods;
  const PeriodicOrbit orbit =
      shoot_forced(*model->forced, model->unknowns(uu), model->unknowns(vv), s);

  std::ostringstream method;
  method.precision(12);
  method << "forced orbit: omega " << o.omega << ", subharmonic m = " << o.subharmonic
         << ", Rayleigh damping a_M " << o.rayleigh_mass << ", b_K " << o.rayleigh_stiffness
         << ", " << load.harmonics() << " load harmonic(s)\n"
         << "method shooting (period fixed by the excitation, exact flow)\n";
  OrbitReport report = describe(model, orbit, OrbitReport{}, method.str());
  report.omega = o.omega;
  report.subharmonic = o.subharmonic;

  // The probe's extremes and the largest energy: the exact flow sampled
  // uniformly and at every switch (where a contact closes or opens the
  // motion has its kinks).
  std::vector<double> times;
  for (int k = 0; k < kAmplitudeSamples; ++k) times.push_back(orbit.period * k / kAmplitudeSamples);
  for (const SwitchEvent& e : orbit.switches) times.push_back(e.t);
  std::sort(times.begin(), times.end());
  const ReducedField& field = model->field();
  const FlowResult r = model->forced->integrate(orbit.u0, orbit.v0, orbit.period, false, times);
  const Index n = field.size();
  Vector lo = Vector::Constant(N, INFINITY), hi = Vector::Constant(N, -INFINITY);
  for (Index k = 0; k < r.samples.cols(); ++k) {
    const Vector uk = r.samples.col(k).head(n), vk = r.samples.col(k).tail(n);
    const Vector user = model->user(uk);
    lo = lo.cwiseMin(user), hi = hi.cwiseMax(user);
    report.energy_max = std::max(
        report.energy_max, field.energies(field.expand(uk), field.expand_velocity(uk, vk))(3));
  }
  report.probe = o.probe;
  if (report.probe < 0) {
    double best = -1;
    for (Index i = 0; i < N; ++i)
      if (problem.internal_index(i) >= 0 && hi(i) - lo(i) > best)
        best = hi(i) - lo(i), report.probe = i;
  }
  report.probe_min = lo(report.probe), report.probe_max = hi(report.probe);
  report.amplitude = 0.5 * (report.probe_max - report.probe_min);
  std::ostringstream probe;
  probe.precision(12);
  probe << "probe dof " << report.probe << ": amplitude " << report.amplitude << " (min "
        << report.probe_min << ", max " << report.probe_max << ")\n"
        << "largest total energy over the period " << report.energy_max << "\n";
  report.summary += probe.str();
  return report;
}

}  // namespace nbm
