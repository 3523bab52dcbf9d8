// nbm::LcpSolver against brute-force enumeration of complementary bases,
// residuals on large problems, warm starts, and error handling.
#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "linalg/lcp.hpp"
#include "test_util.hpp"

namespace {

using nbm::LcpSolver;
using nbm_test::Mat;
using nbm_test::Vec;

// Independent check of the LCP conditions: z >= 0, w = q + A z >= 0 and
// z_i w_i = 0, each relative to the scale of the data.
void expect_lcp_solution(const Mat& A, const Vec& q, const nbm::LcpResult& r, double tol) {
  const Vec w = q + A * r.z;
  const double zs = std::max(r.z.cwiseAbs().maxCoeff(), 1e-300);
  const double ws = std::max(q.cwiseAbs().maxCoeff(), (A * r.z).cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    EXPECT_GE(r.z(i), 0.0);
    EXPECT_GE(w(i), -tol * ws) << "i = " << i;
    EXPECT_LE(std::min(std::abs(r.z(i)) / zs, std::abs(w(i)) / ws), tol) << "i = " << i;
    // The reported active set is z = 0 and the reported w is q + A z.
    if (r.active[i]) {
      EXPECT_EQ(r.z(i), 0.0);
    }
    EXPECT_NEAR(r.w(i), w(i), tol * ws);
  }
}

// z and the brute-force z agree to `rel` relative to the larger of |z| and
// the natural scale |q| / |A| of a solution.
void expect_matches_brute_force(const Mat& A, const Vec& q, double rel) {
  const nbm::LcpResult r = LcpSolver::solve(A, q);
  const Vec z_ref = nbm_test::brute_force_lcp(A, q);
  const double scale = std::max(z_ref.cwiseAbs().maxCoeff(),
                                q.cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff());
  ASSERT_EQ(r.z.size(), q.size());
  EXPECT_LE((r.z - z_ref).cwiseAbs().maxCoeff(), rel * scale)
      << "n = " << q.size() << "\nz   = " << r.z.transpose() << "\nref = " << z_ref.transpose();
  EXPECT_GE(r.pivots, 1);
}

TEST(Lcp, MatchesBruteForceOnRandomSpdProblems) {
  // Sizes 1..12, many seeds, moderate conditioning: mixed active sets.
  for (int n = 1; n <= 12; ++n) {
    const int seeds = n <= 8 ? 30 : 6;
    for (int seed = 0; seed < seeds; ++seed) {
      std::mt19937 rng(1000 * n + seed);
      const Mat A = nbm_test::random_spd(n, 10.0, rng);
      const Vec q = nbm_test::random_vector(n, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", seed = " + std::to_string(seed));
      expect_matches_brute_force(A, q, 1e-10);
    }
  }
}

TEST(Lcp, MatchesBruteForceOnIllConditionedProblems) {
  // Condition numbers up to 1e5: the exact solution is still determined to
  // about cond * eps ~ 1e-11, within the 1e-10 asked for.
  for (double cond : {1e3, 1e4, 1e5}) {
    for (int n : {3, 6, 10}) {
      for (int seed = 0; seed < 6; ++seed) {
        std::mt19937 rng(7 * n + seed + int(cond));
        const Mat A = nbm_test::random_spd(n, cond, rng);
        const Vec q = nbm_test::random_vector(n, rng);
        SCOPED_TRACE("cond = " + std::to_string(cond) + ", n = " + std::to_string(n));
        expect_matches_brute_force(A, q, 1e-10);
      }
    }
  }
}

TEST(Lcp, MatchesBruteForceWithDegenerateRightHandSides) {
  // q with zeros: several complementary bases share the unique solution z.
  for (int n = 2; n <= 9; ++n) {
    for (int seed = 0; seed < 10; ++seed) {
      std::mt19937 rng(555 + 31 * n + seed);
      const Mat A = nbm_test::random_spd(n, 20.0, rng);
      Vec q = nbm_test::random_vector(n, rng);
      for (int i = 0; i < n; i += 2) q(i) = 0.0;
      SCOPED_TRACE("n = " + std::to_string(n) + ", seed = " + std::to_string(seed));
      expect_matches_brute_force(A, q, 1e-10);
    }
  }
  // q = 0 exactly: z = 0 is the solution, found at once from the closed start.
  std::mt19937 rng(3);
  const Mat A = nbm_test::random_spd(5, 10.0, rng);
  const nbm::LcpResult r = LcpSolver::solve(A, Vec::Zero(5));
  EXPECT_EQ(r.z.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(r.pivots, 1);
}

TEST(Lcp, MatchesBruteForceWithNearlyDuplicatedRows) {
  // A = B B^T + delta I where B has two almost equal rows: A has two nearly
  // equal rows and columns (condition ~ 1/delta), yet is positive definite.
  for (int n = 3; n <= 8; ++n) {
    for (int seed = 0; seed < 8; ++seed) {
      std::mt19937 rng(99 + 13 * n + seed);
      Mat B = nbm_test::random_orthogonal(n, rng);
      B.row(1) = B.row(0) + 1e-3 * B.row(1);
      const Mat A = B * B.transpose() + 1e-5 * Mat::Identity(n, n);
      const Vec q = nbm_test::random_vector(n, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", seed = " + std::to_string(seed));
      expect_matches_brute_force(A, q, 1e-10);
    }
  }
}

TEST(Lcp, RowsOfAFarLargerScaleDoNotLoosenTheOthers) {
  // Two rows with q_i = 1e9 and 1e10 (contact nodes far from the obstacle)
  // beside rows of scale 1e-3: the far rows stay open, and the others must be
  // the solution of their own sub-LCP to their own round-off (brute force on
  // the sub-problem), not merely to 1e-13 of the largest |q_i|, which would
  // accept sign errors of 1e-4 in them.
  for (int n = 4; n <= 12; ++n) {
    for (int seed = 0; seed < 10; ++seed) {
      std::mt19937 rng(7000 * n + seed);
      const Mat A = nbm_test::random_spd(n, 20.0, rng);
      Vec q = 1e-3 * nbm_test::random_vector(n, rng);
      const std::vector<int> far = {1, n - 1};
      q(far[0]) = 1e9;
      q(far[1]) = 1e10;
      std::vector<int> near;
      for (int i = 0; i < n; ++i)
        if (i != far[0] && i != far[1]) near.push_back(i);
      const Mat A_near = A(near, near);
      const Vec q_near = q(near);
      const Vec z_ref = nbm_test::brute_force_lcp(A_near, q_near);
      SCOPED_TRACE("n = " + std::to_string(n) + ", seed = " + std::to_string(seed));
      const nbm::LcpResult r = LcpSolver::solve(A, q);
      EXPECT_EQ(r.z(far[0]), 0.0);
      EXPECT_EQ(r.z(far[1]), 0.0);
      const double scale = std::max(z_ref.cwiseAbs().maxCoeff(),
                                    q_near.cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff());
      EXPECT_LE((r.z(near) - z_ref).cwiseAbs().maxCoeff(), 1e-10 * scale);
      const Vec w = q + A * r.z;
      EXPECT_GE(w(near).minCoeff(), -1e-12 * q_near.cwiseAbs().maxCoeff());
    }
  }
}

TEST(Lcp, SolvesOneByOneInClosedForm) {
  // z = max(0, -q/a): the two cases of a scalar LCP.
  const Mat A = Mat::Constant(1, 1, 4.0);
  EXPECT_DOUBLE_EQ(LcpSolver::solve(A, Vec::Constant(1, -2.0)).z(0), 0.5);
  EXPECT_DOUBLE_EQ(LcpSolver::solve(A, Vec::Constant(1, 3.0)).z(0), 0.0);
  EXPECT_DOUBLE_EQ(LcpSolver::solve(A, Vec::Constant(1, 3.0)).w(0), 3.0);
}

TEST(Lcp, EmptyProblemIsTrivial) {
  const nbm::LcpResult r = LcpSolver::solve(Mat(0, 0), Vec(0));
  EXPECT_EQ(r.z.size(), 0);
  EXPECT_EQ(LcpSolver::residual(Mat(0, 0), Vec(0), Vec(0)), 0.0);
}

// ------------------------------------------------------------- large sizes

TEST(Lcp, LargeRandomSpdHasTinyResidual) {
  std::mt19937 rng(2024);
  const int n = 500;
  const Mat A = nbm_test::random_spd(n, 100.0, rng);
  const Vec q = nbm_test::random_vector(n, rng);
  const nbm::LcpResult r = LcpSolver::solve(A, q);
  EXPECT_LE(LcpSolver::residual(A, q, r.z), 1e-12);
  expect_lcp_solution(A, q, r, 1e-12);
  // A mixed problem: both closed and open contacts in the solution.
  const auto closed = std::count(r.active.begin(), r.active.end(), true);
  EXPECT_GT(closed, 50);
  EXPECT_LT(closed, 450);
}

TEST(Lcp, LargeBandedStiffnessMatricesHaveTinyResidual) {
  // 1D: tridiagonal Dirichlet Laplacian, cond ~ 1e5 at n = 500.
  const int n = 500;
  Mat A1 = Mat::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    A1(i, i) = 2;
    if (i + 1 < n) A1(i, i + 1) = A1(i + 1, i) = -1;
  }
  // 2D: 5-point Dirichlet Laplacian on a 25 x 20 grid.
  const int nx = 25, ny = 20;
  Mat A2 = Mat::Zero(n, n);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int k = j * nx + i;
      A2(k, k) = 4;
      if (i + 1 < nx) A2(k, k + 1) = A2(k + 1, k) = -1;
      if (j + 1 < ny) A2(k, k + nx) = A2(k + nx, k) = -1;
    }
  std::mt19937 rng(77);
  for (const Mat* A : {&A1, &A2}) {
    // A load pushing some nodes into contact and pulling others away.
    const Vec q = nbm_test::random_vector(n, rng) + 0.3 * Vec::Ones(n);
    const nbm::LcpResult r = LcpSolver::solve(*A, q);
    EXPECT_LE(LcpSolver::residual(*A, q, r.z), 1e-12);
    expect_lcp_solution(*A, q, r, 1e-12);
  }
}

// ----------------------------------------------------------- warm starts

TEST(Lcp, CorrectWarmStartSolvesInOnePivot) {
  for (int seed = 0; seed < 10; ++seed) {
    std::mt19937 rng(seed);
    const int n = 40;
    const Mat A = nbm_test::random_spd(n, 50.0, rng);
    const Vec q = nbm_test::random_vector(n, rng);
    const nbm::LcpResult cold = LcpSolver::solve(A, q);
    const nbm::LcpResult warm = LcpSolver::solve(A, q, cold.active);
    EXPECT_EQ(warm.pivots, 1);
    EXPECT_LE(LcpSolver::residual(A, q, warm.z), 1e-12);
  }
}

TEST(Lcp, WrongWarmStartGivesTheSameSolution) {
  for (int seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(100 + seed);
    const int n = 10;
    const Mat A = nbm_test::random_spd(n, 30.0, rng);
    const Vec q = nbm_test::random_vector(n, rng);
    const Vec z_ref = nbm_test::brute_force_lcp(A, q);
    std::vector<bool> all_open(n, false), random_set(n);
    for (int i = 0; i < n; ++i) random_set[i] = rng() % 2;
    for (const auto& guess : {all_open, random_set}) {
      const nbm::LcpResult r = LcpSolver::solve(A, q, guess);
      EXPECT_LE((r.z - z_ref).cwiseAbs().maxCoeff(), 1e-10 * std::max(1.0, z_ref.norm()));
    }
    // The complement of the right set is the worst guess.
    std::vector<bool> complement(n);
    const nbm::LcpResult cold = LcpSolver::solve(A, q);
    for (int i = 0; i < n; ++i) complement[i] = !cold.active[i];
    const nbm::LcpResult r = LcpSolver::solve(A, q, complement);
    EXPECT_LE((r.z - z_ref).cwiseAbs().maxCoeff(), 1e-10 * std::max(1.0, z_ref.norm()));
  }
}

// ------------------------------------------------------------------ errors

TEST(Lcp, RejectsMalformedInput) {
  const Mat A = Mat::Identity(3, 3);
  const Vec q = Vec::Ones(3);
  nbm_test::expect_throw_with<nbm::InputError>([&] { LcpSolver::solve(Mat::Identity(3, 2), q); },
                                               {"LCP", "3x2"});
  nbm_test::expect_throw_with<nbm::InputError>([&] { LcpSolver::solve(A, Vec::Ones(2)); },
                                               {"LCP", "expected 2x2"});
  Vec q_nan = q;
  q_nan(1) = std::nan("");
  nbm_test::expect_throw_with<nbm::InputError>([&] { LcpSolver::solve(A, q_nan); },
                                               {"non-finite"});
  Mat A_inf = A;
  A_inf(0, 2) = INFINITY;
  nbm_test::expect_throw_with<nbm::InputError>([&] { LcpSolver::solve(A_inf, q); },
                                               {"non-finite"});
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { LcpSolver::solve(A, q, std::vector<bool>(2, true)); }, {"warm-start"});
}

TEST(Lcp, NonPMatrixIsANumericalErrorNotAHang) {
  // [[0,1],[1,0]] is not a P-matrix: from z = 0 both w_i < 0, and the block
  // it must factor is indefinite.
  Mat swap(2, 2);
  swap << 0, 1, 1, 0;
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { LcpSolver::solve(swap, Vec::Constant(2, -1.0)); }, {"not a P-matrix"});
  // Negative definite, with a right-hand side that forces a factorization.
  std::mt19937 rng(1);
  const Mat neg = -nbm_test::random_spd(4, 5.0, rng);
  Vec q(4);
  q << -1, 1, -1, 1;
  nbm_test::expect_throw_with<nbm::NumericalError>([&] { LcpSolver::solve(neg, q); },
                                                   {"not positive definite"});
}

TEST(Lcp, NonSymmetricMatrixIsRejected) {
  // [[2,3],[0,2]] is a (non-symmetric) P-matrix whose LCP has the unique
  // solution z = (0, 1/2) (brute force below). The solver factors principal
  // blocks by Cholesky, which would read only one triangle and return the
  // solution of another problem: it must refuse instead.
  Mat A(2, 2);
  A << 2, 3, 0, 2;
  Vec q(2);
  q << -1, -1;
  Vec z_ref(2);
  z_ref << 0, 0.5;
  EXPECT_LE((nbm_test::brute_force_lcp(A, q) - z_ref).norm(), 1e-15);
  nbm_test::expect_throw_with<nbm::InputError>([&] { LcpSolver::solve(A, q); },
                                               {"LCP", "not symmetric"});
}

TEST(Lcp, ResidualIsZeroAtTheSolutionAndPositiveElsewhere) {
  // residual() is the merit function: independent of the solver's result.
  Mat A(2, 2);
  A << 2, 1, 1, 2;
  Vec q(2);
  q << -1, 1;
  // Exact solution: z = (1/2, 0), w = (0, 3/2).
  Vec z(2);
  z << 0.5, 0;
  EXPECT_LE(LcpSolver::residual(A, q, z), 1e-16);
  EXPECT_GT(LcpSolver::residual(A, q, Vec::Zero(2)), 0.1);  // w_0 = -1 < 0
  Vec z_bad(2);
  z_bad << 0.5, 0.2;  // z_1 > 0 with w_1 > 0: not complementary
  EXPECT_GT(LcpSolver::residual(A, q, z_bad), 0.1);
}

// ------------------------------------------------------ CachedLcpSolver

TEST(CachedLcp, GivesLcpSolversResultsBitForBit) {
  // A sequence of q as a time loop makes them, warm-started from the last
  // set: the cached factors must not change a bit of z, w, the set or the
  // number of pivots, whether the set is new or met before.
  std::mt19937 rng(31);
  for (int n : {1, 6, 40}) {
    const Mat A = nbm_test::random_spd(n, 30.0, rng);
    const nbm::CachedLcpSolver cached(A);
    std::vector<bool> guess;
    for (int step = 0; step < 30; ++step) {
      const Vec q = nbm_test::random_vector(n, rng) + Vec::Constant(n, step % 3 - 1.0);
      const nbm::LcpResult ref = LcpSolver::solve(A, q, guess);
      const nbm::LcpResult& r = cached.solve(q, guess);
      ASSERT_EQ(r.z, ref.z);
      ASSERT_EQ(r.w, ref.w);
      ASSERT_EQ(r.active, ref.active);
      ASSERT_EQ(r.pivots, ref.pivots);
      guess = r.active;
    }
  }
}

TEST(CachedLcp, RejectsMalformedInput) {
  Mat asymmetric = Mat::Identity(2, 2);
  asymmetric(0, 1) = 1;
  nbm_test::expect_throw_with<nbm::InputError>([&] { nbm::CachedLcpSolver{asymmetric}; },
                                               {"not symmetric"});
  const nbm::CachedLcpSolver cached(Mat::Identity(2, 2));
  nbm_test::expect_throw_with<nbm::InputError>([&] { cached.solve(Vec::Ones(3), {}); },
                                               {"q has size 3"});
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { cached.solve(Vec::Ones(2), {true}); }, {"warm-start"});
}

}  // namespace
