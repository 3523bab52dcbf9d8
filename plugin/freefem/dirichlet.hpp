// FreeFEM's Dirichlet conventions, translated for the core, which knows only
// the `fixed` dofs of SolverOptions. Plain C++ on the CooMatrix arrays the
// binding builds from FreeFEM's matrices: neither FreeFEM nor Eigen, so that
// the tests and the fuzz targets can include it too.
#pragma once

#include <vector>

#include "linalg/coo_matrix.hpp"

namespace nbm_binding {

/// Dofs carrying FreeFEM's default Dirichlet penalty (`on(...)` with
/// tgv = 1e30) on the diagonal of K or M: finite diagonals with
/// |a| >= 1e29 (duplicate entries summed). Sorted.
std::vector<long> tgv_dofs(const nbm::CooMatrix& M, const nbm::CooMatrix& K);

/// on(...) with tgv = -2 zeroes the row and column of a Dirichlet dof of K and
/// puts 1 on its diagonal: the dof is then a unit spring, not clamped, and
/// nothing in K alone says so. Throws nbm::InputError naming K for a row and
/// column of K holding only a unit diagonal while M couples the dof, unless
/// it is in `fixed`. Matrices of wrong or different sizes are left to the core.
void check_tgv_minus2(const nbm::CooMatrix& M, const nbm::CooMatrix& K,
                      const std::vector<long>& fixed);

/// The Dirichlet dofs to hand to the core: `fixed` (the user's fixed=) and
/// tgv_dofs(M, K), sorted, unique; after check_tgv_minus2.
std::vector<long> dirichlet_dofs(const nbm::CooMatrix& M, const nbm::CooMatrix& K,
                                 std::vector<long> fixed);

}  // namespace nbm_binding
