#include "linalg/dense_eigen.hpp"

#include <Eigen/Eigenvalues>

namespace nbm {

SymmetricEigen generalized_symmetric_eigen(const Matrix& K, const Matrix& M) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(K, M);
  if (eig.info() != Eigen::Success) return {Vector(), Matrix(), false};
  return {eig.eigenvalues(), eig.eigenvectors(), true};
}

SymmetricEigen symmetric_eigen(const Matrix& A) {
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(A);
  if (eig.info() != Eigen::Success) return {Vector(), Matrix(), false};
  return {eig.eigenvalues(), eig.eigenvectors(), true};
}

GeneralEigen general_eigen(const Matrix& A, bool with_vectors) {
  const Eigen::EigenSolver<Matrix> eig(A, with_vectors);
  if (eig.info() != Eigen::Success) return {ComplexVector(), ComplexMatrix(), false};
  return {eig.eigenvalues(), with_vectors ? ComplexMatrix(eig.eigenvectors()) : ComplexMatrix(),
          true};
}

}  // namespace nbm
