// Exact restart: the state after a step (u, v, a, active set, load, time),
// restored into a new stepper on a new problem object, continues the run bit
// for bit, for every scheme; nbm::Solver does the same from the arrays it
// hands out in user coordinates, also when rotated contact nodes make the
// round trip user <-> internal coordinates inexact.
#include <gtest/gtest.h>

#include <string>

#include "api/solver.hpp"
#include "base/errors.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Bar;
using nbm_test::expect_throw_with;
using nbm_test::Plate;
using nbm_test::Simulation;
using Vec = Eigen::VectorXd;

enum class Scheme { Newmark, NewmarkDissipative, Massless, Explicit, MoreauJean };

struct Case {
  std::string name;
  bool plate;
  double angle;  // plate only: rotated contact normals when != 0
  Scheme scheme;
  // Plate only: cells along x. With 32, the 33 contact nodes' K_CC is sparse
  // enough for sparse principal-block factors (principal_block.hpp).
  int nx = 8;
};


// The problem of a case with its initial state (bar lifted by 0.05, plate
// 0.02 above the ground, at rest): both bounce within the run.
struct Problem {
  std::unique_ptr<Simulation> sim;
  Vec u0, v0;
};

Problem make(const Case& c) {
  Problem p;
  double dt = 1e-3;
  Eigen::MatrixXd positions;
  if (c.plate) {
    Plate plate;
    plate.nx = c.nx;
    plate.ny = 4;
    plate.angle = c.angle;
    p.sim = std::make_unique<Simulation>(assemble(plate), nbm_test::bottom_contact(plate, 0.02));
    positions = nbm_test::node_positions(plate);
    p.u0 = Vec::Zero(plate.n_dofs());
  } else {
    Bar bar;
    p.sim = std::make_unique<Simulation>(assemble(bar), nbm_test::ground_contact());
    positions = nbm_test::node_positions(bar);
    p.u0 = Vec::Constant(bar.n_dofs(), 0.05);
    dt = 2e-3;
  }
  p.v0 = Vec::Zero(p.u0.size());
  Simulation& s = *p.sim;
  switch (c.scheme) {
    case Scheme::Newmark: s.newmark(dt); break;
    case Scheme::NewmarkDissipative: s.newmark(dt, {0.3025, 0.6}); break;
    case Scheme::Massless: s.massless(dt, positions); break;
    case Scheme::Explicit: s.explicit_scheme(dt); break;
    case Scheme::MoreauJean: s.moreau_jean(dt, 0.5); break;
  }
  return p;
}

bool same(const Vec& a, const Vec& b) {
  return a.size() == b.size() && (a.array() == b.array()).all();
}

// gtest prints a parameter's raw bytes (here a std::string's pointer) unless
// told otherwise, and ctest's test names include that text.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class Restart : public ::testing::TestWithParam<Case> {};

TEST_P(Restart, RestoredStepperContinuesTheRunBitForBit) {
  const Case& c = GetParam();
  for (const int saved_after : {0, 37, 100}) {  // right after initialize, in flight, in contact
    SCOPED_TRACE("restored after step " + std::to_string(saved_after));
    Problem a = make(c);
    a.sim->initialize(a.u0, a.v0);
    for (int n = 0; n < saved_after; ++n) a.sim->step();
    const nbm::Stepper& A = *a.sim->stepper;

    Problem b = make(c);  // a new problem object and stepper
    // With the scheme's own state (the massless boundary's returnable loss:
    // without it, the run differs at the first switching step that gains).
    b.sim->stepper->restore(A.u(), A.v(), A.a(), A.active(),
                            nbm::ContactLoad{a.sim->F_int, A.obstacle()}, A.time(),
                            A.scheme_state());
    const nbm::Stepper& B = *b.sim->stepper;
    int closed_steps = 0, switches = 0;
    for (int n = 0; n < 150; ++n) {
      const nbm::ActiveSet before = A.active();
      const nbm::StepReport ra = a.sim->step(), rb = b.sim->step();
      ASSERT_TRUE(same(A.u(), B.u())) << "u differs after " << n + 1 << " steps";
      ASSERT_TRUE(same(A.v(), B.v())) << "v differs after " << n + 1 << " steps";
      ASSERT_TRUE(same(A.a(), B.a())) << "a differs after " << n + 1 << " steps";
      ASSERT_EQ(A.active(), B.active());
      ASSERT_EQ(A.time(), B.time());
      ASSERT_EQ(ra.active_set_iterations, rb.active_set_iterations);
      ASSERT_EQ(ra.fallback, rb.fallback);
      ASSERT_EQ(A.energies().total(), B.energies().total());
      closed_steps += std::count(A.active().begin(), A.active().end(), true) > 0;
      switches += A.active() != before;
    }
    if (saved_after > 0) {  // the continued run goes through impacts
      EXPECT_GT(closed_steps, 0);
      EXPECT_GT(switches, 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, Restart,
    ::testing::Values(Case{"BarNewmark", false, 0, Scheme::Newmark},
                      Case{"BarNewmarkDissipative", false, 0, Scheme::NewmarkDissipative},
                      Case{"BarMassless", false, 0, Scheme::Massless},
                      Case{"BarExplicit", false, 0, Scheme::Explicit},
                      Case{"BarMoreauJean", false, 0, Scheme::MoreauJean},
                      Case{"PlateNewmark", true, 0, Scheme::Newmark},
                      Case{"InclinedPlateNewmark", true, 0.3, Scheme::Newmark},
                      Case{"InclinedPlateMassless", true, 0.3, Scheme::Massless},
                      Case{"InclinedPlateExplicit", true, 0.3, Scheme::Explicit},
                      Case{"InclinedPlateMoreauJean", true, 0.3, Scheme::MoreauJean},
                      Case{"WideInclinedPlateNewmark", true, 0.3, Scheme::Newmark, 32},
                      Case{"WideInclinedPlateMassless", true, 0.3, Scheme::Massless, 32}),
    [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

TEST(RestartState, RestoreValidatesItsArguments) {
  Problem p = make({"", true, 0.3, Scheme::Newmark});
  nbm::Stepper& s = *p.sim->stepper;
  const Vec u = p.sim->problem->to_internal(p.u0), z = Vec::Zero(u.size());
  const Vec& F = p.sim->F_int;
  const nbm::ActiveSet open(p.sim->problem->n_contact(), false);
  using nbm::InputError;
  expect_throw_with<InputError>([&] { s.restore(u, z, Vec::Zero(3), open, F, 0); },
                                {"a: size 3, expected"});
  expect_throw_with<InputError>([&] { s.restore(u, z, z, nbm::ActiveSet(2), F, 0); },
                                {"active: size 2, expected 9"});
  Vec bad = z;
  bad(4) = std::nan("");
  expect_throw_with<InputError>([&] { s.restore(u, bad, z, open, F, 0); },
                                {"v: non-finite entries"});
  expect_throw_with<InputError>([&] { s.restore(u, z, z, open, F, INFINITY); },
                                {"t: non-finite time"});
  // A state below the ground: NBM never produces one.
  Vec sunk = p.sim->problem->to_internal(p.u0);
  for (nbm::Index c : p.sim->problem->contact_index()) sunk(c) = 0.05;  // gap 0.02 - 0.05
  expect_throw_with<InputError>([&] { s.restore(sunk, z, z, open, F, 0); },
                                {"u: restored penetration at contact node 0"});
  EXPECT_FALSE(s.initialized());
  // Moreau-Jean lets positions penetrate by O(dt v): such states restore.
  Problem mj = make({"", true, 0.3, Scheme::MoreauJean});
  EXPECT_NO_THROW(mj.sim->stepper->restore(sunk, z, z, open, F, 0.5));
  EXPECT_EQ(mj.sim->stepper->time(), 0.5);
  EXPECT_EQ(mj.sim->stepper->reactions().cwiseAbs().maxCoeff(), 0.0);
}

// ------------------------------------------------ the Solver front end

struct SolverRun {
  nbm::CooMatrix M, K;
  std::vector<double> F;
  nbm::ContactDescription contact;
  nbm::SolverOptions options;
  std::vector<double> u0;
};

SolverRun plate_run(double angle, const std::string& mass = "consistent",
                    const std::string& scheme = "newmark") {
  Plate p;
  p.nx = 8;
  p.ny = 4;
  p.angle = angle;
  const auto a = assemble(p);
  SolverRun r;
  r.M = nbm_test::to_coo(a.M);
  r.K = nbm_test::to_coo(a.K);
  r.F = nbm_test::to_std(a.F);
  r.contact = nbm_test::bottom_contact(p, 0.02);
  r.options.dt = 1e-3;
  r.options.scheme = nbm_test::scheme_named(scheme);
  r.options.mass = nbm_test::mass_named(mass);
  if (mass == "redistributed") {
    const Eigen::MatrixXd X = nbm_test::node_positions(p);
    for (int i = 0; i < X.rows(); ++i)
      for (int j = 0; j < X.cols(); ++j) r.options.positions.push_back(X(i, j));
  }
  r.u0.assign(p.n_dofs(), 0.0);
  return r;
}

TEST(RestartSolver, RoundTripThroughUserCoordinatesIsExactOnlyForAxisNormals) {
  Plate flat, inclined;
  inclined.angle = 0.3;
  for (const auto& [p, exact] : {std::pair{flat, true}, {inclined, false}}) {
    Simulation s(assemble(p), nbm_test::bottom_contact(p, 0.02));
    EXPECT_EQ(s.problem->exact_round_trip(), exact) << "angle " << p.angle;
  }
  Simulation bar(assemble(Bar{}), nbm_test::ground_contact());
  EXPECT_TRUE(bar.problem->exact_round_trip());
  // The inclined plate's round trip does change some numbers: without the
  // front end's rounding of its state, a restart from user arrays would not
  // be exact.
  Simulation s(assemble(inclined), nbm_test::bottom_contact(inclined, 0.02));
  const Vec x = Vec::LinSpaced(s.problem->size(), 0.1, 0.7);
  EXPECT_GT((s.problem->to_internal(s.problem->to_user(x)) - x).cwiseAbs().maxCoeff(), 0.0);
}

TEST(RestartSolver, RestartFromUserArraysReproducesTheRunBitForBit) {
  // Undamped and damped (method.md §9: Rayleigh, mass-proportional only for
  // the explicit scheme): damping adds no state, a restart stays exact.
  for (const bool damped : {false, true})
    for (const double angle : {0.0, 0.3})
      for (const std::string scheme : {"newmark", "explicit", "moreau-jean", "redistributed"}) {
      SCOPED_TRACE("angle " + std::to_string(angle) + ", " + scheme +
                   (damped ? ", damped" : ""));
      SolverRun r = scheme == "redistributed" ? plate_run(angle, "redistributed")
                                              : plate_run(angle, "consistent", scheme);
      if (damped) {
        r.options.rayleigh_mass = 2;
        if (scheme != "explicit") r.options.rayleigh_stiffness = 1e-4;
      }
      nbm::Solver a(r.M, r.K, r.contact, r.options);
      std::vector<double> u = r.u0, v(u.size(), 0.0);
      a.initialize(u, v, r.F);
      for (int n = 0; n < 90; ++n) a.step(u, v, r.F);  // in contact
      // What a script saves: the arrays, the time, the acceleration, the active set.
      std::vector<double> us = u, vs = v;
      const std::vector<double> as = a.acceleration();
      const std::vector<long> act = a.active();
      ASSERT_GT(std::count(act.begin(), act.end(), 1L), 0);

      nbm::Solver b(r.M, r.K, r.contact, r.options);
      b.restart(us, vs, r.F, a.time(), as, act, a.scheme_state());
      const double D_saved = a.energies()[5];  // b's dissipation restarts from zero
      EXPECT_EQ(us, u);  // kept as given
      EXPECT_EQ(vs, v);
      EXPECT_EQ(b.acceleration(), as);
      EXPECT_EQ(b.active(), act);
      for (int n = 0; n < 150; ++n) {
        a.step(u, v, r.F);
        b.step(us, vs, r.F);
        ASSERT_EQ(u, us) << "u differs after " << n + 1 << " steps";
        ASSERT_EQ(v, vs) << "v differs after " << n + 1 << " steps";
        ASSERT_EQ(a.acceleration(), b.acceleration());
        ASSERT_EQ(a.active(), b.active());
        ASSERT_EQ(a.reactions(), b.reactions());
        ASSERT_EQ(a.time(), b.time());
      }
      const double D = a.energies()[5] - D_saved;
      EXPECT_NEAR(b.energies()[5], D, 1e-12 * std::abs(D));
      if (damped) {
        EXPECT_GT(D, 0);
      }
    }
}

TEST(RestartSolver, RestartValidatesItsArguments) {
  const SolverRun r = plate_run(0.3);
  nbm::Solver s(r.M, r.K, r.contact, r.options);
  std::vector<double> u = r.u0, v(u.size(), 0.0), a(u.size(), 0.0);
  std::vector<long> act(9, 0);
  using nbm::InputError;
  auto restart = [&] { s.restart(u, v, r.F, 0.0, a, act); };
  act[2] = 2;
  expect_throw_with<InputError>(restart, {"active: entry 2 is 2, expected 0 or 1"});
  act.assign(3, 0);
  expect_throw_with<InputError>(restart, {"active: size 3, expected 9"});
  act.assign(9, 0);
  a.resize(4);
  expect_throw_with<InputError>(restart, {"a: size 4, expected"});
  a.assign(u.size(), 0.0);
  a[1] = INFINITY;
  expect_throw_with<InputError>(restart, {"a: non-finite entries"});
  a[1] = 0;
  EXPECT_FALSE(s.initialized());
  EXPECT_NO_THROW(restart());
  EXPECT_TRUE(s.initialized());
  EXPECT_EQ(s.time(), 0.0);
  EXPECT_EQ(s.steps(), 0);
}

// ------------------------------------------------ replaced contact sets

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  const Vec x = nbm_test::to_eigen(a), y = nbm_test::to_eigen(b);
  return (x - y).cwiseAbs().maxCoeff() / std::max(x.cwiseAbs().maxCoeff(), 1e-300);
}

TEST(ReplaceContacts, TheSameDescriptionKeepsTheRun) {
  // Axis normals (exact round trip): u_O, v_O are kept bit for bit; the
  // acceleration is recomputed from the equations of motion, which Newmark's
  // own a satisfies to round-off: the run goes on to round-off.
  for (const std::string scheme : {"newmark", "explicit", "moreau-jean", "redistributed"}) {
    SCOPED_TRACE(scheme);
    const SolverRun r = scheme == "redistributed" ? plate_run(0.0, "redistributed")
                                                  : plate_run(0.0, "consistent", scheme);
    nbm::Solver a(r.M, r.K, r.contact, r.options), b(r.M, r.K, r.contact, r.options);
    std::vector<double> ua = r.u0, va(ua.size(), 0.0), ub = ua, vb = va;
    a.initialize(ua, va, r.F);
    b.initialize(ub, vb, r.F);
    for (int n = 0; n < 90; ++n) {
      a.step(ua, va, r.F);
      b.step(ub, vb, r.F);
    }
    const std::vector<double> u_before = ub, v_before = vb;
    b.replace_contacts(r.contact, ub, vb, r.F);
    // u_O, v_O as they were; u_C, v_C recomputed from the nodal boundary
    // relation (the same relation: round-off).
    EXPECT_LE(relative_difference(ub, u_before), 1e-14);
    EXPECT_LE(relative_difference(vb, v_before), 1e-12);
    EXPECT_EQ(b.time(), a.time());
    EXPECT_EQ(b.steps(), a.steps());
    if (scheme != "moreau-jean") {  // whose a is (v+ - v)/dt, not the equations' a
      EXPECT_LE(relative_difference(b.acceleration(), a.acceleration()), 1e-9);
    }
    for (int n = 0; n < 100; ++n) {
      a.step(ua, va, r.F);
      b.step(ub, vb, r.F);
    }
    EXPECT_LE(relative_difference(ua, ub), 1e-9);
    EXPECT_LE(relative_difference(va, vb), 1e-7);
  }
}

TEST(ReplaceContacts, ARestartAcrossTheReplacementReproducesTheRunBitForBit) {
  // The inclined plate in contact; its contact set is replaced by one without
  // its last node and with gaps grown by 1e-3 (as a re-linearisation would
  // move them). A new solver built on the new description and restarted from
  // the state after the replacement continues the run bit for bit.
  for (const std::string mass : {"consistent", "redistributed"}) {
    SCOPED_TRACE(mass);
    const SolverRun r = plate_run(0.3, mass);
    nbm::ContactDescription replaced = r.contact;
    replaced.dofs.resize(replaced.dofs.size() - 2);
    replaced.normals.resize(replaced.normals.size() - 2);
    replaced.gaps.pop_back();
    for (double& g : replaced.gaps) g += 1e-3;
    nbm::Solver a(r.M, r.K, r.contact, r.options);
    std::vector<double> u = r.u0, v(u.size(), 0.0);
    a.initialize(u, v, r.F);
    for (int n = 0; n < 90; ++n) a.step(u, v, r.F);
    a.replace_contacts(replaced, u, v, r.F);
    EXPECT_EQ(a.n_contact(), static_cast<long>(replaced.gaps.size()));
    for (int n = 0; n < 20; ++n) a.step(u, v, r.F);

    std::vector<double> us = u, vs = v;
    nbm::Solver b(r.M, r.K, replaced, r.options);
    b.restart(us, vs, r.F, a.time(), a.acceleration(), a.active(), a.scheme_state());
    int closed = 0;
    for (int n = 0; n < 150; ++n) {
      a.step(u, v, r.F);
      b.step(us, vs, r.F);
      ASSERT_EQ(u, us) << "u differs after " << n + 1 << " steps";
      ASSERT_EQ(v, vs) << "v differs after " << n + 1 << " steps";
      ASSERT_EQ(a.active(), b.active());
      ASSERT_EQ(a.reactions(), b.reactions());
      for (long c : a.active()) closed += c;
    }
    EXPECT_GT(closed, 0);
  }
}

TEST(ReplaceContacts, ABadDescriptionIsRejectedAndTheSolverIsUnchanged) {
  const SolverRun r = plate_run(0.3);
  nbm::Solver a(r.M, r.K, r.contact, r.options), b(r.M, r.K, r.contact, r.options);
  std::vector<double> ua = r.u0, va(ua.size(), 0.0), ub = ua, vb = va;
  using nbm::InputError;
  expect_throw_with<InputError>([&] { b.replace_contacts(r.contact, ub, vb, r.F); },
                                {"replace contacts", "initialization"});
  a.initialize(ua, va, r.F);
  b.initialize(ub, vb, r.F);
  for (int n = 0; n < 90; ++n) {
    a.step(ua, va, r.F);
    b.step(ub, vb, r.F);
  }
  nbm::ContactDescription bad = r.contact;
  bad.normals[2] = 2.0;
  expect_throw_with<InputError>([&] { b.replace_contacts(bad, ub, vb, r.F); },
                                {"normals", "unit vector"});
  bad = r.contact;
  for (double& g : bad.gaps) g = -0.5;  // the body would be inside the obstacle
  expect_throw_with<InputError>([&] { b.replace_contacts(bad, ub, vb, r.F); },
                                {"penetration"});
  std::vector<double> moved = ub;
  moved[0] += 1e-3;
  expect_throw_with<InputError>([&] { b.replace_contacts(r.contact, moved, vb, r.F); },
                                {"changed since the last step"});
  for (int n = 0; n < 100; ++n) {
    a.step(ua, va, r.F);
    b.step(ub, vb, r.F);
    ASSERT_EQ(ua, ub) << "the failed replacements changed the run (step " << n + 1 << ")";
  }
}

}  // namespace
