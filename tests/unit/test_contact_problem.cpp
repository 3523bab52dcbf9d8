// The linear algebra under the steppers, each piece against a dense
// computation done here: internal coordinates of ContactProblem, the nodal
// boundary relation (NodalBoundary), the constrained solves of §4
// (ConstrainedSolver) and the SPD inverses.
#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "contact/nodal_boundary.hpp"
#include "linalg/constrained_solver.hpp"
#include "linalg/mass_solve.hpp"
#include "linalg/spd_inverse.hpp"
#include "test_problems.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"
#include "time/newmark_stepper.hpp"

namespace {

using nbm::Index;
using nbm_test::Plate;
using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

// A rotated plate with two fixed dofs (top-left node) and bottom contacts.
struct PlateProblem {
  Plate p;
  nbm_test::Assembled a;
  nbm::ContactDescription c;
  std::vector<Index> fixed;
  std::unique_ptr<nbm::ContactProblem> problem;
  explicit PlateProblem(double angle = 0.4) {
    p.angle = angle;
    a = assemble(p);
    c = nbm_test::bottom_contact(p, 0.01);
    const int top_left = p.node(0, p.ny);
    fixed = {2 * top_left, 2 * top_left + 1};
    nbm::ContactSet set(p.n_dofs(), std::vector<Index>(c.dofs.begin(), c.dofs.end()), c.normals,
                        nbm_test::to_eigen(c.gaps), fixed);
    problem = std::make_unique<nbm::ContactProblem>(a.M, a.K, std::move(set), fixed);
  }
  // n_k placed at the dofs of bottom node k: columns of an n_dofs x n_c matrix.
  Mat normals() const {
    Mat N = Mat::Zero(p.n_dofs(), c.gaps.size());
    for (std::size_t k = 0; k < c.gaps.size(); ++k)
      N.block<2, 1>(c.dofs[2 * k], k) = p.normal();
    return N;
  }
};

// ------------------------------------------------------- ContactProblem

TEST(ContactProblem, InternalCoordinatesAreAnOrthogonalChangeOfBasis) {
  PlateProblem pp;
  const auto& P = *pp.problem;
  EXPECT_EQ(P.n_dofs(), pp.p.n_dofs());
  EXPECT_EQ(P.size(), pp.p.n_dofs() - 2);
  EXPECT_EQ(P.n_contact(), pp.p.nx + 1);
  std::mt19937 rng(1);
  Vec u = nbm_test::random_vector(pp.p.n_dofs(), rng);
  for (Index f : pp.fixed) u(f) = 0;
  const Vec x = P.to_internal(u);
  // Round trip, and fixed dofs come back as zero.
  EXPECT_LE((P.to_user(x) - u).cwiseAbs().maxCoeff(), 1e-15);
  Vec u_fixed = u;
  u_fixed(pp.fixed[0]) = 3.0;
  EXPECT_EQ(P.to_user(P.to_internal(u_fixed))(pp.fixed[0]), 0.0);
  // The contact dof of node k is the normal displacement n.u.
  const Vec un = pp.normals().transpose() * u;
  for (Index k = 0; k < P.n_contact(); ++k)
    EXPECT_NEAR(x(P.contact_index()[k]), un(k), 1e-15);
  // Quadratic forms are invariant: u'Ku and u'Mu.
  EXPECT_NEAR(x.dot(P.K() * x), u.dot(pp.a.K * u), 1e-12 * u.dot(pp.a.K * u));
  EXPECT_NEAR(x.dot(P.M() * x), u.dot(pp.a.M * u), 1e-14);
}

TEST(ContactProblem, ContactBlockAndConstraintBasis) {
  PlateProblem pp;
  const auto& P = *pp.problem;
  const Mat N = pp.normals();
  // K_CC = N' K N: the stiffness between normal displacements.
  const Mat K_CC = N.transpose() * Mat(pp.a.K) * N;
  EXPECT_LE((Mat(P.K_CC()) - K_CC).cwiseAbs().maxCoeff(), 1e-12 * K_CC.cwiseAbs().maxCoeff());
  // B = [K(:, C)  E_C].
  const Mat B = Mat(P.constraint_basis());
  const Index nc = P.n_contact();
  ASSERT_EQ(B.cols(), 2 * nc);
  const Mat K = Mat(P.K());
  for (Index k = 0; k < nc; ++k) {
    EXPECT_LE((B.col(k) - K.col(P.contact_index()[k])).cwiseAbs().maxCoeff(), 0.0);
    Vec e = Vec::Zero(P.size());
    e(P.contact_index()[k]) = 1;
    EXPECT_EQ(B.col(nc + k), e);
  }
}

TEST(ContactProblem, MatrixSizeMismatchNamesM) {
  const auto a = assemble(nbm_test::Bar{});
  const auto small = assemble(nbm_test::Bar{1, 1, 100, 10, 5});
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] {
        nbm::ContactProblem(small.M, a.K, nbm::ContactSet(a.K.rows(), {0}, {-1}, Vec::Zero(1)), {});
      },
      {"M", "size 6", "expected 21"});
}

// -------------------------------------------------------- NodalBoundary

TEST(NodalBoundary, EnforceSolvesTheLcpOfTheContactDofs) {
  // Pull some bottom nodes through the plane, leave others above it: the
  // LCP decides. Check the result against the complementarity conditions,
  // computed from the internal K, F.
  PlateProblem pp(0.2);
  const auto& P = *pp.problem;
  const nbm::NodalBoundary nb(P);
  std::mt19937 rng(4);
  Vec u = 0.02 * nbm_test::random_vector(P.size(), rng);
  Vec F = P.to_internal(pp.a.F) + 50.0 * nbm_test::random_vector(P.size(), rng);
  // Normal forces pushing every other contact node onto the plane, the others away.
  for (Index k = 0; k < P.n_contact(); ++k) F(P.contact_index()[k]) += k % 2 ? -200.0 : 200.0;
  const Vec u_before = u;
  const nbm::LcpResult r = nb.enforce(u, F, P.gaps(), {});
  const Vec lambda = F - P.K() * u;
  Vec gap = P.gaps();
  for (Index k = 0; k < P.n_contact(); ++k) gap(k) -= u(P.contact_index()[k]);
  int closed = 0;
  for (Index k = 0; k < P.n_contact(); ++k) {
    const Index c = P.contact_index()[k];
    EXPECT_GE(gap(k), -1e-14);
    EXPECT_GE(lambda(c), -1e-10);
    EXPECT_LE(std::min(std::abs(gap(k)), std::abs(lambda(c))), 1e-10);
    EXPECT_NEAR(r.z(k), gap(k), 1e-15);
    EXPECT_NEAR(nb.reactions(u, F)(k), lambda(c), 1e-10);
    closed += r.active[k];
  }
  EXPECT_GT(closed, 0);
  EXPECT_LT(closed, P.n_contact());
  EXPECT_LE(nb.violation(u, F, P.gaps(), r.active), nbm::kConsistencyTolerance);
  // Only contact dofs moved.
  Vec diff = u - u_before;
  for (Index c : P.contact_index()) diff(c) = 0;
  EXPECT_EQ(diff.cwiseAbs().maxCoeff(), 0.0);
  // A wrong active set is not consistent.
  nbm::ActiveSet flipped = r.active;
  for (std::size_t k = 0; k < flipped.size(); ++k) flipped[k] = !flipped[k];
  Vec u_wrong = u, h(P.n_contact());
  for (Index k = 0; k < P.n_contact(); ++k)
    h(k) = flipped[k] ? P.gaps()(k) : F(P.contact_index()[k]);
  nb.project(u_wrong, flipped, h);
  EXPECT_GT(nb.violation(u_wrong, F, P.gaps(), flipped), nbm::kConsistencyTolerance);
}

TEST(NodalBoundary, ProjectImposesTheConstraintRows) {
  PlateProblem pp;
  const auto& P = *pp.problem;
  const nbm::NodalBoundary nb(P);
  std::mt19937 rng(8);
  for (int trial = 0; trial < 8; ++trial) {
    nbm::ActiveSet set(P.n_contact());
    for (auto&& s : set) s = rng() % 2;
    Vec x = nbm_test::random_vector(P.size(), rng);
    const Vec h = nbm_test::random_vector(P.n_contact(), rng);
    nb.project(x, set, h);
    const Vec Kx = P.K() * x;
    for (Index k = 0; k < P.n_contact(); ++k) {
      const Index c = P.contact_index()[k];
      if (set[k])
        EXPECT_EQ(x(c), h(k));
      else
        EXPECT_NEAR(Kx(c), h(k), 1e-10);
    }
  }
}

// ---------------------------------------------------- ConstrainedSolver

TEST(ConstrainedSolver, MatchesADenseKktSolve) {
  // X x = r + G' mu, G x = h, against the dense KKT system.
  PlateProblem pp;
  const auto& P = *pp.problem;
  const double beta_dt2 = 0.25 * 1e-4;
  const nbm_test::Sparse X = P.M() + beta_dt2 * P.K();
  const nbm::ConstrainedSolver cs(nbm::make_cholesky_inverse(X, "X"), P.constraint_basis());
  const Mat B = Mat(P.constraint_basis());
  const Index n = P.size(), nc = P.n_contact();
  std::mt19937 rng(21);
  for (int trial = 0; trial < 6; ++trial) {
    nbm::ActiveSet set(nc);
    for (auto&& s : set) s = rng() % 2;
    const Mat G = nbm_test::constraint_rows(B, set);
    const Vec r = nbm_test::random_vector(n, rng), h = nbm_test::random_vector(nc, rng);
    const Vec ref = nbm_test::kkt_solution(Mat(X), B, set, r, h);
    Vec x;
    cs.solve(set, r, h, x);
    EXPECT_LE((x - ref).cwiseAbs().maxCoeff(), 1e-10 * ref.cwiseAbs().maxCoeff());
    EXPECT_LE((G * x - h).cwiseAbs().maxCoeff(), 1e-9);
  }
  EXPECT_EQ(cs.inverse().size(), n);
}

TEST(ConstrainedSolver, LumpedMassMatchesADenseKktSolve) {
  // The explicit scheme's X = diag(m): W = B' X^-1 B is sparse and so are the
  // factors of its Schur complements; the same dense KKT reference, on a
  // plate with enough contact nodes (33) for sparse blocks, sets that
  // recur (cached factors) and one empty of open nodes.
  nbm_test::Plate plate;
  plate.nx = 32;
  plate.ny = 4;
  const nbm_test::Simulation sim(nbm_test::assemble(plate), nbm_test::bottom_contact(plate, 0.0));
  const nbm::ContactProblem& P = *sim.problem;
  const Vec m = P.lumped_mass();
  const nbm::ConstrainedSolver cs(nbm::make_diagonal_inverse(m, "m"), P.constraint_basis());
  ASSERT_TRUE(nbm::PrincipalBlocks(nbm::make_diagonal_inverse(m, "m")->sparse_gram(P.constraint_basis()))
                  .sparse());
  const Mat B = Mat(P.constraint_basis());
  const Index n = P.size(), nc = P.n_contact();
  std::mt19937 rng(22);
  std::vector<nbm::ActiveSet> sets;
  for (int trial = 0; trial < 5; ++trial) {
    nbm::ActiveSet set(nc);
    for (auto&& s : set) s = rng() % 2;
    sets.push_back(set);
  }
  sets.push_back(nbm::ActiveSet(nc, true));
  sets.push_back(sets[1]);
  for (const nbm::ActiveSet& set : sets) {
    const Mat G = nbm_test::constraint_rows(B, set);
    const Vec r = nbm_test::random_vector(n, rng), h = nbm_test::random_vector(nc, rng);
    const Vec ref = nbm_test::kkt_solution(Mat(m.asDiagonal()), B, set, r, h);
    Vec x;
    cs.solve(set, r, h, x);
    EXPECT_LE((x - ref).cwiseAbs().maxCoeff(), 1e-10 * ref.cwiseAbs().maxCoeff());
    EXPECT_LE((G * x - h).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, (G.cwiseAbs() * x.cwiseAbs()).maxCoeff()));
  }
}

// ----------------------------------------------------------- SpdInverse

TEST(SpdInverse, CholeskyAndDiagonalAgreeWithDenseAlgebra) {
  std::mt19937 rng(6);
  const Mat A = nbm_test::random_spd(7, 20.0, rng);
  const nbm_test::Sparse As = A.sparseView();
  const auto chol = nbm::make_cholesky_inverse(As, "A");
  EXPECT_EQ(chol->size(), 7);
  Mat Y = Mat::Identity(7, 7);
  chol->solve_in_place(Y);
  EXPECT_LE((A * Y - Mat::Identity(7, 7)).cwiseAbs().maxCoeff(), 1e-12);
  // Gram matrix B' A^{-1} B for a sparse B, against the dense formula.
  Mat Bd = Mat::Zero(7, 3);
  Bd(0, 0) = 1;
  Bd(3, 1) = 2;
  Bd(6, 2) = -1;
  Bd(2, 2) = 0.5;
  const nbm_test::Sparse B = Bd.sparseView();
  const Mat W_ref = Bd.transpose() * A.inverse() * Bd;
  EXPECT_LE((chol->gram(B) - W_ref).cwiseAbs().maxCoeff(), 1e-12);

  Vec d(7);
  d << 1, 2, 3, 4, 5, 6, 7;
  const auto diag = nbm::make_diagonal_inverse(d, "d");
  EXPECT_EQ(diag->size(), 7);
  Mat Z = Mat::Ones(7, 2);
  diag->solve_in_place(Z);
  for (int i = 0; i < 7; ++i) EXPECT_DOUBLE_EQ(Z(i, 1), 1.0 / d(i));
  const Mat Wd = Bd.transpose() * d.cwiseInverse().asDiagonal() * Bd;
  EXPECT_LE((diag->gram(B) - Wd).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(SpdInverse, SparseGramMatchesDenseSolves) {
  // The Cholesky Gram matrix comes from sparse forward substitutions
  // (Y' Y, Y = L^-1 P B); it must be B' X^-1 B as full dense solves give it,
  // to round-off, on the stepper's own B and X = M + beta dt^2 K.
  PlateProblem pp;
  const auto& P = *pp.problem;
  const nbm_test::Sparse X = P.M() + (0.25 * 1e-4) * P.K();
  const auto inverse = nbm::make_cholesky_inverse(X, "X");
  const nbm_test::Sparse& B = P.constraint_basis();
  Mat Y = Mat(B);
  inverse->solve_in_place(Y);
  const Mat W_dense = Mat(B).transpose() * Y;
  const Mat W = inverse->gram(B);
  EXPECT_LE((W - W_dense).cwiseAbs().maxCoeff(), 1e-12 * W_dense.cwiseAbs().maxCoeff());
  EXPECT_EQ(W, W.transpose());
}

TEST(SpdInverse, CholeskyHalvesComposeTheSolve) {
  // backward(forward(r)) = X^-1 r, and forward(B) (sparse) is the forward
  // half applied to each column of B.
  PlateProblem pp;
  const auto& P = *pp.problem;
  const nbm_test::Sparse X = P.M() + (0.25 * 1e-4) * P.K();
  const auto inverse = nbm::make_cholesky_inverse(X, "X");
  std::mt19937 rng(8);
  const Vec r = nbm_test::random_vector(P.size(), rng);
  Vec x = r, y = r;
  inverse->solve_in_place(x);
  inverse->forward_in_place(y);
  const Vec y_forward = y;
  inverse->backward_in_place(y);
  EXPECT_LE((y - x).cwiseAbs().maxCoeff(), 1e-13 * x.cwiseAbs().maxCoeff());
  EXPECT_NEAR(y_forward.squaredNorm(), r.dot(x), 1e-12 * r.dot(x));  // |L^-1 P r|^2 = r' X^-1 r
  const nbm_test::Sparse& B = P.constraint_basis();
  const Mat Y = Mat(inverse->forward(B));
  for (Index j = 0; j < B.cols(); ++j) {
    Vec b = Mat(B).col(j);
    inverse->forward_in_place(b);
    EXPECT_LE((Y.col(j) - b).cwiseAbs().maxCoeff(), 1e-13 * b.cwiseAbs().maxCoeff());
  }
}

TEST(SpdInverse, ErrorsNameTheMatrix) {
  Mat A = Mat::Identity(3, 3);
  A(1, 1) = -1;
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::make_cholesky_inverse(A.sparseView(), "the matrix X"); },
      {"the matrix X", "not positive definite"});
  Vec d = Vec::Ones(3);
  d(2) = 0;
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::make_diagonal_inverse(d, "lumped M"); }, {"lumped M", "entry 2"});
}

TEST(SpdInverse, MassSolvesReachRoundOffWithoutAFactor) {
  // solve_mass against dense solves: the plate's consistent mass, its
  // redistributed mass with unit contact rows (the massless start), a mass
  // whose diagonal is a poor preconditioner (cond 1e12: the iterations stall
  // and M is factored), a zero right-hand side, and errors naming M.
  PlateProblem pp;
  const auto& P = *pp.problem;
  std::mt19937 rng(31);
  const Mat positions = nbm_test::node_positions(pp.p);
  const nbm::ContactProblem massless(pp.a.M, pp.a.K, P.contacts(), P.fixed(), &positions);
  const nbm::SparseMatrix& E_C = massless.constraint_basis().rightCols(massless.n_contact());
  const nbm_test::Sparse redistributed = massless.M() + nbm_test::Sparse(E_C * E_C.transpose());
  const nbm_test::Sparse stiff = nbm_test::random_spd(80, 1e12, rng).sparseView();
  for (const nbm_test::Sparse* M : {&P.M(), &redistributed, &stiff}) {
    const Vec r = nbm_test::random_vector(static_cast<int>(M->rows()), rng);
    const Vec x = nbm::solve_mass(*M, r, "M");
    const Vec ref = Mat(*M).llt().solve(r);
    if (M == &stiff) {  // factored: as accurate as the dense factorization (cond eps = 1e-4)
      EXPECT_LE((x - ref).norm(), 1e-3 * ref.norm());
      continue;
    }
    EXPECT_LE((r - *M * x).norm(), nbm::kMassSolveTolerance * r.norm());
    EXPECT_LE((x - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
  }
  EXPECT_EQ(nbm::solve_mass(P.M(), Vec::Zero(P.size()), "M"), Vec::Zero(P.size()));
  Mat indefinite = Mat::Identity(4, 4);
  indefinite(2, 2) = 0;
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::solve_mass(indefinite.sparseView(), Vec::Ones(4), "the mass M"); },
      {"the mass M", "not positive definite", "diagonal entry 2"});
  indefinite(2, 2) = 1;
  indefinite(0, 1) = indefinite(1, 0) = 2;  // eigenvector (1, -1, 0, 0): eigenvalue -1
  const Vec along_it = (Vec(4) << 1, -1, 0, 0).finished();
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::solve_mass(indefinite.sparseView(), along_it, "the mass M"); },
      {"the mass M", "not positive definite"});
}

TEST(SpdInverse, NewmarkReportsAnIndefiniteIterationMatrix) {
  // M negative definite: M + beta dt^2 K is not positive definite.
  const nbm_test::Bar b;
  auto a = assemble(b);
  const nbm_test::Sparse M = -1.0 * a.M;
  const nbm::ContactProblem P(M, a.K, nbm::ContactSet(b.n_dofs(), {0}, {-1}, Vec::Zero(1)), {});
  nbm_test::expect_throw_with<nbm::NumericalError>([&] { nbm::NewmarkStepper(P, 1e-3); },
                                                   {"M + beta dt^2 K"});
}

}  // namespace
