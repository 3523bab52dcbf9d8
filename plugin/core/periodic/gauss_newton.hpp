// The damped Gauss-Newton loop shared by the periodic-orbit solvers
// (shooting.cpp, harmonic_balance.cpp).
//
// Unknowns y; the caller's `evaluate(y, jacobian)` returns the scaled
// residual R, its Jacobian J (only if asked), the merit convergence is
// judged on (merit <= tolerance) and the size the line search decreases
// (often |R|; may equal the merit). Each iteration takes the least-squares
// step J s = -R, limits the change of the period-like unknown y(period_index)
// to 20% of its value (a trust region: the period map is only piecewise
// smooth, and a full step from a rough guess can jump to another branch, a
// multiple of the period), then halves the step (down to 1/1024) until the
// size decreases. Non-convergence in max_iterations, or a non-finite merit,
// throws NumericalError("<name>: no convergence in <it> Newton iterations
// <context>(residual <merit>)").
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "base/types.hpp"
#include "periodic/periodic_defaults.hpp"

namespace nbm {

struct GaussNewtonEvaluation {
  Vector R;  ///< scaled residual
  Matrix J;  ///< its Jacobian (rows of R x entries of y); empty if not asked
  double merit = std::numeric_limits<double>::infinity();  ///< converged: <= tolerance
  double size = std::numeric_limits<double>::infinity();   ///< decreased by the line search
};

struct GaussNewtonOptions {
  enum class Solver {
    orthogonal,  ///< complete orthogonal decomposition (rank-deficient J)
    householder  ///< Householder QR if J has more rows than columns, else LU
  };
  /// The period-like unknown of the trust region; -1: none (a forced orbit,
  /// whose period the excitation fixes).
  Index period_index = 0;
  double tolerance = 1e-12;
  int max_iterations = periodic_max_iterations;
  Solver solver = Solver::orthogonal;
  std::string name;     ///< leads the error message ("shooting")
  std::string context;  ///< after the iteration count ("at H = 20 ")
};

struct GaussNewtonResult {
  Vector y;
  GaussNewtonEvaluation last;      ///< the evaluation at y (with J)
  int iterations = 0;
  std::vector<double> merits;      ///< merit at the start of each iteration and at the end
};

using GaussNewtonFunction =
    std::function<GaussNewtonEvaluation(const Vector& y, bool jacobian)>;

/// Damped Gauss-Newton from y (see above). Throws NumericalError on
/// non-convergence.
GaussNewtonResult gauss_newton(const GaussNewtonFunction& evaluate, Vector y,
                               const GaussNewtonOptions& options);

}  // namespace nbm
