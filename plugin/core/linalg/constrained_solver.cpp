#include "linalg/constrained_solver.hpp"

#include <algorithm>
#include <vector>

#include "base/errors.hpp"

namespace nbm {
namespace {

// A set differing from its base (ConstrainedSolver::schur) at
// r <= n_c / kBorderedFraction nodes gets a factor bordered on the base's,
// the others a fresh one; bases are made of kBaseBlocks blocks of nodes, so
// a single contact front leaves at most n_c / (2 kBaseBlocks) changes.
constexpr Index kBorderedFraction = 8;
constexpr Index kBaseBlocks = 16;

// x solves X x = r + G^T mu, G x = h with X = P' L L' P, Y = L^-1 P B and S the
// Cholesky factor of G X^-1 G^T: y = L^-1 P r, mu = S^-1 (h - Y_G^T y),
// x = P' L^-T (y + Y_G mu), one substitution each way. Column k of Y_G is
// Y.col(column(k)); mu is a workspace of n_c values.
template <class Column, class Factor>
void solve_through_halves(const CholeskyInverse& X, const SparseMatrix& Y, Column column,
                          const Factor& S, const Vector& r, const Vector& h, Vector& mu,
                          Vector& x) {
  x = r;
  X.forward_in_place(x);  // y
  for (Index k = 0; k < mu.size(); ++k) mu(k) = h(k) - Y.col(column(k)).dot(x);
  S.solve_in_place(mu);
  for (Index k = 0; k < mu.size(); ++k) x += mu(k) * Y.col(column(k));
  X.backward_in_place(x);
}

}  // namespace

ConstrainedSolver::ConstrainedSolver(std::unique_ptr<DiagonalInverse> X, const SparseMatrix& B)
    : X_(std::move(X)),
      diagonal_(static_cast<const DiagonalInverse*>(X_.get())),
      B_(B),
      n_c_(B.cols() / 2),
      sparse_W_(std::in_place, diagonal_->sparse_gram(B)),
      zero_(Vector::Zero(n_c_)),
      mu_(n_c_) {
  F_.reserve(n_c_);
}

ConstrainedSolver::ConstrainedSolver(std::shared_ptr<const CholeskyInverse> X,
                                     const SparseMatrix& B)
    : X_(std::move(X)),
      cholesky_(static_cast<const CholeskyInverse*>(X_.get())),
      B_(B),
      n_c_(B.cols() / 2),
      Y_(cholesky_->forward(B, &W_)),
      zero_(Vector::Zero(n_c_)),
      mu_(n_c_) {}

const SchurFactor& ConstrainedSolver::schur(const ActiveSet& active) const {
  if (const auto* known = schur_.find(active)) return **known;
  // The base of a set is a function of the set alone (so that the factor of
  // a set, and a run, do not depend on the sets met before: the caches stay
  // pure memoization and a restart is exact): the contact nodes in blocks of
  // n_c / kBaseBlocks consecutive ones, each block wholly closed if most of
  // its nodes are, else wholly open. A contact front sweeping the nodes in
  // their order changes only the blocks it crosses.
  std::vector<Index> columns(n_c_), base_columns(n_c_);
  const Index block = std::max<Index>(1, n_c_ / kBaseBlocks);
  for (Index first = 0; first < n_c_; first += block) {
    const Index last = std::min(first + block, n_c_);
    Index closed = 0;
    for (Index k = first; k < last; ++k) closed += active[k];
    for (Index k = first; k < last; ++k) {
      columns[k] = column(active, k);
      base_columns[k] = 2 * closed > last - first ? n_c_ + k : k;
    }
  }
  // Bordering costs about 2 n_c^2 r flops against n_c^3 / 3 for a fresh
  // factor: break-even at r = n_c / 6, kBorderedFraction leaves a margin for
  // triangular solves being slower per flop (bench/why.md, "Many contact nodes").
  if (kBorderedFraction * SchurFactor::changes(columns, base_columns) > n_c_)
    return *schur_.insert(active, std::make_shared<const SchurFactor>(W_, std::move(columns)));
  if (base_ == nullptr || base_->columns() != base_columns) {
    base_ = std::make_shared<const SchurFactor>(W_, std::move(base_columns));
    // The bordered factors of the previous base would keep it alive outside
    // the cache's budget.
    schur_.remove_if([](const std::shared_ptr<const SchurFactor>& f) { return !f->fresh(); });
  }
  if (columns == base_->columns()) return *schur_.insert(active, base_);
  return *schur_.insert(active,
                        std::make_shared<const SchurFactor>(W_, std::move(columns), base_));
}

void ConstrainedSolver::solve(const ActiveSet& active, const Vector& r, Vector& x) const {
  solve(active, r, zero_, x);
}

void ConstrainedSolver::solve(const ActiveSet& active, const Vector& r, const Vector& h,
                              Vector& x) const {
  if (cholesky_ != nullptr)
    solve_with_factor(active, r, h, x);
  else
    solve_with_diagonal(active, r, h, x);
}

void ConstrainedSolver::solve_with_diagonal(const ActiveSet& active, const Vector& r,
                                            const Vector& h, Vector& x) const {
  const Vector& d = diagonal_->inverse();
  x = d.cwiseProduct(r);
  F_.clear();
  for (Index k = 0; k < n_c_; ++k)
    if (!active[k]) F_.push_back(k);
  for (Index k = 0; k < n_c_; ++k)
    if (active[k]) F_.push_back(n_c_ + k);
  const PrincipalBlockFactor& S =
      blocks_.get(active, [&] { return PrincipalBlockFactor(*sparse_W_, F_); });
  if (!S.positive_definite())
    throw NumericalError("the constraint Schur complement of an active set is singular");
  // mu in the order of F: column F_[a] of B is row a of G.
  for (Index a = 0; a < n_c_; ++a) mu_(a) = h(F_[a] % n_c_) - B_.col(F_[a]).dot(x);
  S.solve_in_place(mu_);
  for (Index a = 0; a < n_c_; ++a)
    for (SparseMatrix::InnerIterator it(B_, F_[a]); it; ++it)
      x(it.row()) += mu_(a) * d(it.row()) * it.value();
}

void ConstrainedSolver::solve_with_factor(const ActiveSet& active, const Vector& r,
                                          const Vector& h, Vector& x) const {
  solve_through_halves(*cholesky_, Y_, [&](Index k) { return column(active, k); }, schur(active),
                       r, h, mu_, x);
}

void solve_constrained_once(const CholeskyInverse& X, const SparseMatrix& B,
                            const ActiveSet& active, const Vector& r, const Vector& h,
                            Vector& x) {
  const Index n_c = B.cols() / 2;
  std::vector<Triplet> picks;
  for (Index k = 0; k < n_c; ++k) picks.emplace_back(active[k] ? n_c + k : k, k, 1.0);
  SparseMatrix select(B.cols(), n_c);
  select.setFromTriplets(picks.begin(), picks.end());
  Matrix W;
  const SparseMatrix Y_G = X.forward(SparseMatrix(B * select), &W);
  std::vector<Index> all(n_c);
  for (Index k = 0; k < n_c; ++k) all[k] = k;
  const SchurFactor S(W, std::move(all));
  Vector mu(n_c);
  solve_through_halves(X, Y_G, [](Index k) { return k; }, S, r, h, mu, x);
}

}  // namespace nbm
