// The FreeFEM binding's Dirichlet conventions (plugin/freefem/dirichlet.hpp):
// the dofs of on()'s default tgv = 1e30 join `fixed`, and the row on() with
// tgv = -2 leaves in K is reported. Plain C++ on CooMatrix arrays, so tested
// here; the FreeFEM scripts check the same through the plugin
// (tests/scripts/bad-input: valid-tgv, k-tgv-minus2).
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "dirichlet.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm::CooMatrix;
using nbm_binding::check_tgv_minus2;
using nbm_binding::dirichlet_dofs;
using nbm_binding::tgv_dofs;

TEST(BindingDirichlet, TgvDiagonalsOfKOrMAreFound) {
  const nbm_test::Bar b;
  auto a = assemble(b);
  a.K.coeffRef(3, 3) = 1e30;
  a.M.coeffRef(7, 7) = -1e30;
  a.K.coeffRef(9, 9) = 9e28;      // large, but below FreeFEM's tgv
  a.K.coeffRef(5, 5) = INFINITY;  // an error for the core, not a tgv
  for (bool lower : {false, true}) {
    SCOPED_TRACE(lower ? "lower half" : "full storage");
    EXPECT_EQ(tgv_dofs(nbm_test::to_coo(a.M, lower), nbm_test::to_coo(a.K, lower)),
              (std::vector<long>{3, 7}));
  }
}

TEST(BindingDirichlet, DuplicateEntriesAreSummed) {
  const auto a = assemble(nbm_test::Bar{});
  CooMatrix K = nbm_test::to_coo(a.K);
  for (double half : {5e29, 5e29}) {  // 1e30 split over two entries
    K.i.push_back(2);
    K.j.push_back(2);
    K.value.push_back(half);
  }
  EXPECT_EQ(tgv_dofs(nbm_test::to_coo(a.M), K), std::vector<long>{2});
}

TEST(BindingDirichlet, FixedAndTgvDofsAreMergedSortedUnique) {
  const nbm_test::Bar b;
  auto a = assemble(b);
  a.K.coeffRef(b.N, b.N) = 1e30;
  a.K.coeffRef(4, 4) = 1e30;
  EXPECT_EQ(dirichlet_dofs(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), {b.N, 6, 4, 6}),
            (std::vector<long>{4, 6, b.N}));
}

TEST(BindingDirichlet, RowOfTgvMinus2IsReportedUnlessFixed) {
  // on(..., tgv = -2) at the top end: row and column N of K zeroed, 1 on the
  // diagonal. The dof would be a unit spring, not clamped.
  const nbm_test::Bar b;
  const auto a = assemble(b);
  const CooMatrix M = nbm_test::to_coo(a.M);
  CooMatrix K = nbm_test::to_coo(a.K);
  for (std::size_t k = 0; k < K.value.size(); ++k) {
    if (K.i[k] == b.N || K.j[k] == b.N) K.value[k] = 0;
    if (K.i[k] == b.N && K.j[k] == b.N) K.value[k] = 1;
  }
  nbm_test::expect_throw_with<nbm::InputError>([&] { dirichlet_dofs(M, K, {}); },
                                               {"K: row " + std::to_string(b.N), "tgv = -2",
                                                "fixed="});
  EXPECT_NO_THROW(check_tgv_minus2(M, K, {b.N}));  // declared fixed: fine
  EXPECT_NO_THROW(check_tgv_minus2(M, nbm_test::to_coo(a.K), {}));
  // tgv = -1 zeroes the row only: not this diagnosis (the core reports the
  // asymmetry).
  CooMatrix K_row = nbm_test::to_coo(a.K);
  for (std::size_t k = 0; k < K_row.value.size(); ++k)
    if (K_row.i[k] == b.N) K_row.value[k] = K_row.j[k] == b.N ? 1 : 0;
  EXPECT_NO_THROW(check_tgv_minus2(M, K_row, {}));
}

TEST(BindingDirichlet, MalformedMatricesAreLeftToTheCore) {
  // Non-square, mismatched sizes, entries outside the matrix: nothing thrown
  // or read out of bounds here; the core names the faulty matrix.
  const auto a = assemble(nbm_test::Bar{});
  CooMatrix M = nbm_test::to_coo(a.M), K = nbm_test::to_coo(a.K);
  M.rows = K.rows = 2 * M.rows;
  EXPECT_NO_THROW(dirichlet_dofs(M, K, {-1, 1000}));
  CooMatrix bad = nbm_test::to_coo(a.K);
  bad.i[3] = bad.rows;
  bad.value.pop_back();
  EXPECT_NO_THROW(dirichlet_dofs(nbm_test::to_coo(a.M), bad, {}));
}

}  // namespace
