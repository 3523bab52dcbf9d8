// Dense eigenproblems of the periodic tools (the modes of a contact region,
// Floquet multipliers, the modes of the damped state-space flow): thin
// wrappers of Eigen's solvers, compiled once in dense_eigen.cpp. Each of
// Eigen's eigensolvers is thousands of lines of templates instantiated in
// every file that uses it (about 20 s of compilation each with the
// sanitizers); behind these functions it is compiled in one file.
#pragma once

#include "base/types.hpp"

namespace nbm {

using ComplexVector = Eigen::VectorXcd;
using ComplexMatrix = Eigen::MatrixXcd;

/// Eigenpairs of a symmetric problem; `ok` is false if the solver failed.
struct SymmetricEigen {
  Vector values;   ///< ascending
  Matrix vectors;  ///< columns; M-orthonormal for the generalized problem
  bool ok = true;
};
/// K x = lambda M x, K symmetric, M symmetric positive definite (lower
/// triangles read), by Eigen's GeneralizedSelfAdjointEigenSolver.
SymmetricEigen generalized_symmetric_eigen(const Matrix& K, const Matrix& M);
/// A x = lambda x, A symmetric (lower triangle read), by Eigen's
/// SelfAdjointEigenSolver.
SymmetricEigen symmetric_eigen(const Matrix& A);

/// Eigenpairs of a general real matrix, by Eigen's EigenSolver (values in
/// its order; vectors only if asked). `ok` is false if the solver failed.
struct GeneralEigen {
  ComplexVector values;
  ComplexMatrix vectors;
  bool ok = true;
};
GeneralEigen general_eigen(const Matrix& A, bool with_vectors);

}  // namespace nbm
