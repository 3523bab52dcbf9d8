// Common linear-algebra types of the nbm core.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace nbm {

using Index = Eigen::Index;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

/// Relative tolerance of the symmetry checks of assembled matrices (M, K, the
/// damping C): assembly in double precision leaves them symmetric to a few
/// ulps.
inline constexpr double kSymmetryTolerance = 1e-10;

}  // namespace nbm
