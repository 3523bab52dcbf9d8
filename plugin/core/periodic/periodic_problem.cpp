#include "periodic/periodic_problem.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "base/errors.hpp"

namespace nbm {

double forced_period(const ExactFlow& flow, int subharmonic) {
  if (flow.forcing().Omega.empty())
    throw InputError("forced orbit: the flow has no harmonic load (no excitation frequency)");
  if (subharmonic < 1)
    throw InputError("forced orbit: the subharmonic order m must be >= 1, got " +
                     std::to_string(subharmonic));
  return 2 * M_PI * subharmonic / flow.forcing().Omega.front();
}

PeriodicProblem::PeriodicProblem(const ReducedField& field)
    : own_(std::make_unique<const ExactFlow>(field)),
      flow_(own_.get()),
      period_(std::numeric_limits<double>::quiet_NaN()) {}

PeriodicProblem::PeriodicProblem(const ExactFlow& flow, int subharmonic)
    : flow_(&flow), subharmonic_(subharmonic), period_(forced_period(flow, subharmonic)) {}

void PeriodicProblem::check_guess(const Vector& u0, const Vector& v0, double T,
                                  const std::string& solver) const {
  const Index n = field().size();
  if (u0.size() != n || v0.size() != n)
    throw InputError(solver + ": initial state of size " + std::to_string(u0.size()) + " and " +
                     std::to_string(v0.size()) + ", expected " + std::to_string(n) +
                     " interior dofs");
  if (!u0.allFinite() || !v0.allFinite()) throw InputError(solver + ": non-finite initial state");
  if (!forced()) {
    if (!(T > 0) || !std::isfinite(T))
      throw InputError(solver + ": the period guess must be > 0");
    return;
  }
  if (!(std::abs(T - period_) <= 1e-12 * period_)) {
    std::ostringstream s;
    s.precision(17);
    s << solver << ": the period " << T << " is not the excitation's, 2 pi m / omega = "
      << period_;
    throw InputError(s.str());
  }
}

}  // namespace nbm
