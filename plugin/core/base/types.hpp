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

}  // namespace nbm
