#include "dense_cholesky.hpp"

extern "C" void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);

namespace nbm {

DenseCholesky::DenseCholesky(Matrix&& A) : L_(std::move(A)) {
  const int n = static_cast<int>(L_.rows()), lda = std::max(1, n);
  int info = 0;
  if (n > 0) dpotrf_("L", &n, L_.data(), &lda, &info);
  // A non-finite entry spreads to the diagonal of the factor (the upper
  // triangle is not read: it may hold anything).
  positive_definite_ = info == 0 && L_.diagonal().allFinite();
}

}  // namespace nbm
