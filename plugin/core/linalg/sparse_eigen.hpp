// The lowest eigenpairs of a sparse symmetric pencil K x = lambda M x, on a
// factor of K the caller already holds: Lanczos (Spectra) in shift-invert
// mode at 0, whose operator x -> K^-1 M x is one solve with that factor and
// one product with M per iteration.
#pragma once

#include "base/types.hpp"
#include "linalg/dense_eigen.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

/// The `count` lowest eigenpairs of K x = lambda M x, K positive definite
/// (K_inverse its inverse), M symmetric positive semi-definite: values
/// ascending, vectors M-orthonormal. Small pencils (count + 20 >= size / 2)
/// go to the dense solver instead. Throws InputError unless
/// 1 <= count <= size, NumericalError if Lanczos does not converge.
SymmetricEigen lowest_eigenpairs(const SparseMatrix& K, const SparseMatrix& M,
                                 const SpdInverse& K_inverse, Index count);

}  // namespace nbm
