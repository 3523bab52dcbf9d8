// The dense kernels of the contact linear algebra (issue 14) against
// independent dense computations on random problems: the Gram matrix Y^T Y
// of a sparse Y (blocked rank-k updates), the one-set constrained solve, the
// principal-block factors of the LCP and the open blocks (sparse and dense),
// and the byte bound of the per-active-set caches.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "linalg/active_set.hpp"
#include "linalg/constrained_solver.hpp"
#include "linalg/gram.hpp"
#include "linalg/principal_block.hpp"
#include "linalg/schur_factor.hpp"
#include "linalg/spd_inverse.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm::Index;
using nbm_test::Mat;
using nbm_test::Vec;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Random sparse n x m matrix shaped like L^-1 P B: column j is nonzero on a
// random "path" of rows from a random start to the end (so the last rows are
// reached by nearly every column), thinned at `keep`, with a few empty rows
// and a few isolated entries.
Sparse path_like(Index n, Index m, double keep, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  std::vector<Eigen::Triplet<double, int>> t;
  for (Index j = 0; j < m; ++j) {
    const Index start = static_cast<Index>(U(rng) * n);
    for (Index i = start; i < n; ++i)
      if (i % 7 != 3 && U(rng) < keep) t.emplace_back(i, j, N(rng));
    t.emplace_back(static_cast<Index>(U(rng) * n), j, N(rng));  // duplicates sum
  }
  Sparse Y(n, m);
  Y.setFromTriplets(t.begin(), t.end());
  return Y;
}

TEST(DenseKernels, GramOfSparseRowsMatchesDenseProduct) {
  std::mt19937 rng(14);
  // Shapes: tall and thin, wide (the top rows are a dense block wider than
  // half of W: the in-place path), very sparse (compact blocks), one row.
  const struct {
    Index n, m;
    double keep;
  } shapes[] = {{400, 30, 0.5}, {300, 120, 0.9}, {2000, 80, 0.02}, {1, 9, 1.0}, {5000, 40, 0.3}};
  for (const auto& s : shapes) {
    const Sparse Y = path_like(s.n, s.m, s.keep, rng);
    const Mat W = nbm::inner_products(Y);
    const Mat Yd = Mat(Y);
    const Mat W_ref = Yd.transpose() * Yd;
    ASSERT_EQ(W.rows(), s.m);
    ASSERT_EQ(W.cols(), s.m);
    const double scale = std::max(1.0, W_ref.cwiseAbs().maxCoeff());
    EXPECT_LE((W - W_ref).cwiseAbs().maxCoeff(), 1e-13 * scale) << s.n << "x" << s.m;
    EXPECT_EQ(W, W.transpose()) << "symmetric to the last bit";
  }
  EXPECT_EQ(nbm::inner_products(Sparse(50, 0)).size(), 0);
}

TEST(DenseKernels, GramSpansSeveralBlocksAtLargeSizes) {
  // More rows than one dense block holds (2^21 entries): the runs are cut
  // by size, and their sum must still be Y^T Y.
  std::mt19937 rng(15);
  const Sparse Y = path_like(40000, 120, 0.8, rng);
  const Mat Yd = Mat(Y);
  const Mat W_ref = Yd.transpose() * Yd;
  const Mat W = nbm::inner_products(Y);
  EXPECT_LE((W - W_ref).cwiseAbs().maxCoeff(), 1e-12 * W_ref.cwiseAbs().maxCoeff());
}

TEST(DenseKernels, GramAccumulatorTakesLargeBlocksInChunks) {
  // Dense blocks larger than one run (2^21 entries) are applied at once, in
  // chunks of rows: over all of W's columns, over most of them (scattered
  // into W's width), and over few of them (a separate product), each
  // against the dense product; blocks and rows mix in one accumulator.
  std::mt19937 rng(16);
  const Index m = 3000;
  std::vector<int> all(m), most, few;
  for (int c = 0; c < m; ++c) {
    all[c] = c;
    if (c % 5 != 2) most.push_back(c);
    if (c % 7 == 0) few.push_back(c);
  }
  nbm::GramAccumulator accumulator(m);
  Mat W_ref = Mat::Zero(m, m);
  auto add = [&](Index rows, const std::vector<int>& columns) {
    const Mat D = Mat::Random(rows, static_cast<Index>(columns.size()));
    accumulator.add(D, columns);
    Mat wide = Mat::Zero(rows, m);
    for (std::size_t c = 0; c < columns.size(); ++c) wide.col(columns[c]) = D.col(c);
    W_ref += wide.transpose() * wide;
  };
  add(800, all);   // 2.4e6 entries
  add(900, most);  // 2.2e6
  add(5, few);     // small: into a run
  add(4000, few);  // 1.7e6: a run of its own
  add(3, most);
  const Mat W = accumulator.finish();
  EXPECT_LE((W - W_ref).cwiseAbs().maxCoeff(), 1e-12 * W_ref.cwiseAbs().maxCoeff());
  EXPECT_EQ(W, W.transpose()) << "symmetric to the last bit";
}

// A 3D grid Laplacian with three components per node (the sparsity of a P1
// elasticity matrix on nx x ny x nz nodes), shifted to be well conditioned.
Sparse grid_3d(int nx, int ny, int nz) {
  auto node = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double, int>> t;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int c = 0; c < 3; ++c) {
          const int a = 3 * node(i, j, k) + c;
          t.emplace_back(a, a, 6.5 + c);
          auto couple = [&](int i2, int j2, int k2) {
            if (i2 >= nx || j2 >= ny || k2 >= nz) return;
            const int b = 3 * node(i2, j2, k2) + c;
            t.emplace_back(a, b, -1.0);
            t.emplace_back(b, a, -1.0);
          };
          couple(i + 1, j, k);
          couple(i, j + 1, k);
          couple(i, j, k + 1);
        }
  Sparse A(3 * nx * ny * nz, 3 * nx * ny * nz);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(DenseKernels, SupernodalForwardMatchesDenseSubstitutions) {
  // Y = L^-1 P B by the supernodal forward substitutions against one dense
  // forward substitution per column, on a 3D grid (separators of hundreds of
  // rows, reached by every column) with the constraint columns of a face
  // (unit columns and the matrix's own columns of the face's dofs), a
  // column with entries far apart (several supernodes start it), an empty
  // column, and W = Y^T Y against the dense Gram matrix.
  const Sparse A = grid_3d(14, 14, 5);
  const Index n = A.rows();
  std::vector<Index> face;
  for (Index node = 0; node < 14 * 14; node += 2) face.push_back(3 * node + 2);
  const Index m = 2 * static_cast<Index>(face.size()) + 2;
  Mat Bd = Mat::Zero(n, m);
  for (std::size_t k = 0; k < face.size(); ++k) {
    Bd.col(k) = Mat(A.col(face[k]));
    Bd(face[k], face.size() + k) = 1.0;
  }
  Bd(5, m - 2) = 1.5;
  Bd(n - 7, m - 2) = -2.0;  // m - 1: empty
  const Sparse B = Bd.sparseView();
  const auto inverse = nbm::make_cholesky_inverse(A, "A");
  Mat W;
  const Sparse Y = inverse->forward(B, &W);
  ASSERT_EQ(Y.rows(), n);
  ASSERT_EQ(Y.cols(), m);
  for (Index j = 0; j < m; ++j) {
    Vec b = Bd.col(j);
    inverse->forward_in_place(b);
    const Vec y = Mat(Y.col(j));
    EXPECT_LE((y - b).cwiseAbs().maxCoeff(), 1e-13 * std::max(1.0, b.cwiseAbs().maxCoeff()))
        << "column " << j;
  }
  EXPECT_EQ(Y.col(m - 1).nonZeros(), 0);
  for (Index j = 0; j < m; ++j)
    for (Sparse::InnerIterator it(Y, j); it; ++it) ASSERT_NE(it.value(), 0.0) << "exact zeros left out";
  Mat X_inv_B = Bd;
  inverse->solve_in_place(X_inv_B);
  const Mat W_ref = Bd.transpose() * X_inv_B;
  EXPECT_LE((W - W_ref).cwiseAbs().maxCoeff(), 1e-12 * W_ref.cwiseAbs().maxCoeff());
  EXPECT_EQ(W, W.transpose());
  EXPECT_EQ(inverse->gram(B), W);
}

// A random constraint basis: sparse "stiffness" columns, unit columns.
Mat random_basis(Index n, Index nc, std::mt19937& rng) {
  Mat Bd = Mat::Zero(n, 2 * nc);
  std::uniform_int_distribution<Index> row(0, n - 1);
  for (Index k = 0; k < nc; ++k) {
    for (int e = 0; e < 4; ++e) Bd(row(rng), k) = 100 * nbm_test::random_vector(1, rng)(0);
    Bd(k, k) += 400;
    Bd(k, nc + k) = 1.0;
  }
  return Bd;
}

TEST(DenseKernels, ConstrainedSolverOnSweepingSetsMatchesDenseKkt) {
  // Every path of ConstrainedSolver::schur, each solve against the dense KKT
  // system. A contact front sweeping 32 nodes, with a second node ahead of it
  // now and then: the bases are blocks of 2 nodes, closed when both are, so
  // each set is its base (fresh) or differs from it at 1 or 2 <= 32 / 8
  // nodes (bordered). Then every other node closed (16 changes from the
  // all-open base: fresh, not a base), all closed (a new base: the bordered
  // factors are dropped), and the first set again (bordered anew).
  std::mt19937 rng(18);
  const Index n = 120, nc = 32;
  const Mat X = nbm_test::random_spd(static_cast<int>(n), 1e3, rng);
  const Mat Bd = random_basis(n, nc, rng);
  const Sparse B = Bd.sparseView();
  const nbm::ConstrainedSolver solver(nbm::make_cholesky_inverse(X.sparseView(), "X"), B);
  nbm::ActiveSet active(nc, false);
  std::vector<nbm::ActiveSet> sets;
  for (Index k = 0; k < 6; ++k) {
    active[k] = true;
    sets.push_back(active);
    if (k % 2 == 1) {
      active[k + 10] = true;
      sets.push_back(active);
    }
  }
  nbm::ActiveSet alternating(nc);
  for (Index k = 0; k < nc; ++k) alternating[k] = k % 2 == 1;
  sets.push_back(alternating);
  sets.push_back(nbm::ActiveSet(nc, true));
  sets.push_back(sets.front());  // again, from the cache
  for (const auto& set : sets) {
    const Vec r = nbm_test::random_vector(static_cast<int>(n), rng);
    const Vec h = nbm_test::random_vector(static_cast<int>(nc), rng);
    const Vec x_ref = nbm_test::kkt_solution(X, Bd, set, r, h);
    Vec x;
    solver.solve(set, r, h, x);
    EXPECT_LE((x - x_ref).cwiseAbs().maxCoeff(), 1e-9 * x_ref.cwiseAbs().maxCoeff());
  }
}

TEST(DenseKernels, OneSetConstrainedSolveMatchesDenseKkt) {
  // X x = r + G^T mu, G x = h with the rows of G chosen per node among the
  // columns of B = [B_open B_closed], against the dense KKT system.
  std::mt19937 rng(16);
  const int n = 40, nc = 6;
  const Mat X = nbm_test::random_spd(n, 1e3, rng);
  Mat Bd = Mat::Zero(n, 2 * nc);
  std::uniform_int_distribution<int> row(0, n - 1);
  for (int k = 0; k < nc; ++k) {
    for (int e = 0; e < 4; ++e) Bd(row(rng), k) = nbm_test::random_vector(1, rng)(0);
    Bd(3 * k + 1, nc + k) = 1.0;
  }
  const Sparse B = Bd.sparseView();
  const auto inverse = nbm::make_cholesky_inverse(X.sparseView(), "X");
  const Vec r = nbm_test::random_vector(n, rng), h = nbm_test::random_vector(nc, rng);
  for (const nbm::ActiveSet& active :
       {nbm::ActiveSet(nc, false), nbm::ActiveSet(nc, true),
        nbm::ActiveSet{true, false, false, true, true, false}}) {
    const Vec x_ref = nbm_test::kkt_solution(X, Bd, active, r, h);
    Vec x;
    nbm::solve_constrained_once(*inverse, B, active, r, h, x);
    EXPECT_LE((x - x_ref).cwiseAbs().maxCoeff(), 1e-10 * x_ref.cwiseAbs().maxCoeff());
    // and the solver that keeps W for every set agrees
    const nbm::ConstrainedSolver kept(nbm::make_cholesky_inverse(X.sparseView(), "X"), B);
    Vec y;
    kept.solve(active, r, h, y);
    EXPECT_LE((y - x_ref).cwiseAbs().maxCoeff(), 1e-10 * x_ref.cwiseAbs().maxCoeff());
  }
}

// Columns of a 2 n x 2 n W for a set: node k's first column k if open,
// n + k if closed.
std::vector<Index> columns_of(const std::vector<bool>& closed) {
  const Index n = static_cast<Index>(closed.size());
  std::vector<Index> c(n);
  for (Index k = 0; k < n; ++k) c[k] = closed[k] ? n + k : k;
  return c;
}

TEST(DenseKernels, BorderedSchurFactorSolvesAsADenseSolve) {
  // A fresh factor of a base set and factors bordered on it for sets that
  // differ at 1, 3 and 9 of 40 nodes, against dense solves of W[c, c], on a
  // W with the scale disparity of the constraint basis (stiffness rows and
  // unit rows: columns scaled by 1e4 and 1).
  std::mt19937 rng(17);
  const Index n = 40;
  Mat W = nbm_test::random_spd(2 * n, 1e4, rng);
  Vec scale = Vec::Ones(2 * n);
  scale.head(n).setConstant(1e4);
  W = scale.asDiagonal() * W * scale.asDiagonal();
  std::vector<bool> base_set(n);
  for (Index k = 0; k < n; ++k) base_set[k] = k % 3 == 0;
  const auto base = std::make_shared<const nbm::SchurFactor>(W, columns_of(base_set));
  EXPECT_TRUE(base->fresh());
  // The same columns are the base's own factor (the solver uses the base).
  EXPECT_THROW(nbm::SchurFactor(W, base->columns(), base), std::logic_error);
  for (int changes : {1, 3, 9}) {
    std::vector<bool> set = base_set;
    for (int i = 0; i < changes; ++i) set[(7 * i + 2) % n] = !set[(7 * i + 2) % n];
    const std::vector<Index> c = columns_of(set);
    EXPECT_EQ(nbm::SchurFactor::changes(c, base->columns()), changes);
    Mat S(n, n);
    for (Index a = 0; a < n; ++a)
      for (Index b = 0; b < n; ++b) S(a, b) = W(c[a], c[b]);
    const nbm::SchurFactor bordered(W, c, base);
    EXPECT_FALSE(bordered.fresh());
    for (int trial = 0; trial < 3; ++trial) {
      const Vec b = nbm_test::random_vector(n, rng);
      const Vec x_ref = S.fullPivLu().solve(b);
      Vec x = b;
      bordered.solve_in_place(x);
      // backward error of the solve, relative to |S| |x|
      const double residual = (S * x - b).cwiseAbs().maxCoeff();
      EXPECT_LE(residual, 1e-12 * S.cwiseAbs().maxCoeff() * x.cwiseAbs().maxCoeff())
          << changes << " changes";
      EXPECT_LE((x - x_ref).norm(), 1e-8 * x_ref.norm()) << changes << " changes";
    }
    // Bordered: 2 n r doubles and small ones, not n^2.
    if (changes > 0) {
      EXPECT_LT(bordered.bytes(), sizeof(double) * n * n);
    }
  }
}

// A random K_CC-like matrix: symmetric positive definite with the sparsity of
// a contact boundary, a band (nodes along an edge coupled to their
// neighbours) plus a few far couplings (a face's grid rows), entries of mixed
// signs and scales 1e4.
Mat sparse_spd(Index n, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1, 1);
  Mat A = Mat::Zero(n, n);
  auto couple = [&](Index i, Index j) {
    const double a = 1e4 * U(rng);
    A(i, j) += a;
    A(j, i) += a;
    A(i, i) += std::abs(a) * 1.01;  // diagonal dominance: definite
    A(j, j) += std::abs(a) * 1.01;
  };
  for (Index i = 0; i + 1 < n; ++i) couple(i, i + 1);
  for (Index i = 0; i + 7 < n; i += 5) couple(i, i + 7);
  for (Index i = 0; i < n; ++i) A(i, i) += 1e2 * (1 + U(rng));
  return A;
}

TEST(DenseKernels, OrderingForConstrainedSolvesShortensContactColumnsOfALongStrip) {
  // Issue 14's 2D strip in small (W/H = 80 as the benchmark's 2000 x 25
  // cells; 640 x 8 here): CHOLMOD's least-fill ordering is AMD, whose
  // elimination tree is nearly a path, so a bottom node's column of
  // Y = L^-1 P B reaches most later rows. The factor ordered for the
  // constrained solves (nested dissection, chosen because it at least halves
  // the step's cost) keeps those columns short, and its constrained
  // solutions are the plain factor's to round-off.
  nbm_test::Plate strip;
  strip.W = 80;
  strip.H = 1;
  strip.nx = 640;
  strip.ny = 8;
  const nbm_test::Simulation sim(nbm_test::assemble(strip), nbm_test::bottom_contact(strip, 0.0));
  const nbm::ContactProblem& problem = *sim.problem;
  const Sparse S = problem.M() + 1e-4 * problem.K();
  const Sparse& B = problem.constraint_basis();
  std::shared_ptr<const nbm::CholeskyInverse> plain = nbm::make_cholesky_inverse(S, "S");
  std::shared_ptr<const nbm::CholeskyInverse> ordered = nbm::make_cholesky_inverse(S, "S", B);
  const Index plain_entries = plain->forward(B).nonZeros();
  const Index ordered_entries = ordered->forward(B).nonZeros();
  EXPECT_LT(4 * ordered_entries, plain_entries);

  const nbm::ConstrainedSolver by_plain(plain, B), by_ordered(ordered, B);
  const Index nc = problem.n_contact();
  nbm::ActiveSet active(nc);
  for (Index k = 0; k < nc; ++k) active[k] = k < nc / 3;  // a front a third of the way
  std::mt19937 rng(41);
  const Vec r = nbm_test::random_vector(static_cast<int>(S.rows()), rng);
  const Vec h = nbm_test::random_vector(static_cast<int>(nc), rng);
  Vec x_plain, x_ordered;
  by_plain.solve(active, r, h, x_plain);
  by_ordered.solve(active, r, h, x_ordered);
  EXPECT_LE((x_ordered - x_plain).cwiseAbs().maxCoeff(), 1e-9 * x_plain.cwiseAbs().maxCoeff());
}

TEST(DenseKernels, PrincipalBlockFactorsSolveAsDenseSolves) {
  // Sparse factors (fill-reducing order) of principal blocks of a sparse
  // matrix, and dense ones of a dense matrix, against dense solves of the
  // blocks, on random free sets (all rows, none, every other, random); the
  // products with A and with its columns in a free set against dense ones.
  std::mt19937 rng(23);
  const Index n = 60;
  const Mat sparse = sparse_spd(n, rng), dense = nbm_test::random_spd(n, 1e4, rng);
  // The sparse matrix given dense and sparse: both kept sparse.
  const nbm::PrincipalBlocks sparse_blocks(sparse), sparse_given_sparse(Sparse(sparse.sparseView())),
      dense_blocks(dense), dense_given_sparse(Sparse(dense.sparseView()));
  EXPECT_TRUE(sparse_blocks.sparse());
  EXPECT_TRUE(sparse_given_sparse.sparse());
  EXPECT_FALSE(dense_blocks.sparse());
  EXPECT_FALSE(dense_given_sparse.sparse());
  EXPECT_EQ(sparse_blocks.max_abs(), sparse.cwiseAbs().maxCoeff());
  EXPECT_EQ(dense_given_sparse.max_abs(), dense.cwiseAbs().maxCoeff());
  std::bernoulli_distribution coin(0.5);
  const std::pair<const nbm::PrincipalBlocks*, const Mat*> cases[] = {
      {&sparse_blocks, &sparse}, {&sparse_given_sparse, &sparse}, {&dense_blocks, &dense},
      {&dense_given_sparse, &dense}};
  for (const auto& [blocks, matrix] : cases) {
    const Mat& A = *matrix;
    ASSERT_EQ(blocks->size(), n);
    // y += A x against the dense product.
    const Vec x = nbm_test::random_vector(n, rng);
    Vec y = nbm_test::random_vector(n, rng);
    const Vec y_ref = y + A * x;
    blocks->add_product(x, y);
    EXPECT_LE((y - y_ref).cwiseAbs().maxCoeff(), 1e-12 * y_ref.cwiseAbs().maxCoeff());
    for (int trial = 0; trial < 6; ++trial) {
      std::vector<Index> F;
      for (Index i = 0; i < n; ++i)
        if (trial == 0 || (trial == 2 && i % 2 == 0) || (trial > 2 && coin(rng))) F.push_back(i);
      // y += A[:, F] x_F against the dense product with x zeroed off F.
      Vec x_F = Vec::Zero(n);
      for (Index i : F) x_F(i) = x(i);
      Vec y_F = y;
      const Vec y_F_ref = y + A * x_F;
      blocks->add_columns_product(F, x_F, y_F);
      EXPECT_LE((y_F - y_F_ref).cwiseAbs().maxCoeff(), 1e-12 * y_F_ref.cwiseAbs().maxCoeff())
          << "trial " << trial;
      const nbm::PrincipalBlockFactor factor(*blocks, F);
      ASSERT_TRUE(factor.positive_definite());
      const Index m = static_cast<Index>(F.size());
      Mat AFF(m, m);
      for (Index a = 0; a < m; ++a)
        for (Index b = 0; b < m; ++b) AFF(a, b) = A(F[a], F[b]);
      const Vec b = nbm_test::random_vector(m, rng);
      Vec z = b;
      factor.solve_in_place(z);
      if (m == 0) continue;
      const Vec z_ref = AFF.fullPivLu().solve(b);
      EXPECT_LE((z - z_ref).norm(), 1e-10 * z_ref.norm()) << "trial " << trial;
      EXPECT_LE((AFF * z - b).cwiseAbs().maxCoeff(),
                1e-12 * AFF.cwiseAbs().maxCoeff() * z.cwiseAbs().maxCoeff());
    }
  }
  // A sparse factor holds about its fill (a band: O(n)), not n^2 doubles.
  std::vector<Index> all(n);
  for (Index i = 0; i < n; ++i) all[i] = i;
  EXPECT_LT(nbm::PrincipalBlockFactor(sparse_blocks, all).bytes(), sizeof(double) * n * n / 2);
  // An indefinite block is reported, not factored.
  Mat indefinite = sparse;
  indefinite(3, 3) = -1e6;
  EXPECT_FALSE(nbm::PrincipalBlockFactor(nbm::PrincipalBlocks(indefinite), all).positive_definite());
  EXPECT_TRUE(nbm::PrincipalBlockFactor(nbm::PrincipalBlocks(indefinite), {0, 1, 2, 4})
                  .positive_definite());
}

TEST(DenseKernels, DenseCholeskySolvesAsADenseSolveAndReportsBadMatrices) {
  // The in-place factor against a dense solve, at sizes on both sides of
  // the switch from Eigen's factorization to LAPACK's, with a garbage upper
  // triangle (only the lower one is read); an indefinite matrix and a
  // non-finite entry are reported by both.
  std::mt19937 rng(24);
  for (const int n : {1, 7, 130, 600}) {
    const Mat A = nbm_test::random_spd(n, 1e6, rng);
    Mat lower = A;
    lower.triangularView<Eigen::StrictlyUpper>().setConstant(std::nan(""));
    const nbm::DenseCholesky factor(std::move(lower));
    ASSERT_TRUE(factor.positive_definite()) << n;
    EXPECT_EQ(factor.size(), n);
    const Mat B = Mat::Random(n, 3);
    Mat X = B;
    factor.solve_in_place(X);
    EXPECT_LE((A * X - B).cwiseAbs().maxCoeff(), 1e-8 * A.cwiseAbs().maxCoeff() * X.cwiseAbs().maxCoeff()) << n;
    EXPECT_LE((X - A.llt().solve(B)).norm(), 1e-8 * X.norm()) << n;
  }
  for (const int n : {50, 200}) {  // Eigen's factorization, LAPACK's
    Mat indefinite = nbm_test::random_spd(n, 10, rng);
    indefinite(20, 20) = -100;
    EXPECT_FALSE(nbm::DenseCholesky(std::move(indefinite)).positive_definite()) << n;
    Mat not_finite = nbm_test::random_spd(n, 10, rng);
    not_finite(30, 10) = std::nan("");
    EXPECT_FALSE(nbm::DenseCholesky(std::move(not_finite)).positive_definite()) << n;
  }
  EXPECT_TRUE(nbm::DenseCholesky(Mat(0, 0)).positive_definite());  // empty: nothing to fail
  EXPECT_EQ(nbm::DenseCholesky(Mat(0, 0)).size(), 0);
}

// A factor of a k x k matrix: 8 k^2 bytes.
nbm::DenseCholesky factor_of_size(Index k) { return nbm::DenseCholesky(Mat::Identity(k, k)); }

nbm::ActiveSet set_number(int i) {
  nbm::ActiveSet s(16);
  for (int b = 0; b < 16; ++b) s[b] = (i >> b) & 1;
  return s;
}

TEST(DenseKernels, ActiveSetCacheStaysWithinItsByteBudget) {
  // 100 x 100 factors hold 80 kB each: a budget of 1 MB keeps 12 of them
  // (with their keys), never more bytes than the budget.
  const std::size_t budget = 1000000;
  nbm::ActiveSetCache<nbm::DenseCholesky> cache(budget);
  int made = 0;
  auto make = [&] {
    ++made;
    return factor_of_size(100);
  };
  for (int i = 0; i < 40; ++i) {
    cache.get(set_number(i), make);
    EXPECT_LE(cache.bytes(), budget);
  }
  EXPECT_EQ(made, 40);
  // Full up to one entry: each holds its 80 kB factor and less than 1 kB more.
  EXPECT_GE(cache.size(), budget / (8 * 100 * 100 + 1000));
  EXPECT_LE(cache.size(), budget / (8 * 100 * 100));
  EXPECT_GT(cache.bytes() + 8 * 100 * 100 + 1000, budget);
  ASSERT_EQ(cache.size(), 12u);  // the sequence below keeps sets 28..39
  // Least recently used evicted: touch the oldest kept set (28), add one:
  // 29 is dropped, 28 kept.
  cache.get(set_number(28), make);
  EXPECT_EQ(made, 40);
  cache.get(set_number(40), make);
  EXPECT_EQ(made, 41);
  cache.get(set_number(28), make);
  EXPECT_EQ(made, 41);
  cache.get(set_number(29), make);
  EXPECT_EQ(made, 42);
}

TEST(DenseKernels, ActiveSetCacheKeepsAtMostItsBoundOnEntries) {
  // Small factors far below the byte budget: the bound on entries decides
  // (memory flat on long runs), least recently used first.
  nbm::ActiveSetCache<nbm::DenseCholesky> cache(std::size_t(1) << 30, 5);
  int made = 0;
  auto make = [&] {
    ++made;
    return factor_of_size(3);
  };
  for (int i = 0; i < 20; ++i) {
    cache.get(set_number(i), make);
    EXPECT_LE(cache.size(), 5u);
  }
  EXPECT_EQ(cache.size(), 5u);
  cache.get(set_number(15), make);  // the oldest kept, now the newest
  cache.get(set_number(20), make);  // drops 16
  EXPECT_EQ(made, 21);
  cache.get(set_number(15), make);
  EXPECT_EQ(made, 21);
  cache.get(set_number(16), make);
  EXPECT_EQ(made, 22);
}

TEST(DenseKernels, ActiveSetCacheKeepsAFactorLargerThanItsBudget) {
  // The entry just made is what the caller uses: kept even alone above the
  // budget, and the only one kept.
  nbm::ActiveSetCache<nbm::DenseCholesky> cache(1000);
  const auto& f = cache.get(set_number(1), [] { return factor_of_size(50); });
  EXPECT_EQ(f.size(), 50);
  EXPECT_EQ(cache.size(), 1u);
  cache.get(set_number(2), [] { return factor_of_size(50); });
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_GT(cache.bytes(), cache.budget());
}

}  // namespace
