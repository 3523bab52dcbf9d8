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

void free_indices(const std::vector<bool>& active, std::vector<Index>& F) {
  F.clear();
  for (std::size_t i = 0; i < active.size(); ++i)
    if (!active[i]) F.push_back(static_cast<Index>(i));
}

void check_matrix(const Matrix& A, Index n) {
  if (A.rows() != n || A.cols() != n)
    throw InputError("LCP: matrix is " + std::to_string(A.rows()) + "x" +
                     std::to_string(A.cols()) + ", expected " + std::to_string(n) + "x" +
                     std::to_string(n));
  if (!A.allFinite()) throw InputError("LCP: non-finite data");
  // Principal blocks are factored by Cholesky, which reads one triangle only:
  // a non-symmetric matrix would be silently replaced by another one.
  if (!A.isApprox(A.transpose(), 1e-12))
    throw InputError("LCP: matrix is not symmetric, expected a symmetric positive definite K_CC");
}

void check_data(const Vector& q, const std::vector<bool>& guess) {
  if (!q.allFinite()) throw InputError("LCP: non-finite data");
  if (!guess.empty() && guess.size() != static_cast<std::size_t>(q.size()))
    throw InputError("LCP: warm-start active set has the wrong size");
}

// Starts r at the guessed active set (default: everything closed, z = 0, w = q).
void start(LcpResult& r, const Vector& q, const std::vector<bool>& guess) {
  const Index n = q.size();
  if (guess.empty())
    r.active.assign(n, true);
  else
    r.active = guess;
  r.z.setZero(n);
  r.w = q;
  r.pivots = 0;
}

// The principal block A_FF of the free set F.
Matrix principal_block(const Matrix& A, const std::vector<Index>& F) {
  const Index m = static_cast<Index>(F.size());
  Matrix AFF(m, m);
  for (Index a = 0; a < m; ++a)
    for (Index b = 0; b < m; ++b) AFF(a, b) = A(F[a], F[b]);
  return AFF;
}

// z solves the principal subproblem of the free set F with the factor of
// A_FF: z_F = -A_FF^{-1} q_F, z_G = 0. `work` holds at least |F| entries.
void solve_principal(const Eigen::LLT<Matrix>& llt, const Vector& q,
                     const std::vector<Index>& F, Vector& work, Vector& z) {
  z.setZero();
  const Index m = static_cast<Index>(F.size());
  auto zF = work.head(m);
  for (Index a = 0; a < m; ++a) zF(a) = -q(F[a]);
  llt.matrixL().solveInPlace(zF);
  llt.matrixU().solveInPlace(zF);
  for (Index a = 0; a < m; ++a) z(F[a]) = zF(a);
}

// Block principal pivoting (header) from the active set in r.
// `factor(F)` returns the Cholesky factor of A_FF for the free set F of
// r.active (a pointer, null if A_FF is not positive definite); F, infeasible
// and work are workspaces.
template <class Factor>
void pivot(const Matrix& A, const Vector& q, double a_max, LcpResult& r, std::vector<Index>& F,
           std::vector<Index>& infeasible, Vector& work, Factor factor) {
  const Index n = q.size();
  // Single pivots alone (Murty) are finite on P-matrices but may need many
  // steps; this bound is far beyond what any practical problem uses and only
  // turns a (theoretically impossible) endless loop into an error.
  const long max_pivots = 1000 + 200L * n;
  Index best_infeasible = n + 1;
  int patience = kBlockPivotPatience;

  for (long p = 0; p < max_pivots; ++p) {
    free_indices(r.active, F);
    ++r.pivots;
    if (F.empty()) {
      r.z.setZero();
    } else {
      const Eigen::LLT<Matrix>* llt = factor(F);
      if (llt == nullptr)
        throw NumericalError("LCP: principal block of size " + std::to_string(F.size()) +
                             " is not positive definite (the matrix is not a P-matrix)");
      solve_principal(*llt, q, F, work, r.z);
    }
    r.w = q;
    r.w.noalias() += A * r.z;
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
      return;
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

}  // namespace

LcpResult LcpSolver::solve(const Matrix& A, const Vector& q, const std::vector<bool>& guess) {
  const Index n = q.size();
  check_matrix(A, n);
  check_data(q, guess);
  LcpResult r;
  start(r, q, guess);
  if (n == 0) return r;
  std::vector<Index> F, infeasible;
  Vector work(n);
  Eigen::LLT<Matrix> llt;
  pivot(A, q, A.cwiseAbs().maxCoeff(), r, F, infeasible, work,
        [&](const std::vector<Index>& free) -> const Eigen::LLT<Matrix>* {
          llt.compute(principal_block(A, free));
          return llt.info() == Eigen::Success ? &llt : nullptr;
        });
  return r;
}

CachedLcpSolver::CachedLcpSolver(Matrix A) : A_(std::move(A)), rhs_(A_.rows()) {
  check_matrix(A_, A_.rows());
  a_max_ = A_.size() > 0 ? A_.cwiseAbs().maxCoeff() : 0.0;
  free_.reserve(A_.rows());
  infeasible_.reserve(A_.rows());
  result_.active.reserve(A_.rows());
}

const LcpResult& CachedLcpSolver::solve(const Vector& q, const std::vector<bool>& guess) const {
  const Index n = A_.rows();
  if (q.size() != n)
    throw InputError("LCP: q has size " + std::to_string(q.size()) + ", expected " +
                     std::to_string(n) + " (the size of the matrix)");
  check_data(q, guess);
  start(result_, q, guess);
  if (n == 0) return result_;
  pivot(A_, q, a_max_, result_, free_, infeasible_, rhs_,
        [&](const std::vector<Index>& free) -> const Eigen::LLT<Matrix>* {
          const auto& llt = principal_blocks_.get(
              result_.active, [&] { return Eigen::LLT<Matrix>(principal_block(A_, free)); });
          return llt.info() == Eigen::Success ? &llt : nullptr;
        });
  return result_;
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
