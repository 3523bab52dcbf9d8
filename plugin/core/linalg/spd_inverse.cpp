#include "linalg/spd_inverse.hpp"

#include <cholmod.h>

#include <algorithm>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "linalg/supernodal_forward.hpp"

namespace nbm {
namespace {

// A CHOLMOD view (no copy) of column-major doubles.
cholmod_dense dense_view(double* data, Index rows, Index cols) {
  cholmod_dense d{};
  d.nrow = d.d = static_cast<std::size_t>(rows);
  d.ncol = static_cast<std::size_t>(cols);
  d.nzmax = d.nrow * d.ncol;
  d.x = data;
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

// A CHOLMOD view of the lower triangle of a symmetric compressed matrix.
cholmod_sparse lower_view(const SparseMatrix& A) {
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(A.rows());
  s.ncol = static_cast<std::size_t>(A.cols());
  s.nzmax = static_cast<std::size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

// Entries of Y = L^-1 P B for the supernodal symbolic factor L: column j of Y
// is nonzero on the union of the elimination-tree paths from the rows of B's
// column j to the root, in the supernodal pattern (which forward()'s sparse
// substitutions use, amalgamation zeros included). In a supernode the parent
// of a column is the next one, and that of its last column the supernode's
// first row below its diagonal block.
double forward_entries(const cholmod_factor& L, const SparseMatrix& B) {
  const int n = static_cast<int>(L.n);
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* rows = static_cast<const int*>(L.s);
  const int* perm = static_cast<const int*>(L.Perm);
  std::vector<int> parent(n, -1), inverse(n), mark(n, -1);
  for (std::size_t k = 0; k < L.nsuper; ++k) {
    const int first = super[k], last = super[k + 1];
    for (int j = first; j + 1 < last; ++j) parent[j] = j + 1;
    if (pi[k + 1] - pi[k] > last - first) parent[last - 1] = rows[pi[k] + last - first];
  }
  for (int k = 0; k < n; ++k) inverse[perm[k]] = k;
  double entries = 0;
  for (int j = 0; j < static_cast<int>(B.cols()); ++j)
    for (SparseMatrix::InnerIterator it(B, j); it; ++it)
      for (int p = inverse[it.row()]; p != -1 && mark[p] != j; p = parent[p]) {
        mark[p] = j;
        ++entries;
      }
  return entries;
}

// The symbolic factor of A whose constrained steps with B cost least: a step
// does two substitutions with L (about 2 xsize flops each) and two products
// with the columns of Y = L^-1 P B that the active set selects (about half
// of Y's entries, 2 flops each). CHOLMOD's own choice minimises the fill
// alone; on a long 2D strip it is AMD, whose elimination tree is nearly a
// path, so that a contact column of Y reaches nearly every later row (the
// setup, the memory and every step then grow with n_c n); nested dissection
// (METIS) keeps the paths to the separators above the node. Both are tried
// when CHOLMOD's choice is not already a nested dissection, and nested
// dissection is taken only if it at least halves the cost: another ordering
// moves every trajectory at round-off level, which near-equal costs do not
// pay for (small bodies keep the factor, and the results, of the plain solves).
cholmod_factor* analyze_for(cholmod_sparse& A, const SparseMatrix& B, cholmod_common& common) {
  cholmod_factor* best = cholmod_analyze(&A, &common);
  if (best == nullptr || B.cols() == 0 || best->ordering == CHOLMOD_METIS ||
      best->ordering == CHOLMOD_NESDIS)
    return best;
  auto cost = [&](const cholmod_factor& L) {
    return 4 * static_cast<double>(L.xsize) + 2 * forward_entries(L, B);
  };
  const int methods = common.nmethods, ordering = common.method[0].ordering;
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_METIS;
  cholmod_factor* dissection = cholmod_analyze(&A, &common);
  common.nmethods = methods;
  common.method[0].ordering = ordering;
  if (dissection != nullptr && 2 * cost(*dissection) < cost(*best)) std::swap(best, dissection);
  cholmod_free_factor(&dissection, &common);
  return best;
}

// Supernodal sparse Cholesky X = P' L L' P through CHOLMOD directly (not
// Eigen's wrapper), for two things the wrapper hides: the factor L itself,
// whose forward substitutions with sparse right-hand sides make the Gram
// matrix cheap, and cholmod_solve2's reusable workspaces, which make a solve
// free of heap allocations once the first one has sized them.
class CholmodInverse final : public CholeskyInverse {
 public:
  /// `constraints`: the columns B of the constrained solves to come (the
  /// ordering is chosen for them, analyze_for), or none.
  CholmodInverse(const SparseMatrix& X, const std::string& what, const SparseMatrix& constraints)
      : n_(X.rows()), permuted_(n_) {
    cholmod_start(&common_);
    common_.final_asis = 1;
    common_.supernodal = CHOLMOD_SUPERNODAL;
    SparseMatrix A = X;
    A.makeCompressed();
    cholmod_sparse view = lower_view(A);
    L_ = analyze_for(view, constraints, common_);
    if (L_ == nullptr || !cholmod_factorize(&view, L_, &common_) || L_->minor != L_->n) {
      release();
      throw NumericalError(what + " is not positive definite (Cholesky factorization failed)");
    }
    if (!L_->is_super) {  // forced above; the half solves below rely on it
      release();
      throw NumericalError(what + ": CHOLMOD returned a simplicial factor, expected supernodal");
    }
    supernode_work_.resize(static_cast<Index>(std::max<std::size_t>(L_->maxesize, 1)));
  }
  ~CholmodInverse() override { release(); }

  Index size() const override { return n_; }
  void solve_in_place(Matrix& x) const override { solve(x.data(), x.cols()); }
  // One vector: the two halves below, which copy less than cholmod_solve2.
  void solve_in_place(Vector& x) const override {
    forward_in_place(x);
    backward_in_place(x);
  }

  // The supernodal substitutions work in place on a dense column: one
  // gather (forward) or scatter (backward) through P is the only copy, and
  // x swaps buffers with the permuted copy (x must have the size n).
  void forward_in_place(Vector& x) const override {
    check_size(x);
    const int* perm = static_cast<const int*>(L_->Perm);
    for (Index k = 0; k < n_; ++k) permuted_(k) = x(perm[k]);
    substitute(cholmod_super_lsolve, permuted_);
    x.swap(permuted_);
  }

  void backward_in_place(Vector& x) const override {
    check_size(x);
    const int* perm = static_cast<const int*>(L_->Perm);
    substitute(cholmod_super_ltsolve, x);
    for (Index k = 0; k < n_; ++k) permuted_(perm[k]) = x(k);
    x.swap(permuted_);
  }

  using CholeskyInverse::forward;
  /// W = B' X^-1 B = Y' Y with Y = L^-1 P B (method.md §4), Y not kept.
  Matrix gram(const SparseMatrix& B) const override {
    check_rows(B);
    Matrix W;
    supernodal_forward(*L_, B, nullptr, &W);
    return W;
  }

  SparseMatrix forward(const SparseMatrix& B, Matrix* gram) const override {
    check_rows(B);
    SparseMatrix Y;
    supernodal_forward(*L_, B, &Y, gram);
    return Y;
  }

  double forward_entries(const SparseMatrix& B) const override {
    check_rows(B);
    return nbm::forward_entries(*L_, B);
  }
  double factor_entries() const override { return static_cast<double>(L_->xsize); }

  // x <- X^{-1} x for `cols` columns in place (several right-hand sides at once).
  void solve(double* x, Index cols) const {
    cholmod_dense b = dense_view(x, n_, cols);
    if (!cholmod_solve2(CHOLMOD_A, L_, &b, nullptr, &solution_, nullptr, &work_y_, &work_e_,
                        &common_))
      throw NumericalError("CHOLMOD solve failed (out of memory?)");
    const double* s = static_cast<const double*>(solution_->x);
    std::copy(s, s + n_ * cols, x);
  }

  void check_rows(const SparseMatrix& B) const {
    if (B.rows() != n_)
      throw InputError("forward: a matrix with " + std::to_string(B.rows()) + " rows, expected " +
                       std::to_string(n_));
  }

  void check_size(const Vector& x) const {
    if (x.size() != n_)
      throw InputError("solve: a vector of size " + std::to_string(x.size()) + ", expected " +
                       std::to_string(n_));
  }

  // x <- L^{-1} x or L^{-T} x (`half`: cholmod_super_lsolve or _ltsolve).
  using Substitution = int (*)(cholmod_factor*, cholmod_dense*, cholmod_dense*, cholmod_common*);
  void substitute(Substitution half, Vector& x) const {
    cholmod_dense b = dense_view(x.data(), n_, 1);
    cholmod_dense e = dense_view(supernode_work_.data(), supernode_work_.size(), 1);
    if (!half(L_, &b, &e, &common_)) throw NumericalError("CHOLMOD substitution failed");
  }

  void release() {
    cholmod_free_dense(&solution_, &common_);
    cholmod_free_dense(&work_y_, &common_);
    cholmod_free_dense(&work_e_, &common_);
    cholmod_free_factor(&L_, &common_);
    cholmod_finish(&common_);
  }

  Index n_;
  // Solves change CHOLMOD's status fields and reuse the workspaces below:
  // mutable, and one solve at a time per inverse.
  mutable cholmod_common common_;
  cholmod_factor* L_ = nullptr;
  mutable cholmod_dense *solution_ = nullptr, *work_y_ = nullptr, *work_e_ = nullptr;
  mutable Vector permuted_;        // P x of the half solves
  mutable Vector supernode_work_;  // CHOLMOD's workspace E of a supernodal substitution
};

}  // namespace

std::vector<Index> fill_reducing_order(const SparseMatrix& X) {
  cholmod_common common;
  cholmod_start(&common);
  SparseMatrix A = X;
  A.makeCompressed();
  cholmod_sparse view = lower_view(A);
  cholmod_factor* L = cholmod_analyze(&view, &common);
  if (L == nullptr) {
    cholmod_finish(&common);
    throw NumericalError("CHOLMOD could not order a matrix of size " + std::to_string(X.rows()));
  }
  const int* perm = static_cast<const int*>(L->Perm);
  std::vector<Index> order(perm, perm + X.rows());
  cholmod_free_factor(&L, &common);
  cholmod_finish(&common);
  return order;
}

std::unique_ptr<CholeskyInverse> make_cholesky_inverse(const SparseMatrix& X,
                                                       const std::string& what) {
  return std::make_unique<CholmodInverse>(X, what, SparseMatrix(X.rows(), 0));
}

std::unique_ptr<CholeskyInverse> make_cholesky_inverse(const SparseMatrix& X,
                                                       const std::string& what,
                                                       const SparseMatrix& constraints) {
  return std::make_unique<CholmodInverse>(X, what, constraints);
}

SparseMatrix DiagonalInverse::sparse_gram(const SparseMatrix& B) const {
  // B^T D^{-1} B costs what B costs.
  const SparseMatrix DB = inverse_.asDiagonal() * B;
  return SparseMatrix(SparseMatrix(B.transpose()) * DB);
}

std::unique_ptr<DiagonalInverse> make_diagonal_inverse(const Vector& d, const std::string& what) {
  for (Index i = 0; i < d.size(); ++i)
    if (!(d(i) > 0))
      throw InputError(what + ": entry " + std::to_string(i) + " is " + std::to_string(d(i)) +
                       ", expected a positive lumped mass");
  return std::make_unique<DiagonalInverse>(d.cwiseInverse());
}

}  // namespace nbm
