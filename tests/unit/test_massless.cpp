// Mass redistribution and the massless-boundary Newmark scheme (method.md
// §4-5): the redistributed mass has no contact rows, keeps the total mass,
// momentum and centre of mass; the scheme keeps impenetrability and the nodal
// boundary relation exactly, conserves energy on steps without a switch, and
// its energy error through impacts vanishes as dt -> 0.
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
using Mat = Eigen::MatrixXd;

Mat bar_positions(const Bar& b) {
  Mat X(b.n_dofs(), 1);
  for (int i = 0; i < b.n_dofs(); ++i) X(i, 0) = i * b.h();
  return X;
}

Mat plate_positions(const Plate& p) {
  Mat X(p.n_dofs(), 2);
  for (int j = 0; j <= p.ny; ++j)
    for (int i = 0; i <= p.nx; ++i)
      for (int c = 0; c < 2; ++c) X.row(2 * p.node(i, j) + c) = p.position(i, j).transpose();
  return X;
}

// The position field as a displacement (component c of a dof: coordinate c).
Vec plate_coordinates(const Plate& p) {
  const Mat X = plate_positions(p);
  Vec x(p.n_dofs());
  for (int d = 0; d < p.n_dofs(); ++d) x(d) = X(d, d % 2);
  return x;
}

Vec plate_translation(const Plate& p, const Eigen::Vector2d& V) {
  Vec v(p.n_dofs());
  for (int node = 0; node < p.n_nodes(); ++node) v.segment<2>(2 * node) = V;
  return v;
}

TEST(MassRedistribution, ContactRowsVanishAndMassMomentumAndCentreArePreserved) {
  for (double angle : {0.0, 0.3}) {
    Plate p;
    p.angle = angle;
    p.nx = 6;
    p.ny = 3;
    Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
    const nbm::SparseMatrix Mr = nbm::redistributed_mass(*s.problem, s.a.M, plate_positions(p));
    const nbm::SparseMatrix& M = s.problem->M();
    SCOPED_TRACE("angle " + std::to_string(angle));
    for (nbm::Index c : s.problem->contact_index())
      EXPECT_EQ(Mat(Mr).col(c).cwiseAbs().maxCoeff(), 0.0);
    const Vec X = s.problem->to_internal(plate_coordinates(p));
    for (const Eigen::Vector2d& V : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), p.normal()}) {
      const Vec e = s.problem->to_internal(plate_translation(p, V));
      EXPECT_NEAR(e.dot(Mr * e), e.dot(M * e), 1e-13);                  // mass
      EXPECT_NEAR(e.dot(Mr * X), e.dot(M * X), 1e-13);                  // centre of mass
      EXPECT_NEAR(e.dot(Mr * e), p.rho * p.W * p.H * V.squaredNorm(), 1e-13);
    }
    // Positive semi-definite, definite on the interior dofs.
    const Eigen::VectorXd values = nbm::symmetric_eigen(Mat(Mr)).values;
    EXPECT_GE(values.minCoeff(), -1e-14);
    const int zero = static_cast<int>((values.array().abs() < 1e-12).count());
    EXPECT_EQ(zero, s.problem->n_contact());
  }
}

TEST(MassRedistribution, BarMovesTheEndMassInwardWithItsCentre) {
  // 1D: the end node's mass goes to the next nodes with weights (2, -1),
  // the only affine ones on the first ring that reproduces x = 0 (two nodes).
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  const Mat Mr(nbm::redistributed_mass(*s.problem, s.a.M, bar_positions(b)));
  const Vec e = s.problem->to_internal(Vec::Ones(b.n_dofs()));
  Vec x(b.n_dofs());
  for (int i = 0; i < b.n_dofs(); ++i) x(i) = i * b.h();
  const Vec xi = s.problem->to_internal(x);
  EXPECT_NEAR(e.dot(Mr * e), b.rho * b.L, 1e-14);
  EXPECT_NEAR(e.dot(Mr * xi), b.rho * b.L * b.L / 2, 1e-14);
  EXPECT_EQ(Mr.row(0).cwiseAbs().maxCoeff(), 0.0);
  // Far from the contact end the mass matrix is untouched.
  EXPECT_NEAR((Mr.bottomRightCorner(10, 10) - Mat(s.problem->M()).bottomRightCorner(10, 10))
                  .cwiseAbs()
                  .maxCoeff(),
              0.0, 1e-16);
}

TEST(MassRedistribution, BadInputIsReported) {
  Plate p;
  Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::redistributed_mass(*s.problem, s.a.M, Mat::Zero(3, 2)); }, {"positions"});
  Mat X = plate_positions(p);
  X(5, 1) = NAN;
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::redistributed_mass(*s.problem, s.a.M, X); }, {"positions", "non-finite"});
  // A mass matrix coupling the x and y dofs of contact node 0.
  nbm_test::Sparse Mc = s.a.M;
  Mc.coeffRef(0, 1) += 1e-3;
  Mc.coeffRef(1, 0) += 1e-3;
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::redistributed_mass(*s.problem, Mc, plate_positions(p)); },
      {"M", "components of contact node 0"});
  // All nodes on one line: no affine weights in 2D.
  Mat aligned = plate_positions(p);
  aligned.col(1).setZero();
  nbm_test::expect_throw_with<nbm::NumericalError>(
      [&] { nbm::redistributed_mass(*s.problem, s.a.M, aligned); }, {"affine weights"});
}

// Bouncing with the massless boundary: per step, impenetrability and the
// nodal boundary relation at the new interior displacement (complementarity
// of gaps and reactions), energy conserved exactly on steps without a switch.
struct MasslessRun {
  double max_switch_energy_jump = 0, final_drift = 0;
  int switches = 0, closed_steps = 0;
};

MasslessRun bounce_massless(Simulation& s, int steps, double energy_scale) {
  MasslessRun run;
  const double e0 = s.stepper->energies().total();
  for (int k = 1; k <= steps; ++k) {
    const nbm::ActiveSet before = s.stepper->active();
    const double e_before = s.stepper->energies().total();
    s.step();
    nbm_test::expect_exact_contact(*s.stepper, 0.1, k);
    const double e = s.stepper->energies().total();
    if (s.stepper->active() == before) {
      EXPECT_NEAR(e, e_before, 1e-12 * energy_scale) << "step " << k;
    } else {
      ++run.switches;
      run.max_switch_energy_jump = std::max(run.max_switch_energy_jump, std::abs(e - e_before));
    }
    for (bool c : s.stepper->active()) run.closed_steps += c;
    run.final_drift = std::abs(e - e0) / energy_scale;
  }
  return run;
}

TEST(MasslessNewmark, BarBouncesWithExactContactAndEnergyErrorOnlyAtSwitches) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  s.massless(1e-3, bar_positions(b));
  s.initialize(Vec::Constant(b.n_dofs(), 0.1), Vec::Zero(b.n_dofs()));
  const MasslessRun run = bounce_massless(s, 1000, b.rho * b.L * b.g * 0.1);
  EXPECT_GT(run.closed_steps, 20);
  EXPECT_GE(run.switches, 2);
}

TEST(MasslessNewmark, PlateOnAnInclinedPlane) {
  Plate p;
  p.angle = 0.3;
  Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
  s.massless(1e-3, plate_positions(p));
  s.initialize(Vec::Zero(p.n_dofs()), Vec::Zero(p.n_dofs()));
  const MasslessRun run = bounce_massless(s, 400, p.rho * p.W * p.H * p.g * 0.02);
  EXPECT_GT(run.closed_steps, 20);
  EXPECT_GE(run.switches, 2);
}

TEST(MasslessNewmark, EnergyErrorThroughImpactsVanishesAsDtDecreases) {
  // The plate bounces on the inclined plane for 0.6 time units (two impacts);
  // the largest energy error (relative to m g gap) must decrease at every
  // refinement of dt, faster than dt.
  Plate p;
  p.angle = 0.3;
  std::vector<double> drift;
  for (double dt : {2e-3, 1e-3, 5e-4, 2.5e-4}) {
    Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
    s.massless(dt, plate_positions(p));
    s.initialize(Vec::Zero(p.n_dofs()), Vec::Zero(p.n_dofs()));
    const double e0 = s.stepper->energies().total();
    double worst = 0;
    for (int k = 0; k < static_cast<int>(0.6 / dt); ++k) {
      s.step();
      worst = std::max(worst, std::abs(s.stepper->energies().total() - e0));
    }
    drift.push_back(worst / (p.rho * p.W * p.H * p.g * 0.02));
  }
  for (std::size_t i = 1; i < drift.size(); ++i) {
    SCOPED_TRACE("refinement " + std::to_string(i) + ": " + std::to_string(drift[i - 1]) +
                 " -> " + std::to_string(drift[i]));
    EXPECT_LT(drift[i], 0.5 * drift[i - 1]);
  }
  std::cout << "massless plate, max energy error / (m g gap) for dt = 2e-3 ... 2.5e-4:";
  for (double d : drift) std::cout << " " << d;
  std::cout << std::endl;
}

TEST(MasslessNewmark, FreeFallOfTheCentreOfMassIsExact) {
  // Translations are test functions of the reduced equations: the momentum
  // e'M'v of the redistributed mass follows -m g t exactly.
  Plate p;
  p.angle = 0.3;
  Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.05));
  s.massless(1e-3, plate_positions(p));
  s.initialize(Vec::Zero(p.n_dofs()), Vec::Zero(p.n_dofs()));
  const Vec e = s.problem->to_internal(plate_translation(p, -p.normal()));
  const double m = p.rho * p.W * p.H;
  const double c0 = e.dot(s.problem->M() * s.stepper->u()) / m;
  for (int k = 1; k <= 50; ++k) {
    s.step();
    ASSERT_EQ(std::count(s.stepper->active().begin(), s.stepper->active().end(), true), 0);
    const double t = k * 1e-3;
    EXPECT_NEAR(e.dot(s.problem->M() * s.stepper->u()) / m, c0 - 0.5 * p.g * t * t, 1e-12);
    EXPECT_NEAR(e.dot(s.problem->M() * s.stepper->v()) / m, -p.g * t, 1e-12);
  }
}

TEST(MasslessNewmark, RecomputedContactColumnsStepAsKeptOnes) {
  // Y = L^-1 P E_C kept or not (the second solve of a step with contact
  // forces instead of the products with Y): the same steps to round-off, the
  // same active sets, through impacts on the inclined plane, undamped and
  // with stiffness-proportional damping (the contact rows' scale s).
  Plate p;
  p.angle = 0.3;
  const Eigen::MatrixXd positions = plate_positions(p);
  for (const double b_K : {0.0, 1e-3}) {
    SCOPED_TRACE("b_K = " + std::to_string(b_K));
    Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
    const nbm::ContactProblem problem(s.a.M, s.a.K, s.problem->contacts(), s.problem->fixed(),
                                      &positions);
    nbm::Damping damping;
    damping.b_K = b_K;
    nbm::MasslessNewmarkStepper kept(problem, 1e-3, {}, damping,
                                     nbm::ContactColumns::kKept),
        recomputed(problem, 1e-3, {}, damping, nbm::ContactColumns::kRecomputed);
    EXPECT_TRUE(kept.keeps_contact_columns());
    EXPECT_FALSE(recomputed.keeps_contact_columns());
    const Vec F = problem.to_internal(s.a.F), zero = Vec::Zero(problem.size());
    kept.initialize(zero, zero, F);
    recomputed.initialize(zero, zero, F);
    int closed_steps = 0;
    for (int k = 1; k <= 400; ++k) {
      kept.step(F);
      recomputed.step(F);
      ASSERT_EQ(kept.active(), recomputed.active()) << "step " << k;
      closed_steps += std::count(kept.active().begin(), kept.active().end(), true) > 0;
      for (const auto& [x, y] : {std::pair{&kept.u(), &recomputed.u()},
                                 std::pair{&kept.v(), &recomputed.v()},
                                 std::pair{&kept.a(), &recomputed.a()}})
        EXPECT_LE((*x - *y).cwiseAbs().maxCoeff(), 1e-11 * x->cwiseAbs().maxCoeff())
            << "step " << k;
    }
    EXPECT_GT(closed_steps, 20);
  }
}

TEST(MasslessNewmark, RequiresAMasslessBoundary) {
  const Bar b;
  Simulation s(assemble(b), nbm_test::ground_contact());
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { nbm::MasslessNewmarkStepper(*s.problem, 1e-3); }, {"M_CC = 0"});
}

}  // namespace
