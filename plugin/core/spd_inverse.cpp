#include "spd_inverse.hpp"

#include <Eigen/CholmodSupport>
#include <string>

#include "errors.hpp"

namespace nbm {
namespace {

// Columns of B are pushed through X^{-1} in blocks, so that the dense
// workspace stays at n x kBlock whatever the number of columns.
constexpr Index kBlock = 64;

class CholeskyInverse final : public SpdInverse {
 public:
  CholeskyInverse(const SparseMatrix& X, const std::string& what) : n_(X.rows()) {
    llt_.compute(X);
    if (llt_.info() != Eigen::Success)
      throw NumericalError(what + " is not positive definite (Cholesky factorization failed)");
  }
  Index size() const override { return n_; }
  void solve_in_place(Matrix& x) const override { x = llt_.solve(x); }
  void solve_in_place(Vector& x) const override { x = llt_.solve(x); }

 private:
  Index n_;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
};

class DiagonalInverse final : public SpdInverse {
 public:
  explicit DiagonalInverse(Vector inv) : inv_(std::move(inv)) {}
  Index size() const override { return inv_.size(); }
  void solve_in_place(Matrix& x) const override { x = inv_.asDiagonal() * x; }
  void solve_in_place(Vector& x) const override { x = inv_.cwiseProduct(x); }
  Matrix gram(const SparseMatrix& B) const override {
    // Stays sparse: B^T D^{-1} B costs what B costs.
    const SparseMatrix DB = inv_.asDiagonal() * B;
    return Matrix(SparseMatrix(B.transpose()) * DB);
  }

 private:
  Vector inv_;
};

}  // namespace

Matrix SpdInverse::gram(const SparseMatrix& B) const {
  const Index m = B.cols();
  Matrix G(m, m);
  for (Index c0 = 0; c0 < m; c0 += kBlock) {
    const Index nc = std::min(kBlock, m - c0);
    Matrix Y = Matrix(B.middleCols(c0, nc));
    solve_in_place(Y);
    G.middleCols(c0, nc) = B.transpose() * Y;
  }
  return 0.5 * (G + G.transpose());  // symmetric to the last bit
}

std::unique_ptr<SpdInverse> make_cholesky_inverse(const SparseMatrix& X, const std::string& what) {
  return std::make_unique<CholeskyInverse>(X, what);
}

std::unique_ptr<SpdInverse> make_diagonal_inverse(const Vector& d, const std::string& what) {
  for (Index i = 0; i < d.size(); ++i)
    if (!(d(i) > 0))
      throw InputError(what + ": entry " + std::to_string(i) + " is " + std::to_string(d(i)) +
                       ", expected a positive lumped mass");
  return std::make_unique<DiagonalInverse>(d.cwiseInverse());
}

}  // namespace nbm
