#include "periodic/user_backbone.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/errors.hpp"
#include "contact/contact_problem.hpp"
#include "periodic/backbone.hpp"
#include "periodic/orbit_model.hpp"

namespace nbm {

BackboneReport backbone(const ContactProblem& problem, const std::vector<double>& F, long mode,
                        const BackboneOptions& options) {
  const Vector FF = user_vector(F, problem.n_dofs(), "F");
  const Index interior = problem.size() - problem.n_contact();
  if (options.modes < 0)
    throw InputError("modes: " + std::to_string(options.modes) +
                     "; expected >= 0 (0: no reduced basis)");
  if (options.modes == 0 && interior > periodic_max_dense_dofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; without a reduced basis backbones accept at most " +
                     std::to_string(periodic_max_dense_dofs) +
                     " (use modes = m for a reduced basis, or a coarser mesh)");
  check_amplitude_probe(problem, options.probe);
  auto model = std::make_shared<OrbitModel>(problem);
  model->F = problem.to_internal(FF);
  model->modes = options.modes;
  if (options.modes > 0)
    model->basis = std::make_shared<const ReducedBasis>(problem, model->F, options.modes);
  else
    model->full = std::make_unique<ReducedField>(ReducedField::from(problem, model->F));
  const ReducedField& field = model->field();
  const Backbone b = backbone(field, mode, options);
  const ExactFlow flow(field);
  // The backbone's shooting conditions (backbone.cpp), which continue_orbit
  // keeps along the family.
  model->shooting = true;
  model->conditions.probe = b.grazing.probe;
  model->conditions.half_period = options.half_period;
  model->conditions.max_iterations = options.max_iterations;

  BackboneReport r;
  r.linear_omega = b.grazing.omega;
  r.grazing_amplitude = b.grazing.amplitude;
  r.grazing_contact = b.grazing.contact;
  r.stop_reason = b.stop_reason;
  for (const BackbonePoint& p : b.points) {
    const OrbitSamples samples = sample_orbit(*model, flow, p.orbit);
    if (r.points.empty()) r.probe = amplitude_probe(problem, samples, options.probe);
    BackbonePointReport q;
    q.probe_min = samples.lo(r.probe), q.probe_max = samples.hi(r.probe);
    q.probe_amplitude = 0.5 * (q.probe_max - q.probe_min);
    q.period = p.orbit.period;
    q.omega = 2 * M_PI / q.period;
    q.energy = p.energy;
    // On a reduced basis the unknowns are modal coordinates: the amplitude
    // is read on the interior dofs they expand to.
    q.amplitude = model->basis ? (model->basis->expand(p.orbit.u0 - b.grazing.static_state))
                                     .cwiseAbs()
                                     .maxCoeff()
                               : p.amplitude;
    q.contact_time = p.orbit.contact_time;
    q.switches = static_cast<long>(p.orbit.switches.size());
    for (const auto& mu : p.orbit.multipliers) {
      q.multipliers_re.push_back(mu.real());
      q.multipliers_im.push_back(mu.imag());
      q.max_multiplier = std::max(q.max_multiplier, std::abs(mu));
    }
    q.stable = p.orbit.stable;
    q.periodicity_residual = p.orbit.periodicity_residual;
    q.events = p.events;
    r.points.push_back(std::move(q));
  }
  std::ostringstream s;
  s.precision(12);
  const BackbonePointReport &first = r.points.front(), &last = r.points.back();
  s << "backbone of mode " << mode << " from grazing (" << (options.half_period ? "half" : "full")
    << "-period shooting, exact flow, pseudo-arclength step " << options.step;
  if (options.branch == BackboneOptions::Branch::frequency)
    s << "; then the frequency branch: steps " << options.frequency_step << " of omega, energy "
      << "jumps above " << options.energy_jump << " skipped, at most " << options.max_skips
      << " in a row";
  s << ")\n";
  if (options.modes > 0)
    s << "reduced basis: " << options.modes << " fixed-interface modes + " << problem.n_contact()
      << " contact shapes (" << field.size() << " unknowns); each orbit's report gives the full "
      << "model's residual along it\n";
  s << "linear: omega " << r.linear_omega << ", period " << first.period << "\n"
    << "grazing: contact " << r.grazing_contact << " (position in the contact list), modal "
    << "amplitude " << r.grazing_amplitude << ", amplitude " << first.amplitude << ", energy "
    << first.energy << "\n"
    << "probe dof " << r.probe << ": amplitude " << first.probe_amplitude << " at grazing, "
    << last.probe_amplitude << " at the last orbit\n"
    << r.points.size() << " orbits; last: omega " << last.omega << " (" << last.omega / first.omega
    << " x linear), energy " << last.energy << ", amplitude " << last.amplitude
    << ", contact time " << last.contact_time << " (" << last.contact_time / last.period
    << " of the period), " << last.switches << " switches\n"
    << "stopped: " << r.stop_reason << "\n";
  r.summary = s.str();
  std::ostringstream method;
  method << "method pseudo-arclength continuation from grazing along the backbone of mode "
         << mode << " (shooting, " << (options.half_period ? "half period" : "full period")
         << ", exact flow)\n";
  // The orbits kept for their reports, without their monodromy matrices
  // (2n x 2n each, which the reports do not read).
  std::vector<PeriodicOrbit> orbits;
  for (const BackbonePoint& p : b.points) {
    orbits.push_back(p.orbit);
    orbits.back().monodromy.resize(0, 0);
  }
  const std::size_t n = orbits.size();  // before orbits moves into the reporter
  r.orbits = std::make_shared<const OrbitSequence>(
      n, [model = std::shared_ptr<const OrbitModel>(std::move(model)),
                      orbits = std::move(orbits), method = method.str(),
                      probe = r.probe](std::size_t k) {
        return describe(model, orbits[k], OrbitReport{}, method, probe);
      });
  return r;
}

}  // namespace nbm
