// The iteration matrix on MUMPS (linalg/mumps_inverse.hpp), in one process:
// its halves, Gram matrices and constrained solves against dense
// computations (Eigen only), and its errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <random>
#include <stdexcept>

#include "api/model.hpp"
#include "api/solver.hpp"
#include "base/errors.hpp"
#include "linalg/active_set.hpp"
#include "linalg/constrained_solver.hpp"
#include "linalg/mumps_inverse.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm::Index;
using nbm_test::Mat;
using nbm_test::Vec;
using Sparse = nbm::SparseMatrix;

// A sparse SPD matrix (a shifted 2D grid Laplacian with random weights, so
// that MUMPS has fill to compute) of size nx * ny.
Sparse grid_spd(int nx, int ny, std::mt19937& rng) {
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const int n = nx * ny;
  Mat A = Mat::Zero(n, n);
  auto couple = [&](int i, int j) {
    const double w = weight(rng);
    A(i, i) += w;
    A(j, j) += w;
    A(i, j) -= w;
    A(j, i) -= w;
  };
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y) {
      const int i = x * ny + y;
      if (x + 1 < nx) couple(i, i + ny);
      if (y + 1 < ny) couple(i, i + 1);
      A(i, i) += 0.01;
    }
  return A.sparseView();
}

// B = [K_{:,C}  E_C] as ContactProblem builds it: the stiffness columns of
// the contact variables C (rows: C and their neighbours) and unit columns.
Sparse constraint_basis(const Sparse& K, const std::vector<Index>& C) {
  const Index nc = static_cast<Index>(C.size());
  Mat B = Mat::Zero(K.rows(), 2 * nc);
  for (Index k = 0; k < nc; ++k) {
    B.col(k) = Mat(K).col(C[k]);
    B(C[k], nc + k) = 1.0;
  }
  return B.sparseView();
}

TEST(Mumps, HalvesAndWholeSolvesAgreeWithADenseSolve) {
  std::mt19937 rng(3);
  const Sparse X = grid_spd(12, 9, rng);
  const Mat Xd = Mat(X);
  const Index n = X.rows();
  for (const std::vector<Index>& schur :
       {std::vector<Index>{}, std::vector<Index>{0, 1, 2, 50, 107}}) {
    const auto inverse = nbm::make_mumps_inverse(X, "X", schur, nbm::mpi_self());
    const Vec r = nbm_test::random_vector(static_cast<int>(n), rng);
    const Vec x_ref = Xd.ldlt().solve(r);
    Vec x = r;
    inverse->solve_in_place(x);
    EXPECT_LE((x - x_ref).norm(), 1e-12 * x_ref.norm());
    Mat R = Mat::Random(n, 3), Y = R;
    inverse->solve_in_place(Y);
    EXPECT_LE((Y - Xd.ldlt().solve(R)).norm(), 1e-12 * Y.norm());
    // y = L^-1 P r carries its Schur rows only (the interior stays in MUMPS)
    Vec y = r;
    inverse->forward_in_place(y);
    if (!schur.empty())
      for (Index i = 0; i < n; ++i)
        if (std::find(schur.begin(), schur.end(), i) == schur.end()) {
          EXPECT_EQ(y(i), 0.0);
        }
    inverse->backward_in_place(y);
    EXPECT_LE((y - x_ref).norm(), 1e-12 * x_ref.norm());
  }
}

TEST(Mumps, ForwardColumnsGiveTheGramMatrixOfTheConstraints) {
  // Y = L^-1 P B with rows on the Schur variables only; Y'Y = B' X^-1 B.
  std::mt19937 rng(5);
  const Sparse X = grid_spd(10, 10, rng);
  const std::vector<Index> C{3, 4, 5, 6, 40, 41};
  const Sparse B = constraint_basis(X, C);
  const auto inverse = nbm::make_mumps_inverse(X, "X", nbm::touched_rows(B), nbm::mpi_self());
  Mat W;
  const Sparse Y = inverse->forward(B, &W);
  const Mat W_ref = Mat(B).transpose() * Mat(X).ldlt().solve(Mat(B));
  EXPECT_LE((W - W_ref).norm(), 1e-12 * W_ref.norm());
  EXPECT_LE((inverse->gram(B) - W_ref).norm(), 1e-12 * W_ref.norm());
  EXPECT_LE((Mat(Y).transpose() * Mat(Y) - W_ref).norm(), 1e-12 * W_ref.norm());
  EXPECT_GT(inverse->factor_entries(), 0.0);
  EXPECT_EQ(inverse->forward_entries(B),
            static_cast<double>(nbm::touched_rows(B).size() * B.cols()));
}

TEST(Mumps, ConstrainedSolvesMatchTheDenseKktSystem) {
  // ConstrainedSolver and solve_constrained_once on MUMPS, over sets that
  // sweep the contact variables (fresh and bordered Schur factors), against
  // the dense KKT system; and the same solves on CHOLMOD.
  std::mt19937 rng(7);
  const Sparse X = grid_spd(14, 8, rng);
  const Index n = X.rows();
  const std::vector<Index> C{0, 8, 16, 24, 32, 40, 48, 56, 64, 72};
  const Index nc = static_cast<Index>(C.size());
  const Sparse B = constraint_basis(X, C);
  const nbm::ConstrainedSolver on_mumps(
      nbm::make_mumps_inverse(X, "X", nbm::touched_rows(B), nbm::mpi_self()), B);
  const nbm::ConstrainedSolver on_cholmod(nbm::make_cholesky_inverse(X, "X", B), B);
  const auto once = nbm::make_mumps_inverse(X, "X", nbm::touched_rows(B), nbm::mpi_self());
  nbm::ActiveSet active(nc, false);
  std::vector<nbm::ActiveSet> sets{active};
  for (Index k = 0; k < nc; ++k) {
    active[k] = true;
    sets.push_back(active);
  }
  sets.push_back(sets[3]);
  for (const auto& set : sets) {
    const Vec r = nbm_test::random_vector(static_cast<int>(n), rng);
    const Vec h = nbm_test::random_vector(static_cast<int>(nc), rng);
    const Vec x_ref = nbm_test::kkt_solution(Mat(X), Mat(B), set, r, h);
    const double scale = x_ref.cwiseAbs().maxCoeff();
    Vec x, x_cholmod, x_once;
    on_mumps.solve(set, r, h, x);
    on_cholmod.solve(set, r, h, x_cholmod);
    nbm::solve_constrained_once(*once, B, set, r, h, x_once);
    EXPECT_LE((x - x_ref).cwiseAbs().maxCoeff(), 1e-10 * scale);
    EXPECT_LE((x_once - x_ref).cwiseAbs().maxCoeff(), 1e-10 * scale);
    EXPECT_LE((x - x_cholmod).cwiseAbs().maxCoeff(), 1e-11 * scale);
  }
}

TEST(Mumps, AMatrixThatIsNotPositiveDefiniteIsRefusedByName) {
  std::mt19937 rng(9);
  Mat A = Mat(grid_spd(6, 6, rng));
  A(20, 20) = -3.0;  // an indefinite interior pivot
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::make_mumps_inverse(A.sparseView(), "the matrix X", {}, nbm::mpi_self()); },
      {"the matrix X", "positive definite"});
  Mat S = Mat(grid_spd(6, 6, rng));
  S(35, 35) = -3.0;  // indefinite on a Schur variable: its dense factor sees it
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::make_mumps_inverse(S.sparseView(), "the matrix X", {34, 35}, nbm::mpi_self()); },
      {"the matrix X", "positive definite"});
}

TEST(Mumps, MisusedInverseSaysWhat) {
  std::mt19937 rng(11);
  const Sparse X = grid_spd(5, 5, rng);
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::make_mumps_inverse(X, "X", {4, 2}, nbm::mpi_self()); },
      {"X", "ascending"});
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::make_mumps_inverse(X, "X", {3, 25}, nbm::mpi_self()); }, {"X", "Schur"});
  const auto inverse = nbm::make_mumps_inverse(X, "X", {3, 4}, nbm::mpi_self());
  Sparse E(25, 1);
  E.insert(7, 0) = 1.0;  // a constraint on an interior variable
  EXPECT_THROW(inverse->forward(E), std::logic_error);
  Vec y = Vec::Ones(25);
  EXPECT_THROW(inverse->backward_in_place(y), std::logic_error);  // no forward before
  Vec short_vector = Vec::Ones(24);
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { inverse->forward_in_place(short_vector); }, {"size 24", "25"});
}

// MUMPS's analysis (no factorization) against what is known of the factors:
// a tridiagonal matrix, eliminated in any order that keeps it a path, has
// a factor of n diagonal and n - 1 subdiagonal entries and costs O(n) flops;
// a grid's factor holds at least the matrix's lower triangle, and the
// factorization of the same input then fills at most the space announced.
TEST(Mumps, EstimatesMatchTheFactorsTheyAnnounce) {
  const int n = 2000;
  Sparse T(n, n);
  std::vector<nbm::Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  T.setFromTriplets(t.begin(), t.end());
  const nbm::MumpsEstimate e = nbm::estimate_mumps_factorization(T, "T", {}, nbm::mpi_self());
  EXPECT_GE(e.factor_entries, 2.0 * n - 1);
  EXPECT_LE(e.factor_entries, 3.0 * n);
  EXPECT_GT(e.flops, 0.0);
  EXPECT_LE(e.flops, 20.0 * n);
  EXPECT_GT(e.memory_max_mb, 0.0);
  EXPECT_EQ(e.memory_max_mb, e.memory_total_mb);  // one rank

  std::mt19937 rng(5);
  const Sparse X = grid_spd(30, 30, rng);
  const std::vector<Index> schur = {3, 400, 899};
  const nbm::MumpsEstimate g = nbm::estimate_mumps_factorization(X, "X", schur, nbm::mpi_self());
  double lower = 0;  // X's lower triangle outside the Schur variables' rows and columns
  for (Index j = 0; j < X.outerSize(); ++j)
    for (Sparse::InnerIterator it(X, j); it; ++it)
      if (it.row() >= j && std::count(schur.begin(), schur.end(), it.row()) == 0 &&
          std::count(schur.begin(), schur.end(), j) == 0)
        ++lower;
  EXPECT_GE(g.factor_entries, lower);
  const auto inverse = nbm::make_mumps_inverse(X, "X", schur, nbm::mpi_self());
  // The estimate is the space MUMPS reserves for the factors: at least the
  // entries the factorization then reports, and not wildly more.
  const double schur_entries = 0.5 * 3 * 4;  // the dense factor of S_X, counted by factor_entries()
  const double effective = inverse->factor_entries() - schur_entries;
  EXPECT_GE(g.factor_entries, effective);
  EXPECT_LE(g.factor_entries, 1.5 * effective);

  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::estimate_mumps_factorization(Sparse(3, 4), "the matrix Y", {}, nbm::mpi_self()); },
      {"the matrix Y", "square"});
}

// A plate on an inclined ground, dropped and bouncing (rotated contact
// nodes, contacts opening and closing), integrated with `solver`.
std::vector<std::vector<double>> plate_run(nbm::SparseSolver solver, const std::string& mass,
                                           nbm::TimeScheme scheme, bool obstacle) {
  nbm_test::Plate plate;
  plate.angle = obstacle ? 0.0 : 0.4;
  plate.nx = 8;
  plate.ny = 3;
  const nbm_test::Assembled a = nbm_test::assemble(plate);
  nbm::SolverOptions o;
  o.solver = solver;
  o.mass = nbm_test::mass_named(mass);
  const Eigen::MatrixXd X = nbm_test::node_positions(plate);
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = 0; j < X.cols(); ++j) o.positions.push_back(X(i, j));
  if (mass == "consistent") o.positions.clear();
  if (obstacle) {  // a round ground under the plate, held exactly (method.md §10)
    nbm::ObstacleDescription bump;
    bump.kind = "circle";
    bump.point = {0.5, -2.01};
    bump.radius = 2.0;
    o.obstacle = bump;
  }
  o.dt = 2e-3;
  o.scheme = scheme;
  if (scheme == nbm::TimeScheme::kNewmark && mass == "consistent")
    o.energy = nbm::EnergyControl::kNone;
  nbm::Solver s(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K),
                nbm_test::bottom_contact(plate, 0.01), o);
  auto u = nbm_test::displacements(s, nbm_test::to_std(a.F), 150);
  long touching = 0;
  for (long k : s.active()) touching += k;
  EXPECT_GT(touching, 0) << "the plate never touched: the comparison proves little";
  return u;
}

struct Case {
  std::string mass;
  nbm::TimeScheme scheme;
  bool obstacle;
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
  return out << c.mass << " mass, " << nbm::name(c.scheme) << (c.obstacle ? ", obstacle" : "");
}

class MumpsStepping : public ::testing::TestWithParam<Case> {};

TEST_P(MumpsStepping, FollowsCholmodToRoundOff) {
  // The same run factored by MUMPS (one process) and by CHOLMOD: the
  // factors differ, the trajectories only by round-off.
  const Case c = GetParam();
  const auto mumps = plate_run(nbm::SparseSolver::kMumps, c.mass, c.scheme, c.obstacle);
  const auto cholmod = plate_run(nbm::SparseSolver::kCholmod, c.mass, c.scheme, c.obstacle);
  ASSERT_EQ(mumps.size(), cholmod.size());
  double scale = 0, error = 0;
  for (std::size_t k = 0; k < mumps.size(); ++k)
    for (std::size_t i = 0; i < mumps[k].size(); ++i) {
      scale = std::max(scale, std::abs(cholmod[k][i]));
      error = std::max(error, std::abs(mumps[k][i] - cholmod[k][i]));
    }
  std::printf("MUMPS against CHOLMOD: trajectories differ by %.2e of %.2e\n", error, scale);
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(error, 1e-12 * scale);
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, MumpsStepping,
    ::testing::Values(Case{"consistent", nbm::TimeScheme::kNewmark, false},
                      Case{"consistent", nbm::TimeScheme::kGeneralizedAlpha, false},
                      Case{"consistent", nbm::TimeScheme::kMoreauJean, false},
                      Case{"redistributed", nbm::TimeScheme::kNewmark, false},
                      Case{"redistributed", nbm::TimeScheme::kHhtAlpha, false},
                      Case{"redistributed", nbm::TimeScheme::kNewmark, true}),
    [](const auto& info) {
      std::string name = info.param.mass + "_" + nbm::name(info.param.scheme) +
                         (info.param.obstacle ? "_obstacle" : "");
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

}  // namespace
