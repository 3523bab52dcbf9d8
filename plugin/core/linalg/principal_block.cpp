#include "linalg/principal_block.hpp"

#include <Eigen/SparseCholesky>

namespace nbm {

PrincipalBlocks::PrincipalBlocks(Matrix A) {
  const Index nonzeros = (A.array() != 0.0).count();
  sparse_ = A.size() > 0 && kSparseFraction * nonzeros <= A.size();
  if (sparse_)
    A_sparse_ = A.sparseView(0.0, 0.0);
  else
    A_ = std::move(A);
}

PrincipalBlocks::PrincipalBlocks(const SparseMatrix& A) {
  SparseMatrix pruned = A.pruned(0.0, 0.0);  // explicit zeros are not couplings
  const double entries = static_cast<double>(A.rows()) * static_cast<double>(A.cols());
  sparse_ = entries > 0 && kSparseFraction * static_cast<double>(pruned.nonZeros()) <= entries;
  if (sparse_)
    A_sparse_ = std::move(pruned);
  else
    A_ = Matrix(pruned);
}

double PrincipalBlocks::max_abs() const {
  if (sparse_) return A_sparse_.nonZeros() > 0 ? A_sparse_.coeffs().cwiseAbs().maxCoeff() : 0.0;
  return A_.size() > 0 ? A_.cwiseAbs().maxCoeff() : 0.0;
}

void PrincipalBlocks::add_product(const Vector& x, Vector& y) const {
  if (sparse_)
    y.noalias() += A_sparse_ * x;
  else
    y.noalias() += A_ * x;
}

void PrincipalBlocks::add_columns_product(const std::vector<Index>& F, const Vector& x,
                                          Vector& y) const {
  if (sparse_) {
    for (Index j : F)
      for (SparseMatrix::InnerIterator it(A_sparse_, j); it; ++it) y(it.row()) += it.value() * x(j);
  } else {
    for (Index j : F) y.noalias() += x(j) * A_.col(j);
  }
}

PrincipalBlockFactor::PrincipalBlockFactor(const PrincipalBlocks& A, const std::vector<Index>& F) {
  const Index m = static_cast<Index>(F.size());
  work_.resize(m);
  if (m == 0) return;
  if (!A.sparse_) {
    Matrix block(m, m);
    for (Index b = 0; b < m; ++b)
      for (Index a = 0; a < m; ++a) block(a, b) = A.A_(F[a], F[b]);
    dense_.emplace(std::move(block));
    positive_definite_ = dense_->positive_definite();
    return;
  }
  // A[F, F] from the columns of F, rows renumbered (position in F, -1 outside).
  std::vector<Index> position(static_cast<std::size_t>(A.A_sparse_.rows()), -1);
  for (Index a = 0; a < m; ++a) position[static_cast<std::size_t>(F[a])] = a;
  std::vector<Triplet> entries;
  for (Index b = 0; b < m; ++b)
    for (SparseMatrix::InnerIterator it(A.A_sparse_, F[b]); it; ++it) {
      const Index a = position[static_cast<std::size_t>(it.row())];
      if (a >= 0) entries.emplace_back(static_cast<int>(a), static_cast<int>(b), it.value());
    }
  SparseMatrix block(m, m);
  block.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> llt(block);
  positive_definite_ = llt.info() == Eigen::Success;
  if (!positive_definite_) return;
  L_ = llt.matrixL();
  P_ = llt.permutationP();
  P_inverse_ = llt.permutationPinv();
}

void PrincipalBlockFactor::solve_in_place(Eigen::Ref<Vector> x) const {
  if (x.size() == 0) return;
  if (dense_) {
    dense_->solve_in_place(x);
    return;
  }
  work_ = P_ * x;
  L_.triangularView<Eigen::Lower>().solveInPlace(work_);
  L_.transpose().triangularView<Eigen::Upper>().solveInPlace(work_);
  x = P_inverse_ * work_;
}

std::size_t PrincipalBlockFactor::bytes() const {
  const auto doubles =
      static_cast<std::size_t>(work_.size());
  const auto sparse = static_cast<std::size_t>(L_.nonZeros()) * (sizeof(double) + sizeof(int)) +
                      static_cast<std::size_t>(L_.outerSize() + 1) * sizeof(int) +
                      static_cast<std::size_t>(P_.size() + P_inverse_.size()) * sizeof(int);
  return (dense_ ? dense_->bytes() : 0) + doubles * sizeof(double) + sparse;
}

}  // namespace nbm
