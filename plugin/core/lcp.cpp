#include "lcp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "errors.hpp"

namespace nbm {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Number of block pivots allowed without a decrease of the number of
// infeasibilities before switching to single pivots (Judice & Pires' p-bar).
constexpr int kBlockPivotPatience = 3;

std::vector<Index> free_indices(const std::vector<bool>& active) {
  std::vector<Index> f;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (!active[i]) f.push_back(static_cast<Index>(i));
  return f;
}

// z solves the principal subproblem of the free set F: z_F = -A_FF^{-1} q_F,
// z_G = 0. Returns false if A_FF is not positive definite.
bool solve_principal(const Matrix& A, const Vector& q, const std::vector<Index>& F,
                     Vector& z) {
  z.setZero();
  if (F.empty()) return true;
  const Index m = static_cast<Index>(F.size());
  Matrix AFF(m, m);
  Vector qF(m);
  for (Index a = 0; a < m; ++a) {
    qF(a) = q(F[a]);
    for (Index b = 0; b < m; ++b) AFF(a, b) = A(F[a], F[b]);
  }
  Eigen::LLT<Matrix> llt(AFF);
  if (llt.info() != Eigen::Success) return false;
  const Vector zF = llt.solve(-qF);
  for (Index a = 0; a < m; ++a) z(F[a]) = zF(a);
  return true;
}

}  // namespace

LcpResult LcpSolver::solve(const Matrix& A, const Vector& q, const std::vector<bool>& guess) {
  const Index n = q.size();
  if (A.rows() != n || A.cols() != n)
    throw InputError("LCP: matrix is " + std::to_string(A.rows()) + "x" +
                     std::to_string(A.cols()) + ", expected " + std::to_string(n) + "x" +
                     std::to_string(n));
  if (!A.allFinite() || !q.allFinite()) throw InputError("LCP: non-finite data");
  // Principal blocks are factored by Cholesky, which reads one triangle only:
  // a non-symmetric matrix would be silently replaced by another one.
  if (!A.isApprox(A.transpose(), 1e-12))
    throw InputError("LCP: matrix is not symmetric, expected a symmetric positive definite K_CC");
  if (!guess.empty() && static_cast<Index>(guess.size()) != n)
    throw InputError("LCP: warm-start active set has the wrong size");

  LcpResult r;
  // Default start: everything closed (z = 0, w = q).
  r.active = guess.empty() ? std::vector<bool>(n, true) : guess;
  r.z = Vector::Zero(n);
  r.w = q;
  if (n == 0) return r;

  const double a_max = A.cwiseAbs().maxCoeff();
  // Single pivots alone (Murty) are finite on P-matrices but may need many
  // steps; this bound is far beyond what any practical problem uses and only
  // turns a (theoretically impossible) endless loop into an error.
  const long max_pivots = 1000 + 200L * n;
  Index best_infeasible = n + 1;
  int patience = kBlockPivotPatience;
  std::vector<Index> infeasible;

  for (long pivot = 0; pivot < max_pivots; ++pivot) {
    const std::vector<Index> F = free_indices(r.active);
    ++r.pivots;
    if (!solve_principal(A, q, F, r.z))
      throw NumericalError("LCP: principal block of size " + std::to_string(F.size()) +
                           " is not positive definite (the matrix is not a P-matrix)");
    r.w.noalias() = q + A * r.z;
    for (Index i : F) r.w(i) = 0.0;  // exact on the free set by construction
    if (!r.z.allFinite() || !r.w.allFinite())  // finite data, overflowing solution
      throw NumericalError("LCP: the solution overflows; the data are too badly scaled");

    // Round-off tolerances scale with the magnitudes of the current solution.
    const double z_scale = r.z.cwiseAbs().maxCoeff();
    const double tol_z = 8 * n * kEps * z_scale;
    const double tol_w = 8 * n * kEps * (q.cwiseAbs().maxCoeff() + a_max * z_scale);
    infeasible.clear();
    for (Index i = 0; i < n; ++i)
      if ((!r.active[i] && r.z(i) < -tol_z) || (r.active[i] && r.w(i) < -tol_w))
        infeasible.push_back(i);

    if (infeasible.empty()) {
      // Feasible complementary basis: this is the unique solution. Remove the
      // round-off sign noise so that z >= 0 and w >= 0 hold exactly.
      r.z = r.z.cwiseMax(0.0);
      r.w = r.w.cwiseMax(0.0);
      return r;
    }
    const Index count = static_cast<Index>(infeasible.size());
    if (count < best_infeasible) {
      best_infeasible = count;
      patience = kBlockPivotPatience;
      for (Index i : infeasible) r.active[i] = !r.active[i];
    } else if (patience > 0) {
      --patience;
      for (Index i : infeasible) r.active[i] = !r.active[i];
    } else {
      // Murty's least-index rule: finite on every P-matrix.
      r.active[infeasible.front()] = !r.active[infeasible.front()];
    }
  }
  throw NumericalError("LCP: no solution after " + std::to_string(max_pivots) + " pivots");
}

double LcpSolver::residual(const Matrix& A, const Vector& q, const Vector& z) {
  if (z.size() == 0) return 0.0;
  const Vector w = q + A * z;
  const double z_scale = std::max(z.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  const double w_scale = std::max({q.cwiseAbs().maxCoeff(), (A * z).cwiseAbs().maxCoeff(),
                                   std::numeric_limits<double>::min()});
  double r = 0;
  for (Index i = 0; i < z.size(); ++i) {
    const double zi = z(i) / z_scale, wi = w(i) / w_scale;
    r = std::max({r, -zi, -wi, std::min(std::abs(zi), std::abs(wi))});
  }
  return r;
}

}  // namespace nbm
