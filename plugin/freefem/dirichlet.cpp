#include "dirichlet.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "base/errors.hpp"

namespace nbm_binding {
namespace {

// FreeFEM's default tgv is 1e30; any diagonal this large is a penalty.
constexpr double kTgvThreshold = 1e29;

struct Entry {
  long i, j;
  double value;
};

// The entries of A inside the matrix, both triangles for a lower-half
// storage, sorted by (row, column) with duplicates summed. Entries outside
// the matrix are the core's to report.
std::vector<Entry> merged_entries(const nbm::CooMatrix& A) {
  std::vector<Entry> e;
  const std::size_t n = std::min({A.i.size(), A.j.size(), A.value.size()});
  e.reserve(n * (A.lower_half ? 2 : 1));
  for (std::size_t k = 0; k < n; ++k) {
    const long i = A.i[k], j = A.j[k];
    if (i < 0 || i >= A.rows || j < 0 || j >= A.cols) continue;
    e.push_back({i, j, A.value[k]});
    if (A.lower_half && i != j) e.push_back({j, i, A.value[k]});
  }
  std::sort(e.begin(), e.end(),
            [](const Entry& a, const Entry& b) { return std::tie(a.i, a.j) < std::tie(b.i, b.j); });
  std::vector<Entry> merged;
  for (const Entry& x : e)
    if (!merged.empty() && merged.back().i == x.i && merged.back().j == x.j)
      merged.back().value += x.value;
    else
      merged.push_back(x);
  return merged;
}

}  // namespace

std::vector<long> tgv_dofs(const nbm::CooMatrix& M, const nbm::CooMatrix& K) {
  std::vector<long> dofs;
  for (const nbm::CooMatrix* A : {&K, &M})
    for (const Entry& x : merged_entries(*A))
      // inf is an error (the core reports it), not a tgv
      if (x.i == x.j && std::isfinite(x.value) && std::abs(x.value) >= kTgvThreshold)
        dofs.push_back(x.i);
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

void check_tgv_minus2(const nbm::CooMatrix& M, const nbm::CooMatrix& K,
                      const std::vector<long>& fixed) {
  const long n = K.rows;
  if (K.cols != n || M.rows != n || M.cols != n) return;  // the core reports the sizes
  std::vector<char> is_fixed(n, 0);
  for (long f : fixed)
    if (f >= 0 && f < n) is_fixed[f] = 1;  // out of range: the core reports it
  // Row and column: with tgv = -1 only the row is zeroed, which leaves K
  // non-symmetric, as the core reports.
  std::vector<int> k_row_entries(n, 0), k_col_entries(n, 0), m_off_diagonal(n, 0);
  std::vector<double> k_diagonal(n, 0.0);
  for (const Entry& x : merged_entries(K))
    if (x.value != 0.0) {
      ++k_row_entries[x.i];
      ++k_col_entries[x.j];
      if (x.i == x.j) k_diagonal[x.i] = x.value;
    }
  for (const Entry& x : merged_entries(M))
    if (x.value != 0.0 && x.i != x.j) ++m_off_diagonal[x.i];
  for (long i = 0; i < n; ++i)
    if (!is_fixed[i] && k_row_entries[i] == 1 && k_col_entries[i] == 1 && k_diagonal[i] == 1.0 &&
        m_off_diagonal[i] > 0)
      throw nbm::InputError("K: row " + std::to_string(i) +
                            " holds only a unit diagonal, as on() with tgv = -2 leaves a "
                            "Dirichlet dof; such a dof is not held at zero: assemble K with the "
                            "default tgv or list the dof in fixed=");
}

std::vector<long> dirichlet_dofs(const nbm::CooMatrix& M, const nbm::CooMatrix& K,
                                 std::vector<long> fixed) {
  check_tgv_minus2(M, K, fixed);
  for (long f : tgv_dofs(M, K)) fixed.push_back(f);
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  return fixed;
}

}  // namespace nbm_binding
