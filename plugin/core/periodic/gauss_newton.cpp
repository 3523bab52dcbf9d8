#include "periodic/gauss_newton.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <Eigen/QR>

#include "base/errors.hpp"

namespace nbm {

GaussNewtonResult gauss_newton(const GaussNewtonFunction& evaluate, Vector y,
                               const GaussNewtonOptions& o) {
  GaussNewtonResult out;
  GaussNewtonEvaluation e = evaluate(y, true);
  for (int it = 0;; ++it) {
    out.merits.push_back(e.merit);
    out.iterations = it;
    if (e.merit <= o.tolerance) break;
    if (it >= o.max_iterations || !std::isfinite(e.merit))
      throw NumericalError(o.name + ": no convergence in " + std::to_string(it) +
                           " Newton iterations " + o.context + "(residual " +
                           std::to_string(e.merit) + ")");
    Vector step;
    if (o.solver == GaussNewtonOptions::Solver::orthogonal)
      step = e.J.completeOrthogonalDecomposition().solve(-e.R);
    else if (e.J.rows() > e.J.cols())
      step = e.J.householderQr().solve(-e.R);
    else
      step = e.J.partialPivLu().solve(-e.R);
    // Trust region on the period-like unknown: at most 20% change per step.
    const Index iT = o.period_index;
    double damping =
        iT < 0 ? 1.0
               : std::min(1.0, 0.2 * std::abs(y(iT)) / std::max(std::abs(step(iT)), periodic_tiny));
    GaussNewtonEvaluation trial = evaluate(y + damping * step, false);
    while (!(trial.size < e.size) && damping > 1.0 / 1024) {
      damping /= 2;
      trial = evaluate(y + damping * step, false);
    }
    y += damping * step;
    e = evaluate(y, true);
  }
  out.y = std::move(y);
  out.last = std::move(e);
  return out;
}

}  // namespace nbm
