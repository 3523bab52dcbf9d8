#include "linalg/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>

#include "base/errors.hpp"

namespace nbm {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Number of block pivots allowed without a decrease of the number of
// infeasibilities before switching to single pivots (Judice & Pires' p-bar).
constexpr int kBlockPivotPatience = 3;

// Ratio of magnitudes of the right-hand side above which rows are of two
// scales (solve_two_scale).
constexpr double kScaleSeparation = 1e3;

void free_indices(const std::vector<bool>& active, std::vector<Index>& F) {
  F.clear();
  for (std::size_t i = 0; i < active.size(); ++i)
    if (!active[i]) F.push_back(static_cast<Index>(i));
}

// A square, finite, symmetric matrix, dense or sparse.
template <class AnyMatrix>
const AnyMatrix& check_matrix(const AnyMatrix& A, Index n) {
  if (A.rows() != n || A.cols() != n)
    throw InputError("LCP: matrix is " + std::to_string(A.rows()) + "x" +
                     std::to_string(A.cols()) + ", expected " + std::to_string(n) + "x" +
                     std::to_string(n));
  if constexpr (std::is_same_v<AnyMatrix, SparseMatrix>) {
    if (!A.coeffs().allFinite()) throw InputError("LCP: non-finite data");
  } else {
    if (!A.allFinite()) throw InputError("LCP: non-finite data");
  }
  // Principal blocks are factored by Cholesky, which reads one triangle only:
  // a non-symmetric matrix would be silently replaced by another one. (A
  // dense matrix is compared with its transpose in place, without a copy.)
  bool symmetric = false;
  if constexpr (std::is_same_v<AnyMatrix, SparseMatrix>)
    symmetric = A.isApprox(SparseMatrix(A.transpose()), 1e-12);
  else
    symmetric = A.isApprox(A.transpose(), 1e-12);
  if (!symmetric)
    throw InputError("LCP: matrix is not symmetric, expected a symmetric positive definite K_CC");
  return A;
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

// z solves the principal subproblem of the free set F with the factor of
// A_FF: z_F = -A_FF^{-1} q_F, z_G = 0. `work` holds at least |F| entries.
void solve_principal(const PrincipalBlockFactor& factor, const Vector& q,
                     const std::vector<Index>& F, Vector& work, Vector& z) {
  z.setZero();
  const Index m = static_cast<Index>(F.size());
  auto zF = work.head(m);
  for (Index a = 0; a < m; ++a) zF(a) = -q(F[a]);
  factor.solve_in_place(zF);
  for (Index a = 0; a < m; ++a) z(F[a]) = zF(a);
}

// Block principal pivoting (header) from the active set in r.
// `factor(F)` returns the Cholesky factor of A_FF for the free set F of
// r.active (a pointer, null if A_FF is not positive definite); a_max is the
// largest |A_ij|; F, infeasible and work are workspaces. Rows marked in `frozen` (empty: none) stay at
// z_i = 0 and are neither checked nor part of the tolerances' scale: the
// pivoting then solves the principal sub-LCP of the other rows. Returns the
// smallest w_i of the checked rows with z_i = 0 before the round-off noise
// is removed (negative: a row accepted by its tolerance only).
template <class Factor>
double pivot(const PrincipalBlocks& A, const Vector& q, double a_max, LcpResult& r,
             std::vector<Index>& F, std::vector<Index>& infeasible, Vector& work,
             const std::vector<bool>& frozen, Factor factor) {
  const Index n = q.size();
  // Single pivots alone (Murty) are finite on P-matrices but may need many
  // steps; this bound is far beyond what any practical problem uses and only
  // turns a (theoretically impossible) endless loop into an error.
  const long max_pivots = 1000 + 200L * n;
  const bool has_frozen = !frozen.empty();
  double q_scale = 0;
  for (Index i = 0; i < n; ++i)
    if (!has_frozen || !frozen[i]) q_scale = std::max(q_scale, std::abs(q(i)));
  Index best_infeasible = n + 1;
  int patience = kBlockPivotPatience;

  for (long p = 0; p < max_pivots; ++p) {
    free_indices(r.active, F);
    ++r.pivots;
    if (F.empty()) {
      r.z.setZero();
    } else {
      const PrincipalBlockFactor* A_FF = factor(F);
      if (A_FF == nullptr)
        throw NumericalError("LCP: principal block of size " + std::to_string(F.size()) +
                             " is not positive definite (the matrix is not a P-matrix)");
      solve_principal(*A_FF, q, F, work, r.z);
    }
    r.w = q;
    A.add_columns_product(F, r.z, r.w);  // z = 0 off F
    for (Index i : F) r.w(i) = 0.0;  // exact on the free set by construction
    if (!r.z.allFinite() || !r.w.allFinite())  // finite data, overflowing solution
      throw NumericalError("LCP: the solution overflows; the data are too badly scaled");

    // Round-off tolerances scale with the magnitudes of the current solution.
    const double z_scale = r.z.cwiseAbs().maxCoeff();
    const double tol_z = 8 * n * kEps * z_scale;
    const double tol_w = 8 * n * kEps * (q_scale + a_max * z_scale);
    infeasible.clear();
    double w_min = std::numeric_limits<double>::infinity();
    for (Index i = 0; i < n; ++i) {
      if (has_frozen && frozen[i]) continue;
      if (r.active[i]) w_min = std::min(w_min, r.w(i));
      if ((!r.active[i] && r.z(i) < -tol_z) || (r.active[i] && r.w(i) < -tol_w))
        infeasible.push_back(i);
    }

    if (infeasible.empty()) {
      // Feasible complementary basis: this is the unique solution. Remove the
      // round-off sign noise so that z >= 0 and w >= 0 hold exactly.
      r.z = r.z.cwiseMax(0.0);
      r.w = r.w.cwiseMax(0.0);
      return w_min;
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

// Marks in ws.frozen the rows of a two-scale LCP that the solution r leaves
// open by far: the rows with the largest q_i, all with z_i = 0 and w_i > 0,
// whose q_i exceed every other |q_j| by kScaleSeparation or more. Returns
// whether there are such rows.
bool mark_far_rows(const Vector& q, const LcpResult& r, LcpWorkspace& ws) {
  const Index n = q.size();
  ws.order.resize(n);  // capacity reserved: no allocation
  std::iota(ws.order.begin(), ws.order.end(), Index{0});
  std::sort(ws.order.begin(), ws.order.end(),
            [&](Index a, Index b) { return std::abs(q(a)) > std::abs(q(b)); });
  Index split = 0;
  for (Index k = 0; k + 1 < n; ++k) {
    const Index i = ws.order[k];
    if (!r.active[i] || q(i) <= 0 || r.w(i) <= 0) break;
    if (q(i) >= kScaleSeparation * std::abs(q(ws.order[k + 1]))) split = k + 1;
  }
  if (split == 0) return false;
  ws.frozen.assign(n, false);
  for (Index k = 0; k < split; ++k) ws.frozen[ws.order[k]] = true;
  return true;
}

// The solution by pivoting, with the rows of two scales judged apart. The
// tolerances of the sign checks scale with max |q_i|, so one row with a huge
// q_i (a contact node far from the obstacle: gap 1e9 beside gaps of 1e-3)
// would let every other row pass with w_i down to -1e-5. When the solution
// has such far rows and a row was accepted by its tolerance only, the far
// rows are frozen at z = 0 and the sub-LCP of the others solved again, warm,
// with their own scale; the far rows are then checked with the full scale.
// Should that check or the second pivoting fail, the first solution (valid
// to the full scale's round-off) stands.
template <class Factor>
void solve_two_scale(const PrincipalBlocks& A, const Vector& q, double a_max, LcpResult& r,
                     LcpWorkspace& ws, Factor factor) {
  const double w_min = pivot(A, q, a_max, r, ws.free, ws.infeasible, ws.rhs, {}, factor);
  if (w_min >= 0 || !mark_far_rows(q, r, ws)) return;
  ws.first = r;
  try {
    pivot(A, q, a_max, r, ws.free, ws.infeasible, ws.rhs, ws.frozen, factor);
  } catch (const NumericalError&) {
    r = ws.first;
    return;
  }
  const double tol_w = 8 * q.size() * kEps *
                       (q.cwiseAbs().maxCoeff() + a_max * r.z.cwiseAbs().maxCoeff());
  for (Index i = 0; i < q.size(); ++i)
    if (ws.frozen[i] && r.w(i) < -tol_w) {
      r = ws.first;
      return;
    }
}

}  // namespace

LcpWorkspace::LcpWorkspace(Index n) : rhs(n) {
  free.reserve(n);
  infeasible.reserve(n);
  order.reserve(n);
  frozen.reserve(n);
  first.z.resize(n);
  first.w.resize(n);
  first.active.reserve(n);
}

LcpResult LcpSolver::solve(const Matrix& A, const Vector& q, const std::vector<bool>& guess) {
  const Index n = q.size();
  check_matrix(A, n);
  check_data(q, guess);
  LcpResult r;
  start(r, q, guess);
  if (n == 0) return r;
  LcpWorkspace ws(n);
  const PrincipalBlocks blocks(A);
  std::optional<PrincipalBlockFactor> factor;  // the current one
  solve_two_scale(blocks, q, A.cwiseAbs().maxCoeff(), r, ws,
        [&](const std::vector<Index>& free) -> const PrincipalBlockFactor* {
          factor.emplace(blocks, free);
          return factor->positive_definite() ? &*factor : nullptr;
        });
  return r;
}

CachedLcpSolver::CachedLcpSolver(Matrix A)
    : A_((check_matrix(A, A.rows()), std::move(A))),
      a_max_(A_.max_abs()),
      workspace_(A_.size()) {
  result_.active.reserve(A_.size());
}

CachedLcpSolver::CachedLcpSolver(const SparseMatrix& A)
    : A_(check_matrix(A, A.rows())), a_max_(A_.max_abs()), workspace_(A.rows()) {
  result_.active.reserve(A.rows());
}

const PrincipalBlockFactor& CachedLcpSolver::principal_factor(const std::vector<bool>& active,
                                                              const std::vector<Index>& F) const {
  return principal_blocks_.get(active, [&] { return PrincipalBlockFactor(A_, F); });
}

const LcpResult& CachedLcpSolver::solve(const Vector& q, const std::vector<bool>& guess) const {
  const Index n = A_.size();
  if (q.size() != n)
    throw InputError("LCP: q has size " + std::to_string(q.size()) + ", expected " +
                     std::to_string(n) + " (the size of the matrix)");
  check_data(q, guess);
  start(result_, q, guess);
  if (n == 0) return result_;
  solve_two_scale(A_, q, a_max_, result_, workspace_,
        [&](const std::vector<Index>& free) -> const PrincipalBlockFactor* {
          const auto& factor = principal_factor(result_.active, free);
          return factor.positive_definite() ? &factor : nullptr;
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
