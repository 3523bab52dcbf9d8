// CentralDifferenceStepper (lumped mass) and its stability estimate:
// the critical time step of the P1 bar in closed form, exact free fall,
// approximate energy conservation, impenetrability, and max_eigenvalue
// against a dense eigen-solve.
#include <gtest/gtest.h>


#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Bar;
using nbm_test::Plate;
using nbm_test::Simulation;
using Vec = Eigen::VectorXd;

constexpr double kH0 = 0.1;

// Exact critical step of the free-free P1 bar with row-sum lumped mass:
// omega_max^2 = 4E/(rho h^2) (the lumped chain with half masses at the ends
// is half of a periodic chain), so dt_crit = 2/omega_max = h sqrt(rho/E).
double exact_critical_dt(const Bar& b) { return 2.0 / b.omega_max_lumped(); }

// Contact at the top end x = L, outward normal +1 (a ceiling): no sign flip
// of the contact dof.
nbm::ContactDescription ceiling_contact(const Bar& b) {
  nbm::ContactDescription c;
  c.dofs = {b.N};
  c.normals = {1.0};
  c.gaps = {0.5};
  return c;
}

TEST(ExplicitCriticalStep, BarWithCeilingContactMatchesClosedForm) {
  const Bar b;
  Simulation s(assemble(b), ceiling_contact(b));
  auto& cd = s.explicit_scheme(0.5 * exact_critical_dt(b));
  EXPECT_NEAR(cd.critical_dt(), exact_critical_dt(b), 1e-6 * exact_critical_dt(b));
}

TEST(ExplicitCriticalStep, BarWithGroundContactMatchesClosedForm) {
  // Same bar, contact at x = 0 with outward normal -1. The lumped mass is a
  // property of the bar, not of the orientation of its contact dof.
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  auto& cd = s.explicit_scheme(0.5 * exact_critical_dt(b));
  EXPECT_NEAR(cd.critical_dt(), exact_critical_dt(b), 1e-6 * exact_critical_dt(b));
}

TEST(ExplicitCriticalStep, ClampedBarMatchesClosedForm) {
  // Bar clamped at x = L (dof N fixed), free at x = 0. Lumping the assembled
  // mass gives rho h/2 at x = 0 and rho h at every other free node (the mass
  // of a node does not depend on its neighbour being clamped). This chain is
  // the symmetric half of a fixed-fixed chain of 2N intervals, whose top
  // symmetric mode has omega^2 = 4E/(rho h^2) sin^2((2N - 1) pi / (4N)).
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact(0.02), {b.N});
  auto& cd = s.explicit_scheme(1e-4);
  const double w2 = 4 * b.E / (b.rho * b.h() * b.h()) *
                    std::pow(std::sin((2 * b.N - 1) * M_PI / (4 * b.N)), 2);
  EXPECT_NEAR(cd.critical_dt(), 2 / std::sqrt(w2), 1e-6 * 2 / std::sqrt(w2));
}

TEST(ExplicitCriticalStep, TimeStepAboveCriticalIsRejected) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { s.explicit_scheme(1.001 * exact_critical_dt(b)); }, {"dt", "critical"});
  EXPECT_NO_THROW(s.explicit_scheme(0.999 * exact_critical_dt(b)));
}

TEST(ExplicitCriticalStep, LumpedMassIsRowSumWhateverTheNormal) {
  // Row sums of the P1 consistent bar mass: rho h/2 at the ends, rho h inside,
  // also on a contact dof whose rotation flips its sign (normal -1).
  const Bar b;
  for (const auto& contact : {ceiling_contact(b), nbm_test::ground_contact()}) {
    Simulation s(assemble(b), contact);
    const Vec m = s.problem->lumped_mass();
    EXPECT_NEAR(m(0), b.rho * b.h() / 2, 1e-15);
    EXPECT_NEAR(m(b.N), b.rho * b.h() / 2, 1e-15);
    for (int i = 1; i < b.N; ++i) EXPECT_NEAR(m(i), b.rho * b.h(), 1e-15);
  }
}

TEST(ExplicitCriticalStep, LumpedMassOfTheProblemIsTheBodyMass) {
  // Whatever the rotation of the contact dofs, a rigid translation with
  // velocity V has the kinetic energy m V^2 / 2 under the lumped mass. (The
  // open contacts keep the translation: stiffness rows annihilate it.)
  Plate p;
  p.angle = 0.3;
  Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
  s.explicit_scheme(1e-5);
  for (const Eigen::Vector2d& V : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), p.normal()}) {
    Vec v(p.n_dofs());
    for (int node = 0; node < p.n_nodes(); ++node) v.segment<2>(2 * node) = V;
    s.initialize(Vec::Zero(p.n_dofs()), v);
    EXPECT_LE((s.v() - v).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_NEAR(s.stepper->energies().kinetic, 0.5 * p.rho * p.W * p.H, 1e-13);
  }
}

TEST(ExplicitCriticalStep, ContactNodeWithUnequalComponentMassesIsRejected) {
  // A rotated node whose x and y components carry different lumped masses
  // would have a non-diagonal rotated mass: reported, naming M.
  Plate p;
  p.angle = 0.3;
  nbm_test::Assembled a = assemble(p);
  const nbm::ContactDescription c = nbm_test::bottom_contact(p, 0.02);
  a.M.coeffRef(c.dofs[0], c.dofs[0]) *= 1.5;
  Simulation s(a, c);
  nbm_test::expect_throw_with<nbm::InputError>([&] { s.explicit_scheme(1e-5); },
                                               {"M", "contact node 0", "lumped"});
}

// ------------------------------------------------------------ max_eigenvalue

TEST(ExplicitMaxEigenvalue, MatchesDenseEigenSolveAndStaysBelowGershgorin) {
  for (int seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    const int n = 6 + seed % 7;
    // Sparse-ish SPD K: random SPD with small entries dropped, plus a shift.
    Eigen::MatrixXd Kd = nbm_test::random_spd(n, 50.0, rng);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)  // symmetric rule: keeps K symmetric
        if (i != j && std::abs(Kd(i, j)) < 0.2 * std::sqrt(Kd(i, i) * Kd(j, j))) Kd(i, j) = 0;
    Kd += n * Eigen::MatrixXd::Identity(n, n);  // keep it positive definite
    const nbm_test::Sparse K = Kd.sparseView();
    std::uniform_real_distribution<double> U(0.5, 2.0);
    Vec m(n);
    for (int i = 0; i < n; ++i) m(i) = U(rng);
    const double exact =
        nbm::generalized_symmetric_eigen(Kd, Eigen::MatrixXd(m.asDiagonal())).values.maxCoeff();
    // Gershgorin bound of D^{-1/2} K D^{-1/2}, computed here.
    double gershgorin = 0;
    for (int i = 0; i < n; ++i) {
      double r = 0;
      for (int j = 0; j < n; ++j) r += std::abs(Kd(i, j)) / std::sqrt(m(i) * m(j));
      gershgorin = std::max(gershgorin, r);
    }
    const double est = nbm::max_eigenvalue(K, m);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_LE(est, gershgorin * (1 + 1e-14));
    EXPECT_NEAR(est, exact, 1e-6 * exact);
  }
}

TEST(ExplicitMaxEigenvalue, DiagonalCaseIsExact) {
  Vec m(3);
  m << 1, 2, 4;
  Eigen::MatrixXd Kd = Eigen::MatrixXd::Zero(3, 3);
  Kd.diagonal() << 3, 10, 4;  // eigenvalues 3, 5, 1
  // Power iteration stops on a relative change of 1e-10: accurate to ~1e-9.
  const double est = nbm::max_eigenvalue(Kd.sparseView(), m);
  EXPECT_NEAR(est, 5.0, 1e-8 * 5.0);
  EXPECT_LE(est, 5.0 * (1 + 1e-15));
  EXPECT_EQ(nbm::max_eigenvalue(nbm_test::Sparse(0, 0), Vec(0)), 0.0);
}

// -------------------------------------------------------------- dynamics

// Central differences integrate a constant acceleration exactly, and the
// lumped total momentum obeys m c'' = -m g while the contact is open.
void check_explicit_free_fall(const nbm::ContactDescription& contact, double c0_expected) {
  const Bar b;
  const double dt = 0.5 * exact_critical_dt(b);
  Simulation s(assemble(b), contact);
  s.explicit_scheme(dt);
  s.initialize(Vec::Constant(b.n_dofs(), kH0), Vec::Zero(b.n_dofs()));
  const Vec e1 = Vec::Ones(1);
  const double c0 = s.centre(s.u(), e1);
  EXPECT_NEAR(c0, c0_expected, 1e-14);
  const int steps = static_cast<int>(0.1 / dt);
  for (int k = 1; k <= steps; ++k) {
    s.step();
    const double t = k * dt;
    ASSERT_FALSE(s.stepper->active()[0]);
    EXPECT_NEAR(s.centre(s.u(), e1), c0 - 0.5 * b.g * t * t, 1e-10 * kH0) << "t = " << t;
    EXPECT_NEAR(s.centre(s.v(), e1), -b.g * t, 1e-10) << "t = " << t;
  }
}

TEST(ExplicitBar, FreeFallOfTheCentreOfMassIsExactWithGroundContact) {
  // The open contact node 0 sits where its stiffness row balances its load:
  // u_0 = h0 - rho g h^2/(2E), which moves the centre by (h/2L) of that.
  const Bar b;
  check_explicit_free_fall(nbm_test::ground_contact(),
                           kH0 - (b.h() / (2 * b.L)) * b.rho * b.g * b.h() * b.h() / (2 * b.E));
}

TEST(ExplicitBar, FreeFallOfTheCentreOfMassIsExactWithCeilingContact) {
  // Contact node N: (E/h)(u_N - u_{N-1}) = -rho g h/2, the same shift.
  const Bar b;
  check_explicit_free_fall(ceiling_contact(b),
                           kH0 - (b.h() / (2 * b.L)) * b.rho * b.g * b.h() * b.h() / (2 * b.E));
}

TEST(ExplicitBar, FreeFlightConservesEnergyApproximately) {
  // Central differences conserve a modified energy: the physical one (with
  // the lumped mass) stays within O((omega dt)^2) of the vibration energy.
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  s.explicit_scheme(0.5 * exact_critical_dt(b));
  s.initialize(Vec::Constant(b.n_dofs(), kH0), Vec::Zero(b.n_dofs()));
  const double scale = b.rho * b.L * b.g * kH0;
  const double e0 = s.stepper->energies().total();
  for (int k = 1; k * s.stepper->dt() <= 0.1; ++k) {
    s.step();
    EXPECT_NEAR(s.stepper->energies().total(), e0, 1e-3 * scale) << "step " << k;
  }
  EXPECT_GT(s.stepper->energies().kinetic, 0.3 * scale);
}

TEST(ExplicitBar, StableAndImpenetrableThroughBounces) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  s.explicit_scheme(0.9 * exact_critical_dt(b));
  s.initialize(Vec::Constant(b.n_dofs(), kH0), Vec::Zero(b.n_dofs()));
  int closed = 0;
  for (int k = 1; k * s.stepper->dt() <= 1.0; ++k) {
    const nbm::StepReport r = s.step();
    EXPECT_EQ(r.active_set_iterations, 1);
    EXPECT_FALSE(r.fallback);
    const Vec u = s.u();
    EXPECT_GE(u(0), -1e-12 * kH0) << "step " << k;  // n.u = -u_0 <= 0
    EXPECT_GE(s.stepper->gaps()(0), -1e-12 * kH0);
    EXPECT_LE(u.cwiseAbs().maxCoeff(), 2 * kH0);  // no blow-up
    closed += s.stepper->active()[0];
  }
  EXPECT_GT(closed, 10);
}

TEST(ExplicitPlate, StableAndImpenetrableWithInclinedContact) {
  Plate p;
  p.angle = 0.3;
  const nbm::ContactDescription c = nbm_test::bottom_contact(p, 0.02);
  Simulation s(assemble(p), c);
  // The estimate is checked on the bar; here it only has to be usable.
  const double dt_guess = 1e-4;
  auto& cd = s.explicit_scheme(dt_guess);
  const double dt = 0.8 * cd.critical_dt();
  s.explicit_scheme(dt);
  s.initialize(Vec::Zero(p.n_dofs()), Vec::Zero(p.n_dofs()));
  const Eigen::Vector2d n = p.normal();
  const double c0 = s.centre(s.u(), n);
  int closed = 0;
  for (int k = 1; k * dt <= 0.4; ++k) {
    s.step();
    const Vec u = s.u();
    for (int node : p.bottom_nodes())
      EXPECT_LE(n.dot(u.segment<2>(2 * node)), 0.02 + 1e-12 * 0.02) << "step " << k;
    EXPECT_LE(u.cwiseAbs().maxCoeff(), 0.1);
    for (bool a : s.stepper->active()) closed += a;
    if (closed == 0) {  // still in flight: exact free fall along n
      const double t = k * dt;
      EXPECT_NEAR(s.centre(u, n), c0 + 0.5 * p.g * t * t, 1e-10 * 0.02);
    }
  }
  EXPECT_GT(closed, 0);
}

TEST(ExplicitErrors, StepBeforeInitializeAndBadTimeStep) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  s.explicit_scheme(0.5 * exact_critical_dt(b));
  nbm_test::expect_throw_with<nbm::InputError>([&] { s.step(); }, {"step"});
  nbm_test::expect_throw_with<nbm::InputError>([&] { s.explicit_scheme(-1.0); }, {"dt"});
}

}  // namespace
