// The lowest eigenpairs of a sparse pencil (linalg/sparse_eigen.hpp) against
// the closed form of the P1 bar fixed at both ends: with N elements of
// length h = 1/N, K = tridiag(-1, 2, -1) / h and M = h tridiag(1, 4, 1) / 6
// on the N - 1 inner nodes have the eigenvalues
//     lambda_k = (6 / h^2) (1 - cos(k pi h)) / (2 + cos(k pi h)),  k = 1 .. N - 1,
// with the eigenvectors sin(k pi x_i) (the discrete sine transform).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/errors.hpp"
#include "linalg/sparse_eigen.hpp"

namespace {

using nbm::Index;
using nbm::Matrix;
using nbm::SparseMatrix;
using nbm::Vector;

struct Bar {
  SparseMatrix K, M;
  double h;
  explicit Bar(int N) : h(1.0 / N) {
    const Index n = N - 1;
    std::vector<nbm::Triplet> k, m;
    for (Index i = 0; i < n; ++i) {
      k.emplace_back(i, i, 2 / h), m.emplace_back(i, i, 4 * h / 6);
      if (i + 1 < n) {
        k.emplace_back(i, i + 1, -1 / h), k.emplace_back(i + 1, i, -1 / h);
        m.emplace_back(i, i + 1, h / 6), m.emplace_back(i + 1, i, h / 6);
      }
    }
    K.resize(n, n), M.resize(n, n);
    K.setFromTriplets(k.begin(), k.end());
    M.setFromTriplets(m.begin(), m.end());
  }
  double lambda(int k) const {
    const double c = std::cos(k * M_PI * h);
    return 6 / (h * h) * (1 - c) / (2 + c);
  }
};

// Both paths: Lanczos (12 of 399) and the dense solver (150 of 399, too
// many for a Krylov space much smaller than the pencil).
TEST(LowestEigenpairs, MatchTheFixedBarsClosedForm) {
  const Bar bar(400);
  const auto K_inverse = nbm::make_cholesky_inverse(bar.K, "K");
  for (Index count : {1, 12, 150}) {
    const nbm::SymmetricEigen e = nbm::lowest_eigenpairs(bar.K, bar.M, *K_inverse, count);
    ASSERT_EQ(e.values.size(), count);
    ASSERT_EQ(e.vectors.cols(), count);
    for (Index k = 0; k < count; ++k) {
      const double exact = bar.lambda(static_cast<int>(k) + 1);
      EXPECT_NEAR(e.values(k), exact, 1e-10 * exact) << count << " " << k;
      // The eigenvector is the sine of its mode (up to sign and scale).
      const Vector v = e.vectors.col(k);
      Vector s(v.size());
      for (Index i = 0; i < s.size(); ++i) s(i) = std::sin((k + 1) * M_PI * (i + 1) * bar.h);
      const double cosine = std::abs(v.dot(s)) / (v.norm() * s.norm());
      EXPECT_NEAR(cosine, 1, 1e-10) << count << " " << k;
    }
    const Matrix G = e.vectors.transpose() * (bar.M * e.vectors);
    EXPECT_LT((G - Matrix::Identity(count, count)).cwiseAbs().maxCoeff(), 1e-10) << count;
  }
}

TEST(LowestEigenpairs, RejectsACountOutOfRange) {
  const Bar bar(20);
  const auto K_inverse = nbm::make_cholesky_inverse(bar.K, "K");
  EXPECT_THROW(nbm::lowest_eigenpairs(bar.K, bar.M, *K_inverse, 0), nbm::InputError);
  EXPECT_THROW(nbm::lowest_eigenpairs(bar.K, bar.M, *K_inverse, 20), nbm::InputError);
  EXPECT_EQ(nbm::lowest_eigenpairs(bar.K, bar.M, *K_inverse, 19).values.size(), 19);
}

}  // namespace
