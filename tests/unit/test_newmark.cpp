// NewmarkStepper on a 1D bar falling on the ground and on a rotated 2D
// plane-strain plate falling on an inclined plane: exact free fall, energy
// conservation within a fixed active set, impenetrability, numerical
// dissipation of the other parameters, and the step reports.
#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Bar;
using nbm_test::Plate;
using nbm_test::Simulation;
using Vec = Eigen::VectorXd;

constexpr double kH0 = 0.1;  // initial height of the bar above the ground

Simulation falling_bar(const Bar& b = {}) { return Simulation(assemble(b), nbm_test::ground_contact()); }

// Bar at height h0 (uniform), at rest.
void start_bar(Simulation& s, double h0 = kH0) {
  s.initialize(Vec::Constant(s.a.K.rows(), h0), Vec::Zero(s.a.K.rows()));
}

// Plate at distance `gap` above the inclined plane, at rest, undeformed.
Simulation falling_plate(const Plate& p, double gap) {
  return Simulation(assemble(p), nbm_test::bottom_contact(p, gap));
}
void start_plate(Simulation& s) { s.initialize(Vec::Zero(s.a.K.rows()), Vec::Zero(s.a.K.rows())); }

// Largest violation of n.u <= g over the contact nodes, in user coordinates.
double penetration(const Simulation& s, const nbm::ContactDescription& c) {
  const Vec u = s.u();
  const int dim = static_cast<int>(c.dofs.size() / c.gaps.size());
  double worst = -INFINITY;
  for (std::size_t k = 0; k < c.gaps.size(); ++k) {
    double un = 0;
    for (int j = 0; j < dim; ++j) un += c.normals[k * dim + j] * u(c.dofs[k * dim + j]);
    worst = std::max(worst, un - c.gaps[k]);
  }
  return worst;
}

// ------------------------------------------------------------- free fall

TEST(NewmarkBar, InitialContactDisplacementFollowsTheNodalBoundaryRelation) {
  // Open contact: the stiffness row of node 0 is in equilibrium with its load,
  // (E/h)(u_0 - u_1) = -rho g h / 2, hence u_0 = h0 - rho g h^2 / (2E).
  const Bar b;
  Simulation s = falling_bar(b);
  s.newmark(1e-3);
  start_bar(s);
  const Vec u = s.u();
  EXPECT_NEAR(u(0), kH0 - b.rho * b.g * b.h() * b.h() / (2 * b.E), 1e-15);
  for (int i = 1; i <= b.N; ++i) EXPECT_EQ(u(i), kH0);
  EXPECT_FALSE(s.stepper->active()[0]);
  EXPECT_NEAR(s.stepper->reactions()(0), 0.0, 1e-14);
  EXPECT_NEAR(s.stepper->gaps()(0), u(0), 1e-15);  // gap = 0 - n.u = u_0
}

TEST(NewmarkBar, FreeFallOfTheCentreOfMassIsExact) {
  // The reduced equations conserve the total momentum balance m c'' = -m g
  // (1'K = 0, and the open-contact constraint row K_0 annihilates 1), and
  // Newmark integrates a constant acceleration exactly for any beta, gamma.
  const Bar b;
  const double dt = 1e-3;
  const double c0 = kH0 - (b.h() / (2 * b.L)) * b.rho * b.g * b.h() * b.h() / (2 * b.E);
  for (auto [beta, gamma] : {std::pair{0.25, 0.5}, {0.3025, 0.6}, {0.5, 1.0}}) {
    SCOPED_TRACE("beta = " + std::to_string(beta) + ", gamma = " + std::to_string(gamma));
    Simulation s = falling_bar(b);
    s.newmark(dt, {beta, gamma});
    start_bar(s);
    const Vec e1 = Vec::Ones(1);
    EXPECT_NEAR(s.centre(s.u(), e1), c0, 1e-15);
    for (int n = 1; n <= 100; ++n) {  // t = 0.1 s < time of impact (0.14 s)
      s.step();
      const double t = n * dt;
      ASSERT_FALSE(s.stepper->active()[0]) << "contact closed during free flight";
      EXPECT_NEAR(s.centre(s.u(), e1), c0 - 0.5 * b.g * t * t, 1e-10 * kH0) << "t = " << t;
      EXPECT_NEAR(s.centre(s.v(), e1), -b.g * t, 1e-10 * b.g * 0.1) << "t = " << t;
      EXPECT_NEAR(s.centre(s.acc(), e1), -b.g, 1e-10 * b.g) << "t = " << t;
      EXPECT_NEAR(s.stepper->time(), t, 1e-15);
    }
  }
}

TEST(NewmarkBar, FreeFlightConservesEnergy) {
  const Bar b;
  Simulation s = falling_bar(b);
  s.newmark(1e-3);
  start_bar(s);
  const double scale = b.rho * b.L * b.g * kH0;  // m g h0
  const double e0 = s.energy();
  for (int n = 1; n <= 100; ++n) {
    s.step();
    ASSERT_FALSE(s.stepper->active()[0]);
    const nbm::Energies e = s.stepper->energies();
    // The stepper's energies are the physical ones (independent formulas).
    const Vec u = s.u(), v = s.v();
    EXPECT_NEAR(e.kinetic, 0.5 * v.dot(s.a.M * v), 1e-13 * scale);
    EXPECT_NEAR(e.elastic, 0.5 * u.dot(s.a.K * u), 1e-13 * scale);
    EXPECT_NEAR(e.load, -s.a.F.dot(u), 1e-13 * scale);
    EXPECT_NEAR(e.total(), e0, 1e-10 * scale) << "step " << n;
  }
  // Energy did move between its forms: the test is not vacuous.
  EXPECT_GT(s.stepper->energies().kinetic, 0.3 * scale);
}

TEST(NewmarkBar, StaticEquilibriumOnTheGroundIsKeptAndReactionIsTheWeight) {
  // Standing bar: u(x) = -(rho g / E)(L x - x^2/2), nodally exact for P1.
  // Released at rest in this state it stays there; the reaction is m g.
  const Bar b;
  Simulation s = falling_bar(b);
  s.newmark(2e-3);
  Vec u(b.n_dofs());
  for (int i = 0; i <= b.N; ++i) {
    const double x = i * b.h();
    u(i) = -(b.rho * b.g / b.E) * (b.L * x - x * x / 2);
  }
  s.initialize(u, Vec::Zero(b.n_dofs()));
  const double weight = b.rho * b.L * b.g;
  for (int n = 0; n < 100; ++n) {
    ASSERT_TRUE(s.stepper->active()[0]);
    EXPECT_NEAR(s.stepper->reactions()(0), weight, 1e-11 * weight);
    EXPECT_LE((s.u() - u).cwiseAbs().maxCoeff(), 1e-12 * u.cwiseAbs().maxCoeff());
    EXPECT_LE(s.v().cwiseAbs().maxCoeff(), 1e-10);
    s.step();
  }
}

TEST(NewmarkBar, LongContactPhaseConservesEnergy) {
  // Bar released unstressed on the ground: it stays in contact (reaction
  // >= rho g h / 2 > 0) and vibrates; the active set never changes.
  const Bar b;
  Simulation s = falling_bar(b);
  s.newmark(1e-3);
  start_bar(s, 0.0);
  const double e0 = s.energy();  // zero: undeformed, at rest, on the ground
  // Energy scale: the weight times the static compression of the top.
  const double scale = (b.rho * b.L * b.g) * (b.rho * b.g * b.L * b.L / (2 * b.E));
  double kinetic = 0;
  for (int n = 1; n <= 2000; ++n) {  // 2 s: five fundamental periods 4L/c
    s.step();
    ASSERT_TRUE(s.stepper->active()[0]) << "contact opened at step " << n;
    kinetic = std::max(kinetic, s.stepper->energies().kinetic);
    EXPECT_NEAR(s.stepper->energies().total(), e0, 1e-10 * scale) << "step " << n;
  }
  EXPECT_GT(kinetic, 0.1 * scale);  // it did vibrate
}

// ------------------------------------------------------------- 2D plate

// Initial state of the plate solved independently: bottom node k moves by
// delta_k along n so that n.(F - K u)_k = 0 (open contacts, tangential parts
// untouched).
Vec plate_initial_state(const Plate& p, const nbm_test::Assembled& a) {
  const std::vector<int> bottom = p.bottom_nodes();
  const int m = static_cast<int>(bottom.size());
  const Eigen::Vector2d n = p.normal();
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(a.K.rows(), m);  // columns: n at node k
  for (int k = 0; k < m; ++k) N.block<2, 1>(2 * bottom[k], k) = n;
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(a.K);
  const Vec delta = (N.transpose() * Kd * N).ldlt().solve(N.transpose() * a.F);
  return N * delta;
}

TEST(NewmarkPlate, InitialStateAndFreeFallAreExactWithRotatedNormals) {
  Plate p;
  p.angle = 0.3;
  const nbm_test::Assembled a = assemble(p);
  const Vec u0 = plate_initial_state(p, a);
  Simulation s = falling_plate(p, 0.05);
  s.newmark(1e-3);
  start_plate(s);
  EXPECT_LE((s.u() - u0).cwiseAbs().maxCoeff(), 1e-13 * u0.cwiseAbs().maxCoeff());
  // Free fall along n, none along the tangent: c(t) = c(0) + n g t^2 / 2.
  const Eigen::Vector2d n = p.normal(), t_dir(-n.y(), n.x());
  const double cn0 = s.centre(u0, n), ct0 = s.centre(u0, t_dir);
  const double scale = 0.05;
  for (int k = 1; k <= 80; ++k) {  // impact at about t = 0.1 s
    s.step();
    const double t = k * 1e-3;
    for (bool closed : s.stepper->active()) ASSERT_FALSE(closed);
    EXPECT_NEAR(s.centre(s.u(), n), cn0 + 0.5 * p.g * t * t, 1e-10 * scale);
    EXPECT_NEAR(s.centre(s.u(), t_dir), ct0, 1e-10 * scale);
    EXPECT_NEAR(s.centre(s.v(), n), p.g * t, 1e-10 * p.g * 0.1);
  }
}

TEST(NewmarkPlate, FreeFlightConservesEnergy) {
  Plate p;
  p.angle = -0.4;
  Simulation s = falling_plate(p, 0.05);
  s.newmark(2e-3);
  start_plate(s);
  const double scale = p.rho * p.W * p.H * p.g * 0.05;
  const double e0 = s.stepper->energies().total();
  EXPECT_NEAR(e0, s.energy(), 1e-13 * scale);
  for (int k = 1; k <= 40; ++k) {
    s.step();
    for (bool closed : s.stepper->active()) ASSERT_FALSE(closed);
    EXPECT_NEAR(s.stepper->energies().total(), e0, 1e-10 * scale) << "step " << k;
    EXPECT_NEAR(s.stepper->energies().total(), s.energy(), 1e-12 * scale);
  }
}

TEST(NewmarkPlate, MotionIsRotationInvariant) {
  // The same plate in a frame rotated by a: its displacements are those of
  // the unrotated plate, rotated. Exercises normals (0,-1) and (sin a,-cos a).
  Plate p0, pa;
  pa.angle = 0.7;
  Simulation s0 = falling_plate(p0, 0.02), sa = falling_plate(pa, 0.02);
  s0.newmark(2e-3);
  sa.newmark(2e-3);
  start_plate(s0);
  start_plate(sa);
  const Eigen::Matrix2d R = pa.rotation();
  double u_scale = 0.02;
  for (int k = 0; k <= 150; ++k) {  // through the first impact
    if (k > 0) {
      s0.step();
      sa.step();
    }
    ASSERT_EQ(s0.stepper->active(), sa.stepper->active()) << "step " << k;
    const Vec u0 = s0.u(), ua = sa.u();
    u_scale = std::max(u_scale, u0.cwiseAbs().maxCoeff());
    for (int node = 0; node < p0.n_nodes(); ++node)
      EXPECT_LE((ua.segment<2>(2 * node) - R * u0.segment<2>(2 * node)).norm(), 1e-9 * u_scale)
          << "step " << k << ", node " << node;
  }
  bool touched = false;
  for (bool c : s0.stepper->active()) touched |= c;
  EXPECT_TRUE(touched) << "the plate should be on the plane at the end";
}

// ----------------------------------------------- energy and active sets

// Runs a bouncing simulation and checks, step by step: impenetrability, and
// exact energy conservation on every step whose active set did not change
// (the reduced system is then linear and Lagrangian, average acceleration
// conserves its energy). Returns the number of such steps.
struct BounceStats {
  int steps_same_set = 0, steps_changed = 0, fallbacks = 0, closed_steps = 0;
};
BounceStats bounce(Simulation& s, const nbm::ContactDescription& c, int steps, bool conserving) {
  BounceStats st;
  double u_scale = 0;
  for (double g : c.gaps) u_scale = std::max(u_scale, std::abs(g));
  double e_scale = std::abs(s.energy());
  for (int k = 1; k <= steps; ++k) {
    const nbm::ActiveSet before = s.stepper->active();
    const double e_before = s.stepper->energies().total();
    const nbm::StepReport r = s.step();
    const nbm::ActiveSet& after = s.stepper->active();
    u_scale = std::max(u_scale, s.u().cwiseAbs().maxCoeff());
    e_scale = std::max({e_scale, s.stepper->energies().kinetic, s.stepper->energies().elastic});
    EXPECT_LE(penetration(s, c), 1e-12 * u_scale) << "step " << k;
    EXPECT_GE(s.stepper->gaps().minCoeff(), -1e-12 * u_scale) << "step " << k;
    EXPECT_GE(r.active_set_iterations, 1);
    for (std::size_t i = 0; i < after.size(); ++i) st.closed_steps += after[i];
    if (r.fallback) ++st.fallbacks;
    if (before == after && !r.fallback) {
      ++st.steps_same_set;
      // The first guess is the old set; if it is consistent, one solve.
      EXPECT_EQ(r.active_set_iterations, 1) << "step " << k;
      if (conserving) {
        EXPECT_NEAR(s.stepper->energies().total(), e_before, 1e-12 * e_scale) << "step " << k;
      }
    } else {
      ++st.steps_changed;
      if (!r.fallback) {
        EXPECT_GE(r.active_set_iterations, 2) << "step " << k;
      }
    }
  }
  return st;
}

TEST(NewmarkBar, BouncingConservesEnergyBetweenActiveSetChangesAndNeverPenetrates) {
  Simulation s = falling_bar();
  s.newmark(1e-3);
  start_bar(s);
  const BounceStats st = bounce(s, nbm_test::ground_contact(), 1000, true);
  EXPECT_GT(st.closed_steps, 20);   // it did touch down
  EXPECT_GE(st.steps_changed, 2);   // and lifted off again
  EXPECT_GT(st.steps_same_set, 900);
}

TEST(NewmarkPlate, BouncingConservesEnergyBetweenActiveSetChangesAndNeverPenetrates) {
  Plate p;
  p.angle = 0.3;
  Simulation s = falling_plate(p, 0.02);
  s.newmark(1e-3);
  start_plate(s);
  const BounceStats st = bounce(s, nbm_test::bottom_contact(p, 0.02), 600, true);
  EXPECT_GT(st.closed_steps, 20);
  EXPECT_GE(st.steps_changed, 2);
  EXPECT_GT(st.steps_same_set, 400);
}

TEST(NewmarkImpenetrability, HoldsForSeveralTimeStepsAndParameters) {
  struct Case {
    double dt, beta, gamma;
  };
  for (const Case& c : {Case{1e-3, 0.25, 0.5}, Case{5e-3, 0.25, 0.5}, Case{2e-3, 0.3025, 0.6},
                        Case{4e-3, 0.5, 1.0}, Case{1e-2, 0.25, 0.5}}) {
    SCOPED_TRACE("dt = " + std::to_string(c.dt) + ", beta = " + std::to_string(c.beta) +
                 ", gamma = " + std::to_string(c.gamma));
    const int steps = static_cast<int>(0.8 / c.dt);
    {
      Simulation s = falling_bar();
      s.newmark(c.dt, {{c.beta, c.gamma}});
      start_bar(s);
      const BounceStats st = bounce(s, nbm_test::ground_contact(), steps, false);
      EXPECT_GT(st.closed_steps, 0);
    }
    {
      Plate p;
      p.angle = -0.25;
      Simulation s = falling_plate(p, 0.02);
      s.newmark(c.dt, {{c.beta, c.gamma}});
      start_plate(s);
      const BounceStats st = bounce(s, nbm_test::bottom_contact(p, 0.02), steps, false);
      EXPECT_GT(st.closed_steps, 0);
    }
  }
}

// ---------------------------------------------------- dissipative Newmark

TEST(NewmarkDissipation, ModifiedEnergyDecaysByTheNewmarkIdentity) {
  // For M a + K u = F (the reduced system in flight) Newmark satisfies
  //   [E + dt^2 (beta - gamma/2)/2 a'Ma] = -(gamma - 1/2)([u]'K[u] + dt^2 (beta - gamma/2)[a]'M[a]),
  // so with gamma > 1/2, beta >= gamma/2 this modified energy decreases at
  // every step, while gamma = 1/2, beta = 1/4 conserves E exactly.
  const double beta = 0.3025, gamma = 0.6, dt = 2e-3;
  Simulation s = falling_bar();
  s.newmark(dt, {beta, gamma});
  start_bar(s);
  const double c = dt * dt * (beta - gamma / 2);
  auto modified = [&] {
    const Vec a = s.acc();
    return s.energy() + 0.5 * c * a.dot(s.a.M * a);
  };
  const double scale = s.a.mass * 10 * kH0;
  const double e_start = s.energy();
  double e_prev = e_start;
  for (int k = 1; k <= 60; ++k) {  // in flight until t = 0.12 s
    const Vec u0 = s.u(), a0 = s.acc();
    const double m0 = modified();
    s.step();
    ASSERT_FALSE(s.stepper->active()[0]);
    const Vec du = s.u() - u0, da = s.acc() - a0;
    const double decay = (gamma - 0.5) * (du.dot(s.a.K * du) + c * da.dot(s.a.M * da));
    EXPECT_GE(decay, 0.0);
    EXPECT_NEAR(modified() - m0, -decay, 1e-12 * scale) << "step " << k;
    EXPECT_LE(modified(), m0 + 1e-13 * scale) << "step " << k;
    // The physical energy differs from the modified one by c/2 a'Ma, which
    // barely changes in flight (a is -g plus small vibrations): here it is
    // non-increasing too, to round-off. (Not a theorem in general.)
    EXPECT_LE(s.energy(), e_prev + 1e-13 * scale) << "step " << k;
    e_prev = s.energy();
  }
  EXPECT_LT(s.energy(), e_start);
}

// ------------------------------------------------------------ step reports

TEST(NewmarkReports, ForcedFallbackKeepsImpenetrability) {
  // One guess only: every active-set change goes through the fallback (§5).
  Simulation s = falling_bar();
  nbm::NewmarkParameters prm;
  prm.max_active_set_iterations = 1;
  s.newmark(1e-3, prm);
  start_bar(s);
  const BounceStats st = bounce(s, nbm_test::ground_contact(), 800, false);
  EXPECT_GE(st.fallbacks, 1);
  EXPECT_GT(st.closed_steps, 0);
}

TEST(NewmarkReports, DefaultRunsReportSaneIterationCounts) {
  Plate p;
  p.angle = 0.1;
  Simulation s = falling_plate(p, 0.01);
  s.newmark(2e-3);
  start_plate(s);
  int max_iterations = 0;
  for (int k = 0; k < 300; ++k) {
    const nbm::StepReport r = s.step();
    EXPECT_GE(r.active_set_iterations, 1);
    // At most max_active_set_iterations guesses (25) plus the fallback solve.
    EXPECT_LE(r.active_set_iterations, 26);
    if (r.fallback) {
      EXPECT_GE(r.active_set_iterations, 2);
    }
    max_iterations = std::max(max_iterations, r.active_set_iterations);
  }
  EXPECT_GE(max_iterations, 2);  // some step had to change its guess
}

// ------------------------------------- the one-step problem (method.md §5.2)

// One P1 element, ground at x = -gap under its node 0 (the contact node C),
// node 1 the interior O; mass mu [2 1; 1 2], mu = rho h / 6, stiffness
// k [1 -1; -1 1], load f / 2 per node. The relation switches at
// u_O* = -gap - f / (2 k): open above, closed below. From the predictor
// u^ = u_O + dt v_O + beta' a_O (beta' = dt^2 / 4), z = u^ - u_O*:
//   open:   the whole mass moves, a = f / (6 mu): consistent iff z >= -beta' f / (6 mu);
//   closed: O alone on a spring, (2 mu + k beta') a = f - k z: consistent iff
//           z <= -beta' f / (2 mu).
// The reduced mass jumps from 6 mu to 2 mu with the set, so the two windows
// do not meet: with f > 0 (a load away from the ground) no set is consistent
// for -beta' f / (2 mu) < z < -beta' f / (6 mu), with f < 0 both are for
// z between the two bounds. Values computed here by hand, not by the core.
struct OneElementBar {
  Bar b;
  double gap = 0.01, dt = 0.01;
  explicit OneElementBar(double g) {
    b.N = 1;
    b.L = 1;
    b.rho = 1;
    b.E = 100;
    b.g = g;  // f = -rho g h
  }
  double mu() const { return b.rho * b.h() / 6; }
  double f() const { return -b.rho * b.g * b.h(); }
  double k() const { return b.E / b.h(); }
  double beta_dt2() const { return dt * dt / 4; }
  double switch_point() const { return -gap - f() / (2 * k()); }
};

TEST(NewmarkOneStepProblem, ConsistentMassCanHaveNoConsistentActiveSet) {
  OneElementBar bar(-10);  // f = 10 > 0: pulled away from the ground
  // Start open at u = 0, moving down so that z is mid-window: z = -beta' f / (3 mu).
  const double a0 = bar.f() / (6 * bar.mu());  // open: the whole mass
  const double z = -bar.beta_dt2() * bar.f() / (3 * bar.mu());
  const double v0 = (z + bar.switch_point() - bar.beta_dt2() * a0) / bar.dt;
  Simulation s(assemble(bar.b), nbm_test::ground_contact(bar.gap));
  s.newmark(bar.dt);
  s.initialize(Vec::Zero(2), Vec::Constant(2, v0));
  ASSERT_NEAR(s.acc()(1), a0, 1e-12 * a0);
  const nbm::StepReport r = s.step();
  EXPECT_TRUE(r.fallback) << "the fixed point found a consistent set where none exists";
  EXPECT_GE(r.active_set_iterations, 2);
  EXPECT_GE(s.u()(0), -bar.gap - 1e-12);  // the fallback keeps impenetrability
  // (The massless boundary has one reduced mass for every set, so its
  // windows meet exactly: one LCP, a unique step. One element has too few
  // interior nodes to redistribute the mass, so it is not run here.)
}

TEST(NewmarkOneStepProblem, ConsistentMassCanHaveTwoConsistentActiveSets) {
  OneElementBar bar(10);  // f = -10 < 0: gravity towards the ground
  // The same predictor, z mid-window (= 2 beta' g, both sets consistent),
  // from an open start and from a closed one: the step ends where the start's
  // set was, two different solutions of the same one-step problem.
  const double z = -bar.beta_dt2() * bar.f() / (3 * bar.mu());
  const double u_hat = z + bar.switch_point();
  const double dt = bar.dt, b = bar.beta_dt2();

  // Open start: u_O above u_O*, a = f / (6 mu).
  const double u_open = bar.switch_point() + 1e-3;
  const double a_open = bar.f() / (6 * bar.mu());
  Simulation open(assemble(bar.b), nbm_test::ground_contact(bar.gap));
  open.newmark(dt);
  open.initialize(Vec::Constant(2, u_open), Vec::Constant(2, (u_hat - u_open - b * a_open) / dt));
  ASSERT_NEAR(open.acc()(1), a_open, 1e-12 * std::abs(a_open));
  EXPECT_FALSE(open.step().fallback);
  const double end_open = open.u()(1);
  EXPECT_NEAR(end_open, u_hat + b * a_open, 1e-12);
  EXPECT_LT(end_open, u_open);  // it moved down, towards the ground
  EXPECT_GT(open.u()(0), -bar.gap + 1e-6);  // still open

  // Closed start: u_O below u_O*, 2 mu a = f / 2 - k (u_O + gap).
  const double u_closed = bar.switch_point() - 1e-3;
  const double a_closed = (bar.f() / 2 - bar.k() * (u_closed + bar.gap)) / (2 * bar.mu());
  Simulation closed(assemble(bar.b), nbm_test::ground_contact(bar.gap));
  closed.newmark(dt);
  Vec u0(2);
  u0 << -bar.gap, u_closed;
  closed.initialize(u0, Vec::Constant(2, (u_hat - u_closed - b * a_closed) / dt));
  ASSERT_NEAR(closed.acc()(1), a_closed, 1e-10 * std::abs(a_closed));
  EXPECT_FALSE(closed.step().fallback);
  const double a_end = (bar.f() - bar.k() * z) / (2 * bar.mu() + bar.k() * b);
  EXPECT_NEAR(closed.u()(1), u_hat + b * a_end, 1e-12);
  EXPECT_NEAR(closed.u()(0), -bar.gap, 1e-14);  // still closed
  EXPECT_GT(end_open - closed.u()(1), 1e-6);    // two different steps
}

// ------------------------------------------------------------------ errors

TEST(NewmarkErrors, ParametersOutOfRange) {
  Simulation s = falling_bar();
  using nbm_test::expect_throw_with;
  expect_throw_with<nbm::InputError>([&] { s.newmark(1e-3, {0.0, 0.5}); }, {"beta"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(1e-3, {0.6, 0.5}); }, {"beta"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(1e-3, {0.25, 0.4}); }, {"gamma"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(1e-3, {0.25, 1.1}); }, {"gamma"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(1e-3, {std::nan(""), 0.5}); }, {"beta"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(0.0); }, {"dt"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(-1e-3); }, {"dt"});
  expect_throw_with<nbm::InputError>([&] { s.newmark(INFINITY); }, {"dt"});
}

TEST(NewmarkErrors, StateErrors) {
  using nbm_test::expect_throw_with;
  Simulation s = falling_bar();
  s.newmark(1e-3);
  EXPECT_FALSE(s.stepper->initialized());
  expect_throw_with<nbm::InputError>([&] { s.step(); }, {"step", "initial state"});
  const Eigen::Index n = s.problem->size();
  // Penetration: u_0 = -0.01 below the ground.
  Vec u = Vec::Constant(s.a.K.rows(), 0.1);
  u(0) = -0.01;
  expect_throw_with<nbm::InputError>([&] { s.initialize(u, Vec::Zero(u.size())); },
                                     {"u", "penetration"});
  expect_throw_with<nbm::InputError>(
      [&] { s.stepper->initialize(Vec::Zero(n + 1), Vec::Zero(n), s.F_int); }, {"u", "size"});
  expect_throw_with<nbm::InputError>(
      [&] { s.stepper->initialize(Vec::Zero(n), Vec::Zero(n - 1), s.F_int); }, {"v", "size"});
  Vec F_nan = s.F_int;
  F_nan(3) = std::nan("");
  expect_throw_with<nbm::InputError>(
      [&] { s.stepper->initialize(Vec::Zero(n), Vec::Zero(n), F_nan); }, {"F", "non-finite"});
  expect_throw_with<nbm::InputError>(
      [&] { s.stepper->initialize(Vec::Zero(n), Vec::Zero(n), s.F_int, NAN); }, {"t"});
  EXPECT_FALSE(s.stepper->initialized());
}

}  // namespace
