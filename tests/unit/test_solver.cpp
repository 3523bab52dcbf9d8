// nbm::Solver, the facade on user dofs and coordinate-form matrices: storage
// variants, Dirichlet dofs (the fixed option), diagnostics, and the
// error messages that name the faulty argument.
#include <gtest/gtest.h>

#include <cmath>

#include "api/solver.hpp"
#include "base/errors.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm::CooMatrix;
using nbm::Solver;
using nbm::SolverOptions;
using nbm_test::Bar;
using nbm_test::expect_throw_with;
using Vec = Eigen::VectorXd;
using StdVec = std::vector<double>;

SolverOptions newmark(double dt = 1e-3) {
  SolverOptions o;
  o.dt = dt;
  return o;
}

// A run of the bar falling from h0 = 0.1 through the facade; returns the
// trajectory of u (one vector per step, initial state first).
std::vector<StdVec> trajectory(const CooMatrix& M, const CooMatrix& K, const StdVec& F,
                               const nbm::ContactDescription& c, const SolverOptions& o,
                               int steps, double h0 = 0.1) {
  Solver s(M, K, c, o);
  return nbm_test::displacements(s, F, steps, h0);
}

void expect_same_trajectory(const std::vector<StdVec>& a, const std::vector<StdVec>& b,
                            double tol) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].size(), b[k].size());
    for (std::size_t i = 0; i < a[k].size(); ++i)
      ASSERT_NEAR(a[k][i], b[k][i], tol) << "step " << k << ", dof " << i;
  }
}

// ---------------------------------------------------------------- storage

TEST(SolverStorage, LowerHalfEqualsFullStorage) {
  const Bar b;
  const auto a = assemble(b);
  const StdVec F = nbm_test::to_std(a.F);
  const auto c = nbm_test::ground_contact();
  const auto full = trajectory(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), F, c, newmark(), 400);
  const auto half = trajectory(nbm_test::to_coo(a.M, true), nbm_test::to_coo(a.K, true), F, c,
                               newmark(), 400);
  expect_same_trajectory(full, half, 1e-14);
}

TEST(SolverStorage, LowerHalfEqualsFullStorageIn2D) {
  nbm_test::Plate p;
  p.angle = 0.5;
  const auto a = assemble(p);
  const StdVec F = nbm_test::to_std(a.F);
  const auto c = nbm_test::bottom_contact(p, 0.01);
  const auto full = trajectory(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), F, c, newmark(), 150, 0.0);
  const auto half = trajectory(nbm_test::to_coo(a.M, true), nbm_test::to_coo(a.K, true), F, c,
                               newmark(), 150, 0.0);
  expect_same_trajectory(full, half, 1e-14);
}

TEST(SolverStorage, DuplicateCoordinateEntriesAreSummed) {
  // FreeFEM may hand over an entry in pieces: (i, j, a) and (i, j, b) mean a + b.
  const Bar b;
  const auto a = assemble(b);
  CooMatrix K = nbm_test::to_coo(a.K);
  CooMatrix K_split = K;
  for (std::size_t k = 0; k < K.value.size(); ++k) {
    K_split.value[k] = 0.25 * K.value[k];
    K_split.i.push_back(K.i[k]);
    K_split.j.push_back(K.j[k]);
    K_split.value.push_back(0.75 * K.value[k]);
  }
  const StdVec F = nbm_test::to_std(a.F);
  const auto c = nbm_test::ground_contact();
  expect_same_trajectory(trajectory(nbm_test::to_coo(a.M), K, F, c, newmark(), 200),
                         trajectory(nbm_test::to_coo(a.M), K_split, F, c, newmark(), 200), 1e-13);
}

// ------------------------------------------------------------ fixed dofs

// The bar clamped at its top x = L (dof N), hanging above the ground.
struct Clamped {
  Bar b;
  nbm_test::Assembled a = assemble(b);
  StdVec F = nbm_test::to_std(a.F);
  nbm::ContactDescription c = nbm_test::ground_contact(0.02);
};

TEST(SolverFixedDofs, RowsAndColumnsOfFixedDofsAreIgnored) {
  Clamped cl;
  const int N = cl.b.N;
  SolverOptions fixed = newmark();
  fixed.fixed = {N, N};  // repeats allowed
  const auto ref = trajectory(nbm_test::to_coo(cl.a.M), nbm_test::to_coo(cl.a.K), cl.F, cl.c,
                              fixed, 300, 0.0);
  for (int both : {0, 1}) {
    // Whatever a front end leaves in the rows of a fixed dof (FreeFEM's on():
    // 1e30 on the diagonal of K, and of M if its varf has on()) is ignored.
    nbm_test::Sparse K = cl.a.K, M = cl.a.M;
    K.coeffRef(N, N) = 1e30;
    if (both) M.coeffRef(N, N) = 1e30;
    Solver s(nbm_test::to_coo(M), nbm_test::to_coo(K), cl.c, fixed);
    EXPECT_EQ(s.fixed_dofs(), std::vector<long>{N});
    const auto penalised = trajectory(nbm_test::to_coo(M), nbm_test::to_coo(K), cl.F, cl.c, fixed,
                                      300, 0.0);
    expect_same_trajectory(ref, penalised, 1e-15);
  }
  // The clamped end stays put, the hanging bar reaches the ground (gap 0.02
  // is less than the static elongation rho g L^2 / (2E) = 0.05).
  double lowest = 0;
  for (const auto& u : ref) {
    EXPECT_EQ(u[N], 0.0);
    lowest = std::min(lowest, u[0]);
  }
  EXPECT_NEAR(lowest, -0.02, 1e-12);
}

TEST(SolverFixedDofs, AHugeDiagonalNotListedAsFixedIsAStiffEntry) {
  // The core knows only the `fixed` option (the FreeFEM binding turns on()'s
  // tgv into it): a 1e30 diagonal is a stiff spring, not a Dirichlet dof.
  Clamped cl;
  nbm_test::Sparse K = cl.a.K;
  K.coeffRef(cl.b.N, cl.b.N) = 1e30;
  Solver s(nbm_test::to_coo(cl.a.M), nbm_test::to_coo(K), cl.c, newmark());
  EXPECT_TRUE(s.fixed_dofs().empty());
}

TEST(SolverFixedDofs, InitializeZeroesFixedDofsAndSlavesContactDofs) {
  Clamped cl;
  const int N = cl.b.N;
  SolverOptions o = newmark();
  o.fixed = {N};
  Solver s(nbm_test::to_coo(cl.a.M), nbm_test::to_coo(cl.a.K), cl.c, o);
  StdVec u(N + 1, 0.0), v(N + 1, 0.0);
  u[N] = 0.3;  // not admissible: reset to zero
  v[N] = 1.0;
  s.initialize(u, v, cl.F);
  EXPECT_EQ(u[N], 0.0);
  EXPECT_EQ(v[N], 0.0);
  // Open contact: (E/h)(u_0 - u_1) = -rho g h/2 with u_1 = 0.
  EXPECT_NEAR(u[0], -cl.b.rho * cl.b.g * cl.b.h() * cl.b.h() / (2 * cl.b.E), 1e-15);
  EXPECT_TRUE(s.initialized());
  EXPECT_EQ(s.time(), 0.0);
  EXPECT_EQ(s.n_dofs(), N + 1);
  EXPECT_EQ(s.n_contact(), 1);
}

// ----------------------------------------------------------- diagnostics

TEST(SolverDiagnostics, ComplementarityEnergiesAndCountersAlongABouncingRun) {
  const Bar b;
  const auto a = assemble(b);
  for (const char* scheme : {"newmark", "explicit"}) {
    SCOPED_TRACE(scheme);
    SolverOptions o = newmark(1e-3);
    o.scheme = nbm_test::scheme_named(scheme);
    Solver s(nbm_test::to_coo(a.M, true), nbm_test::to_coo(a.K, true), nbm_test::ground_contact(), o);
    StdVec u(b.n_dofs(), 0.05), v(b.n_dofs(), 0.0);
    const StdVec F = nbm_test::to_std(a.F);
    s.initialize(u, v, F);
    int closed = 0;
    for (int k = 1; k <= 600; ++k) {
      const nbm::StepInfo info = s.step(u, v, F);
      EXPECT_GE(info.active_set_iterations, 1);
      EXPECT_EQ(s.steps(), k);
      EXPECT_NEAR(s.time(), k * o.dt, 1e-12);
      const double gap = s.gaps()[0], lambda = s.reactions()[0];
      EXPECT_NEAR(gap, u[0], 1e-15);  // gap = 0 - n.u with n = -1
      EXPECT_GE(gap, -1e-14);
      if (s.active()[0]) {
        ++closed;
        EXPECT_NEAR(gap, 0.0, 1e-14);  // closed: u_C = g to round-off
        EXPECT_GE(lambda, -1e-10);
      } else {
        EXPECT_NEAR(lambda, 0.0, 1e-10);  // an open contact carries no force
      }
      const std::vector<double> e = s.energies();
      ASSERT_EQ(e.size(), 7u);
      EXPECT_NEAR(e[3], e[0] + e[1] + e[2], 1e-14);
      EXPECT_EQ(e[4], 0.0);  // a fixed obstacle does no work
      EXPECT_EQ(e[5], 0.0);  // nothing dissipated without damping
      EXPECT_EQ(e[6], 0.0);  // a constant load changes nothing
      EXPECT_NEAR(e[1], 0.5 * nbm_test::to_eigen(u).dot(a.K * nbm_test::to_eigen(u)), 1e-12);
      EXPECT_NEAR(e[2], -a.F.dot(nbm_test::to_eigen(u)), 1e-12);
      EXPECT_EQ(s.acceleration().size(), u.size());
    }
    EXPECT_GT(closed, 0);
    EXPECT_GE(s.fallbacks(), 0);
    EXPECT_LE(s.fallbacks(), s.steps());
  }
}

TEST(SolverDiagnostics, StandingBarReactionIsItsWeight) {
  // Static solution u(x) = -(rho g/E)(L x - x^2/2), nodally exact for P1.
  const Bar b;
  const auto a = assemble(b);
  Solver s(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), newmark(2e-3));
  StdVec u(b.n_dofs()), v(b.n_dofs(), 0.0);
  for (int i = 0; i <= b.N; ++i) {
    const double x = i * b.h();
    u[i] = -(b.rho * b.g / b.E) * (b.L * x - x * x / 2);
  }
  const StdVec F = nbm_test::to_std(a.F);
  s.initialize(u, v, F);
  for (int k = 0; k < 50; ++k) s.step(u, v, F);
  EXPECT_EQ(s.active()[0], 1);
  EXPECT_NEAR(s.reactions()[0], b.rho * b.L * b.g, 1e-10);
  for (double ai : s.acceleration()) EXPECT_NEAR(ai, 0.0, 1e-9);
}

TEST(SolverDiagnostics, CriticalTimeStepIsReportedForTheExplicitScheme) {
  const Bar b;
  const auto a = assemble(b);
  const double exact = 2 / b.omega_max_lumped();  // h sqrt(rho/E)
  SolverOptions o = newmark(0.5 * exact);
  EXPECT_EQ(Solver(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), o)
                .critical_dt(),
            0.0);
  o.scheme = nbm::TimeScheme::kExplicit;
  const Solver s(nbm_test::to_coo(a.M), nbm_test::to_coo(a.K), nbm_test::ground_contact(), o);
  EXPECT_NEAR(s.critical_dt(), exact, 1e-6 * exact);
  EXPECT_EQ(s.options().scheme, nbm::TimeScheme::kExplicit);
}

// ---------------------------------------------------------------- errors

struct SolverErrors : ::testing::Test {
  Bar b;
  nbm_test::Assembled a = assemble(b);
  CooMatrix M = nbm_test::to_coo(a.M), K = nbm_test::to_coo(a.K);
  nbm::ContactDescription c = nbm_test::ground_contact();
  StdVec F = nbm_test::to_std(a.F);
  StdVec u = StdVec(b.n_dofs(), 0.1), v = StdVec(b.n_dofs(), 0.0);

  void expect_construction_error(const SolverOptions& o, std::vector<std::string> parts) {
    expect_throw_with<nbm::InputError>([&] { Solver(M, K, c, o); }, parts);
  }
};

TEST_F(SolverErrors, TimeStep) {
  expect_construction_error(newmark(0.0), {"dt"});
  expect_construction_error(newmark(-1e-3), {"dt"});
  expect_construction_error(newmark(std::nan("")), {"dt"});
  SolverOptions o = newmark(std::nan(""));
  o.scheme = nbm::TimeScheme::kExplicit;
  expect_construction_error(o, {"dt"});
  o.dt = 1.0;  // far above the critical step
  expect_construction_error(o, {"dt", "critical"});
}

TEST_F(SolverErrors, SchemeAndNewmarkParameters) {
  SolverOptions o = newmark();
  o.beta = 0.75;
  expect_construction_error(o, {"beta"});
  o.beta = -0.1;
  expect_construction_error(o, {"beta"});
  o = newmark();
  o.gamma = 0.3;
  expect_construction_error(o, {"gamma"});
  o.gamma = 1.5;
  expect_construction_error(o, {"gamma"});
  // Newmark parameters have no meaning for central differences: an error,
  // not a silently ignored option.
  for (const char* name : {"beta", "gamma"}) {
    o = newmark(1e-4);
    o.scheme = nbm::TimeScheme::kExplicit;
    (std::string(name) == "beta" ? o.beta : o.gamma) = 0.5;
    expect_construction_error(o, {name, "explicit", "newmark"});
  }
}

TEST_F(SolverErrors, MassTreatment) {
  SolverOptions o = newmark();
  o.mass = nbm::MassTreatment::kRedistributed;  // without positions
  expect_construction_error(o, {"positions", "redistributed"});
  o.positions.assign(b.n_dofs() + 1, 0.0);
  expect_construction_error(o, {"positions", "size"});
  o.positions.resize(b.n_dofs());
  for (int i = 0; i < b.n_dofs(); ++i) o.positions[i] = i * b.h();
  EXPECT_NO_THROW(Solver(M, K, c, o));
  o.scheme = nbm::TimeScheme::kExplicit;
  o.dt = 1e-4;
  expect_construction_error(o, {"mass", "newmark"});
  o = newmark();
  o.positions.assign(b.n_dofs(), 0.0);
  expect_construction_error(o, {"positions", "consistent"});
}

TEST_F(SolverErrors, ADecoupledUnitRowIsAUnitSpring) {
  // Row and column N of K zeroed, 1 on the diagonal (what FreeFEM's on() with
  // tgv = -2 leaves): to the core a dof on a unit spring, accepted with or
  // without being fixed. The binding diagnoses tgv = -2 (dirichlet.hpp).
  CooMatrix K_d = K;
  for (std::size_t k = 0; k < K_d.value.size(); ++k) {
    if (K_d.i[k] == b.N || K_d.j[k] == b.N) K_d.value[k] = 0;
    if (K_d.i[k] == b.N && K_d.j[k] == b.N) K_d.value[k] = 1;
  }
  EXPECT_NO_THROW(Solver(M, K_d, c, newmark()));
  SolverOptions o = newmark();
  o.fixed = {b.N};
  EXPECT_NO_THROW(Solver(M, K_d, c, o));
}

TEST_F(SolverErrors, NonSquareMatricesAreReportedBeforeAnyDiagonalIsRead) {
  // M and K both 2n x n (a test space of another size): reported as such,
  // nothing read past the columns.
  CooMatrix M2 = M, K2 = K;
  M2.rows = K2.rows = 2 * M.rows;
  expect_throw_with<nbm::InputError>([&] { Solver(M2, K2, c, newmark()); }, {"not square"});
}

TEST_F(SolverErrors, MatrixShapes) {
  // Non-square: both M and K n x (n+1), so that their sizes agree.
  CooMatrix M2 = M, K2 = K;
  M2.cols = K2.cols = M.cols + 1;
  expect_throw_with<nbm::InputError>([&] { Solver(M2, K2, c, newmark()); }, {"K", "not square"});
  CooMatrix M_small = nbm_test::to_coo(assemble(Bar{1, 1, 100, 10, 10}).M);
  expect_throw_with<nbm::InputError>([&] { Solver(M_small, K, c, newmark()); },
                                     {"M", "differs from the size of K"});
  CooMatrix empty;
  expect_throw_with<nbm::InputError>([&] { Solver(M, empty, c, newmark()); }, {"K", "empty"});
  CooMatrix bad_index = K;
  bad_index.i[3] = K.rows;
  expect_throw_with<nbm::InputError>([&] { Solver(M, bad_index, c, newmark()); },
                                     {"K", "outside the matrix"});
  CooMatrix ragged = M;
  ragged.j.pop_back();
  expect_throw_with<nbm::InputError>([&] { Solver(ragged, K, c, newmark()); },
                                     {"M", "inconsistent"});
}

TEST_F(SolverErrors, MatrixEntries) {
  CooMatrix K_ns = K;
  for (std::size_t k = 0; k < K_ns.value.size(); ++k)
    if (K_ns.i[k] == 3 && K_ns.j[k] == 4) K_ns.value[k] *= 1.01;
  expect_throw_with<nbm::InputError>([&] { Solver(M, K_ns, c, newmark()); }, {"K", "symmetric"});
  CooMatrix M_nan = M;
  M_nan.value[5] = std::nan("");
  expect_throw_with<nbm::InputError>([&] { Solver(M_nan, K, c, newmark()); }, {"M", "non-finite"});
}

TEST_F(SolverErrors, InfiniteDiagonalIsNonFiniteNotAPenalty) {
  // An infinite diagonal is not a penalty: it must be reported as a
  // non-finite entry of K, also on the contact dof (not as "fixed dof").
  for (long d : {5L, 0L}) {
    CooMatrix K_inf = K;
    for (std::size_t k = 0; k < K_inf.value.size(); ++k)
      if (K_inf.i[k] == d && K_inf.j[k] == d) K_inf.value[k] = INFINITY;
    SCOPED_TRACE("diagonal " + std::to_string(d));
    expect_throw_with<nbm::InputError>([&] { Solver(M, K_inf, c, newmark()); },
                                       {"K", "non-finite"});
  }
}

TEST_F(SolverErrors, AsymmetryIsDetectedNextToPenaltiesOnFixedDofs) {
  // A fixed dof's diagonal holding a penalty (1e30, as on() leaves it): the
  // symmetry test of the remaining (free) part must not be scaled by it.
  // Here K(3,4) is 1% off K(4,3).
  CooMatrix K_ns = K;
  for (std::size_t k = 0; k < K_ns.value.size(); ++k) {
    if (K_ns.i[k] == 3 && K_ns.j[k] == 4) K_ns.value[k] *= 1.01;
    if (K_ns.i[k] == b.N && K_ns.j[k] == b.N) K_ns.value[k] = 1e30;
  }
  SolverOptions o = newmark();
  o.fixed = {b.N};
  expect_throw_with<nbm::InputError>([&] { Solver(M, K_ns, c, o); }, {"K", "symmetric"});
}

TEST_F(SolverErrors, ContactDescription) {
  nbm::ContactDescription empty;
  expect_throw_with<nbm::InputError>([&] { Solver(M, K, empty, newmark()); },
                                     {"contact set is empty"});
  nbm::ContactDescription bad = c;
  bad.normals = {0.5};
  expect_throw_with<nbm::InputError>([&] { Solver(M, K, bad, newmark()); }, {"normals"});
  SolverOptions o = newmark();
  o.fixed = {0};
  expect_throw_with<nbm::InputError>([&] { Solver(M, K, c, o); }, {"contact dofs", "fixed"});
  o.fixed = {b.N + 1};
  expect_throw_with<nbm::InputError>([&] { Solver(M, K, c, o); }, {"fixed", "outside"});
}

TEST_F(SolverErrors, SingularContactBlock) {
  // An extra dof with mass but no stiffness, made the contact dof: K_CC = 0.
  const int n = b.n_dofs() + 1;
  CooMatrix M3 = M, K3 = K;
  M3.rows = M3.cols = K3.rows = K3.cols = n;
  M3.i.push_back(n - 1);
  M3.j.push_back(n - 1);
  M3.value.push_back(1.0);
  nbm::ContactDescription c3;
  c3.dofs = {n - 1};
  c3.normals = {1.0};
  c3.gaps = {0.0};
  expect_throw_with<nbm::InputError>([&] { Solver(M3, K3, c3, newmark()); }, {"K_CC"});
}

TEST_F(SolverErrors, InitialState) {
  Solver s(M, K, c, newmark());
  EXPECT_FALSE(s.initialized());
  expect_throw_with<nbm::InputError>([&] { s.step(u, v, F); }, {"step", "initial"});
  StdVec pen = u;
  pen[0] = -1e-3;  // below the ground
  expect_throw_with<nbm::InputError>([&] { s.initialize(pen, v, F); }, {"penetration"});
  StdVec short_u(b.n_dofs() - 1, 0.1);
  expect_throw_with<nbm::InputError>([&] { s.initialize(short_u, v, F); }, {"u", "size"});
  StdVec v_nan = v;
  v_nan[2] = NAN;
  expect_throw_with<nbm::InputError>([&] { s.initialize(u, v_nan, F); }, {"v", "non-finite"});
  EXPECT_FALSE(s.initialized());
}

TEST_F(SolverErrors, StepArguments) {
  Solver s(M, K, c, newmark());
  s.initialize(u, v, F);
  s.step(u, v, F);
  StdVec F_short(F.begin(), F.end() - 1);
  expect_throw_with<nbm::InputError>([&] { s.step(u, v, F_short); }, {"F", "size"});
  StdVec F_nan = F;
  F_nan[1] = NAN;
  expect_throw_with<nbm::InputError>([&] { s.step(u, v, F_nan); }, {"F", "non-finite"});
  StdVec u_mod = u;
  u_mod[5] += 1e-9;
  expect_throw_with<nbm::InputError>([&] { s.step(u_mod, v, F); }, {"changed"});
  StdVec v_mod = v;
  v_mod[5] += 1e-9;
  expect_throw_with<nbm::InputError>([&] { s.step(u, v_mod, F); }, {"changed"});
  StdVec u_big = u;
  u_big.push_back(0.0);
  expect_throw_with<nbm::InputError>([&] { s.step(u_big, v, F); }, {"u", "resized"});
  StdVec v_small(v.begin(), v.end() - 1);
  expect_throw_with<nbm::InputError>([&] { s.step(u, v_small, F); }, {"v", "resized"});
  // After the failures the unchanged arrays still step, and a new
  // initialization accepts a modified state.
  EXPECT_NO_THROW(s.step(u, v, F));
  EXPECT_EQ(s.steps(), 2);
  EXPECT_NO_THROW(s.initialize(u_mod, v, F));
  EXPECT_EQ(s.steps(), 0);
}

}  // namespace
