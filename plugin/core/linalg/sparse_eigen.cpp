#include "linalg/sparse_eigen.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include "base/errors.hpp"

namespace nbm {
namespace {

// Spectra's shift-invert operator y = (K - sigma M)^-1 x at the one shift
// used here, sigma = 0: a solve with the factor of K.
class FactorInverse {
 public:
  using Scalar = double;
  explicit FactorInverse(const SpdInverse& K_inverse) : K_inverse_(K_inverse) {}
  Index rows() const { return K_inverse_.size(); }
  Index cols() const { return K_inverse_.size(); }
  void set_shift(double sigma) {
    if (sigma != 0) throw NumericalError("lowest eigenpairs: the factor is K's (shift 0)");
  }
  void perform_op(const double* x, double* y) const {
    Vector v = Eigen::Map<const Vector>(x, rows());
    K_inverse_.solve_in_place(v);
    Eigen::Map<Vector>(y, rows()) = v;
  }

 private:
  const SpdInverse& K_inverse_;
};

}  // namespace

SymmetricEigen lowest_eigenpairs(const SparseMatrix& K, const SparseMatrix& M,
                                 const SpdInverse& K_inverse, Index count) {
  const Index n = K.rows();
  if (count < 1 || count > n)
    throw InputError("lowest eigenpairs: " + std::to_string(count) + " wanted of a pencil of size " +
                     std::to_string(n));
  // Lanczos keeps ncv > count vectors: 2 count + 20 converge in few restarts.
  const Index ncv = 2 * count + 20;
  if (ncv >= n / 2) {
    SymmetricEigen dense = generalized_symmetric_eigen(Matrix(K), Matrix(M));
    if (!dense.ok) throw NumericalError("lowest eigenpairs: the dense eigenvalue solver failed");
    dense.values.conservativeResize(count);
    dense.vectors.conservativeResize(n, count);
    return dense;
  }
  using MassProduct = Spectra::SparseSymMatProd<double, Eigen::Lower, Eigen::ColMajor, int>;
  FactorInverse op(K_inverse);
  MassProduct mass(M);
  Spectra::SymGEigsShiftSolver<FactorInverse, MassProduct, Spectra::GEigsMode::ShiftInvert> eigs(
      op, mass, count, ncv, 0.0);
  eigs.init();  // a fixed starting vector: the same pairs on every run
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw NumericalError("lowest eigenpairs: Lanczos (shift-invert) did not converge for " +
                         std::to_string(count) + " pairs of a pencil of size " + std::to_string(n));
  // Spectra orders the pairs by |1 / lambda|: the largest lambda first.
  const Vector values = eigs.eigenvalues();
  const Matrix vectors = eigs.eigenvectors();
  std::vector<Index> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return values(a) < values(b); });
  SymmetricEigen out;
  out.values.resize(count);
  out.vectors.resize(n, count);
  for (Index k = 0; k < count; ++k) {
    out.values(k) = values(order[k]);
    out.vectors.col(k) = vectors.col(order[k]);
  }
  return out;
}

}  // namespace nbm
