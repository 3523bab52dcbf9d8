#include "user_orbit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact_problem.hpp"
#include "errors.hpp"
#include "harmonic_balance.hpp"
#include "shooting.hpp"

namespace nbm {
namespace {

// Dense reduced matrices: beyond this size a reduced basis would be needed.
constexpr Index kMaxInteriorDofs = 3000;

Vector user_vector(const std::vector<double>& x, Index n, const char* name) {
  if (static_cast<Index>(x.size()) != n)
    throw InputError(std::string(name) + ": size " + std::to_string(x.size()) + ", expected " +
                     std::to_string(n) + " (the number of dofs)");
  Vector y = Eigen::Map<const Vector>(x.data(), n);
  if (!y.allFinite()) throw InputError(std::string(name) + ": non-finite entries");
  return y;
}

std::vector<double> to_std(const Vector& x) { return {x.data(), x.data() + x.size()}; }

ShootingOptions::Amplitude condition_of(const std::string& c) {
  if (c == "displacement") return ShootingOptions::Amplitude::displacement;
  if (c == "energy") return ShootingOptions::Amplitude::energy;
  if (c == "period") return ShootingOptions::Amplitude::period;
  throw InputError("condition: \"" + c + "\"; expected \"displacement\", \"energy\" or \"period\"");
}

// Position in u_O of a user dof.
Index interior_position(const ContactProblem& p, const ReducedField& field, long dof) {
  if (dof < 0 || dof >= p.n_dofs())
    throw InputError("probe: dof " + std::to_string(dof) + " out of range [0, " +
                     std::to_string(p.n_dofs()) + ")");
  const Index internal = p.internal_index(dof);
  const auto& in = field.interior();
  const auto it = std::lower_bound(in.begin(), in.end(), internal);
  if (internal < 0 || it == in.end() || *it != internal)
    throw InputError("probe: dof " + std::to_string(dof) +
                     " is fixed or the normal component of a contact node; choose an interior "
                     "dof");
  return it - in.begin();
}

}  // namespace

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
  if (interior > kMaxInteriorDofs)
    throw InputError("the model has " + std::to_string(interior) +
                     " interior dofs; the periodic-orbit solvers use dense matrices and accept "
                     "at most " + std::to_string(kMaxInteriorDofs) + " (use a coarser mesh)");

  const ReducedField field = ReducedField::from(problem, problem.to_internal(FF));
  const Vector u0 = field.restrict(problem.to_internal(uu));
  const Vector v0 = field.restrict(problem.to_internal(vv));
  Index probe = 0;
  if (o.probe >= 0)
    probe = interior_position(problem, field, o.probe);
  else
    u0.cwiseAbs().maxCoeff(&probe);

  OrbitReport report;
  PeriodicOrbit orbit;
  std::ostringstream extra;
  if (o.method == "shooting") {
    ShootingOptions s;
    s.probe = probe, s.kind = kind, s.amplitude = o.amplitude;
    s.half_period = o.half_period, s.max_iterations = o.max_iterations;
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
    report.harmonics = r.harmonics;
    report.balance_residual = r.residual;
    report.truncation = r.truncation;
    const Index cols = r.coefficients.cols();
    report.coefficients.assign(static_cast<std::size_t>(N * cols), 0.0);
    for (Index k = 0; k < cols; ++k) {
      Vector x = Vector::Zero(problem.size());
      x(field.interior()) = r.coefficients.col(k);
      const Vector user = problem.to_user(x);
      for (Index i = 0; i < N; ++i) report.coefficients[i * cols + k] = user(i);
    }
    extra << "method harmonic balance (" << (o.cosine_only ? "cosine only" : "cosine and sine")
          << ", " << o.integration << " integration), H = " << r.harmonics << "\n"
          << "Galerkin residual " << r.residual << ", truncation estimate " << r.truncation << "\n";
  }
  report.period = orbit.period;
  report.u0 = to_std(problem.to_user(field.expand(orbit.u0)));
  report.v0 = to_std(problem.to_user(field.expand_velocity(orbit.u0, orbit.v0)));
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
                   "\n" + summary(orbit);
  return report;
}

void orbit_states(const ContactProblem& problem, const std::vector<double>& F,
                  const OrbitReport& orbit, const std::vector<double>& times,
                  std::vector<std::vector<double>>& u, std::vector<std::vector<double>>& v) {
  const Index N = problem.n_dofs();
  const ReducedField field = ReducedField::from(problem, problem.to_internal(user_vector(F, N, "F")));
  for (std::size_t k = 0; k < times.size(); ++k)
    if (!(times[k] >= 0) || (k > 0 && times[k] < times[k - 1]))
      throw InputError("times: expected sorted non-negative times");
  const Vector u0 = field.restrict(problem.to_internal(user_vector(orbit.u0, N, "u0")));
  const Vector v0 = field.restrict(problem.to_internal(user_vector(orbit.v0, N, "v0")));
  const Index n = field.size();
  const double end = times.empty() ? 0 : times.back();
  const FlowResult r = ExactFlow(field).integrate(u0, v0, end, false, times);
  u.clear(), v.clear();
  for (Index k = 0; k < r.samples.cols(); ++k) {
    const Vector uk = r.samples.col(k).head(n), vk = r.samples.col(k).tail(n);
    u.push_back(to_std(problem.to_user(field.expand(uk))));
    v.push_back(to_std(problem.to_user(field.expand_velocity(uk, vk))));
  }
}

}  // namespace nbm
