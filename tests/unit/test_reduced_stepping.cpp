// Time integration on the reduced model (SchemeOptions::modes, method.md §6
// "Time integration on the reduced model"): the full model's run is the
// reference. With every interior mode the basis spans the whole interior
// and the implicit schemes, invariant under a change of coordinates, give
// the full run to round-off; with fewer modes the run converges to it. The
// energies reported are the full model's energies of the expanded state,
// restarts are exact, and bad options are named errors.
#include <gtest/gtest.h>

#include <cmath>

#include "api/solver.hpp"
#include "base/errors.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm::Solver;
using nbm::SolverOptions;
using nbm_test::expect_throw_with;
using StdVec = std::vector<double>;

// A cantilever plate (left edge clamped, tilted by `angle`) whose free bottom
// nodes fall under gravity onto the ground `gap` below: contact closes at
// the tip and opens again, contact normals not along the axes.
struct Cantilever {
  nbm_test::Plate plate;
  nbm_test::Assembled a;
  nbm::ContactDescription contact;
  std::vector<long> fixed;
  Eigen::MatrixXd positions;

  explicit Cantilever(double angle = 0.3, double gap = 0.01, int nx = 8, int ny = 2) {
    plate.nx = nx;
    plate.ny = ny;
    plate.angle = angle;
    a = assemble(plate);
    for (int j = 0; j <= plate.ny; ++j)
      for (int c = 0; c < 2; ++c) fixed.push_back(2 * plate.node(0, j) + c);
    const Eigen::Vector2d n = plate.normal();
    for (int i = 1; i <= plate.nx; ++i) {
      const int node = plate.node(i, 0);
      contact.dofs.insert(contact.dofs.end(), {2L * node, 2L * node + 1});
      contact.normals.insert(contact.normals.end(), {n.x(), n.y()});
      contact.gaps.push_back(gap);
    }
    positions = nbm_test::node_positions(plate);
  }
  // Interior dofs of the internal problem: free dofs less one per contact node.
  int interior() const {
    return plate.n_dofs() - static_cast<int>(fixed.size()) - static_cast<int>(contact.gaps.size());
  }

  SolverOptions options(bool massless, double dt, std::optional<int> modes = {}) const {
    SolverOptions o;
    o.dt = dt;
    o.fixed = fixed;
    if (massless) {
      o.mass = nbm::MassTreatment::kRedistributed;
      for (Eigen::Index i = 0; i < positions.rows(); ++i)  // dof-major
        for (Eigen::Index j = 0; j < positions.cols(); ++j) o.positions.push_back(positions(i, j));
    }
    o.modes = modes;
    return o;
  }
};

struct History {
  std::vector<StdVec> u, v;
  std::vector<std::vector<double>> energies;
  long closed = 0;  // steps ending with a closed contact
};

History run(const Cantilever& c, const SolverOptions& o, int steps) {
  Solver s(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact, o);
  const StdVec F = nbm_test::to_std(c.a.F);
  StdVec u(F.size(), 0.0), v(F.size(), 0.0);
  s.initialize(u, v, F);
  History r{{u}, {v}, {s.energies()}, 0};
  for (int k = 0; k < steps; ++k) {
    s.step(u, v, F);
    r.u.push_back(u);
    r.v.push_back(v);
    r.energies.push_back(s.energies());
    for (long a : s.active()) r.closed += a;
  }
  return r;
}

double max_abs(const std::vector<StdVec>& x) {
  double m = 0;
  for (const StdVec& y : x)
    for (double z : y) m = std::max(m, std::abs(z));
  return m;
}

// max over steps and dofs of |a - b|, relative to max |b|.
double relative_difference(const std::vector<StdVec>& a, const std::vector<StdVec>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t i = 0; i < a[k].size(); ++i) d = std::max(d, std::abs(a[k][i] - b[k][i]));
  return d / max_abs(b);
}

TEST(ReducedStepping, EveryInteriorModeGivesTheFullRun) {
  for (const bool massless : {false, true})
    for (const double angle : {0.0, 0.3}) {
      const Cantilever c(angle);
      const double dt = 2e-3;
      const History full = run(c, c.options(massless, dt), 400);
      const History reduced = run(c, c.options(massless, dt, c.interior()), 400);
      ASSERT_GT(full.closed, 0) << "the tip must strike the ground";
      const double du = relative_difference(reduced.u, full.u);
      const double dv = relative_difference(reduced.v, full.v);
      std::printf("  %s, angle %.1f: %ld closed contact-steps, |du| %.1e, |dv| %.1e\n",
                  massless ? "massless" : "consistent", angle, full.closed, du, dv);
      EXPECT_LT(du, 1e-9);
      EXPECT_LT(dv, 1e-9);
    }
}

TEST(ReducedStepping, GeneralizedAlphaOnEveryModeGivesTheFullRun) {
  const Cantilever c(0.3, 0.01, 6, 2);
  SolverOptions full = c.options(true, 2e-3), reduced = c.options(true, 2e-3, c.interior());
  full.scheme = reduced.scheme = nbm::TimeScheme::kGeneralizedAlpha;
  full.rho_inf = reduced.rho_inf = 0.7;
  const History a = run(c, full, 300), b = run(c, reduced, 300);
  EXPECT_LT(relative_difference(b.u, a.u), 1e-9);
}

TEST(ReducedStepping, TheRunConvergesToTheFullOneAsModesAreAdded) {
  // 16 x 4 cells: 160 interior dofs. Errors of u over the whole run.
  for (const bool massless : {true, false}) {
    const Cantilever c(0.3, 0.005, 16, 4);
    const double dt = 2e-3;
    const int steps = 300;
    const History full = run(c, c.options(massless, dt), steps);
    ASSERT_GT(full.closed, 0);
    std::vector<double> errors;
    for (const int m : {2, 4, 8, 16, 32, 64, 128}) {
      const History r = run(c, c.options(massless, dt, m), steps);
      errors.push_back(relative_difference(r.u, full.u));
      std::printf("  %s, %2d modes: |u - u_full| / |u_full| = %.2e\n",
                  massless ? "massless" : "consistent", m, errors.back());
    }
    EXPECT_LT(errors.back(), 1e-2 * errors.front());
    EXPECT_LT(errors.back(), 3e-3);
    for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_LT(errors[k], 1.5 * errors[k - 1]);
  }
}

TEST(ReducedStepping, TheReductionResidualFallsWithTheModes) {
  // The full model's residual at the expanded state: round-off with every
  // interior mode, falling as modes are added, both mass treatments.
  for (const bool massless : {true, false}) {
    const Cantilever c(0.3, 0.005, 16, 4);
    const StdVec F = nbm_test::to_std(c.a.F);
    std::vector<double> residuals;
    for (const int m : {4, 16, 64, c.interior()}) {
      Solver s(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact,
               c.options(massless, 2e-3, m));
      StdVec u(F.size(), 0.0), v(F.size(), 0.0);
      s.initialize(u, v, F);
      double worst = 0;
      long closed = 0;
      for (int k = 0; k < 200; ++k) {
        s.step(u, v, F);
        worst = std::max(worst, s.reduction_residual());
        for (long a : s.active()) closed += a;
      }
      ASSERT_GT(closed, 0);
      residuals.push_back(worst);
      std::printf("  %s, %3d modes: largest reduction residual over 200 steps %.2e\n",
                  massless ? "massless" : "consistent", m, worst);
    }
    EXPECT_LT(residuals.back(), 1e-10);
    for (std::size_t k = 1; k < residuals.size(); ++k) EXPECT_LT(residuals[k], residuals[k - 1]);
  }
  const Cantilever c(0.3);
  Solver full(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact, c.options(true, 2e-3));
  expect_throw_with<nbm::InputError>([&] { full.reduction_residual(); },
                                     {"reduction residual: the solver integrates the full model"});
  Solver fresh(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact,
               c.options(true, 2e-3, 4));
  expect_throw_with<nbm::InputError>([&] { fresh.reduction_residual(); },
                                     {"reduction residual: no state yet"});
}

TEST(ReducedStepping, EnergiesAreTheFullModelsOfTheExpandedState) {
  // Consistent mass: the reported total is 1/2 v'Mv + 1/2 u'Ku - F'u of the
  // published (expanded) state with the user's matrices.
  const Cantilever c(0.3);
  const History r = run(c, c.options(false, 2e-3, 6), 300);
  double worst = 0;
  for (std::size_t k = 0; k < r.u.size(); ++k) {
    const double e = nbm_test::total_energy(c.a, nbm_test::to_eigen(r.u[k]),
                                            nbm_test::to_eigen(r.v[k]));
    worst = std::max(worst, std::abs(e - r.energies[k][3]));
  }
  const double scale = std::abs(r.energies.back()[1]) + std::abs(r.energies.back()[2]);
  EXPECT_LT(worst, 1e-12 * scale);
  // Massless boundary: the reduced model's energy never rises above its
  // start, the tip striking the ground many times, and what the switching
  // steps take (method.md §5.1) is what they take from the full model.
  const History m = run(c, c.options(true, 2e-3, 6), 600);
  const History f = run(c, c.options(true, 2e-3), 600);
  ASSERT_GT(m.closed, 0);
  auto rise_and_loss = [](const History& h) {
    double rise = -1e300, loss = 0;
    for (const auto& e : h.energies) {
      rise = std::max(rise, e[3] - h.energies[0][3]);
      loss = std::max(loss, h.energies[0][3] - e[3]);
    }
    return std::pair{rise, loss};
  };
  const auto [rise, loss] = rise_and_loss(m);
  const auto [full_rise, full_loss] = rise_and_loss(f);
  std::printf("  massless, 6 modes: energy rise %.1e, loss %.2e (full model: %.1e, %.2e), "
              "of %.2e\n", rise, loss, full_rise, full_loss, scale);
  EXPECT_LT(rise, 1e-12 * scale);
  EXPECT_LT(loss, 2 * full_loss);
  EXPECT_GT(loss, 0.5 * full_loss);
}

TEST(ReducedStepping, ARestartContinuesTheRunBitForBit) {
  for (const bool massless : {false, true}) {
    const Cantilever c(0.3);
    const SolverOptions o = c.options(massless, 2e-3, 5);
    const StdVec F = nbm_test::to_std(c.a.F);
    Solver a(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact, o);
    StdVec u(F.size(), 0.0), v(F.size(), 0.0);
    a.initialize(u, v, F);
    for (int k = 0; k < 120; ++k) a.step(u, v, F);
    StdVec us = u, vs = v;
    Solver b(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact, o);
    b.restart(us, vs, F, a.time(), a.acceleration(), a.active(), a.scheme_state());
    for (int k = 0; k < 120; ++k) {
      a.step(u, v, F);
      b.step(us, vs, F);
    }
    EXPECT_EQ(u, us);
    EXPECT_EQ(v, vs);
    // The reduced state is part of the scheme state: without it, or with
    // one of another time, the restart is refused by name.
    Solver c2(nbm_test::to_coo(c.a.M), nbm_test::to_coo(c.a.K), c.contact, o);
    expect_throw_with<nbm::InputError>(
        [&] { c2.restart(us, vs, F, a.time(), a.acceleration(), a.active(), {}); },
        {"scheme state: size 0, expected at least", "reduced state of modes="});
    a.step(u, v, F);
    expect_throw_with<nbm::InputError>(
        [&] { c2.restart(us, vs, F, a.time(), a.acceleration(), a.active(), a.scheme_state()); },
        {"scheme state: its reduced state does not expand to u"});
  }
}

TEST(ReducedStepping, BadOptionsAreNamedErrors) {
  const Cantilever c(0.3);
  const auto M = nbm_test::to_coo(c.a.M), K = nbm_test::to_coo(c.a.K);
  auto make = [&](const SolverOptions& o) { Solver s(M, K, c.contact, o); };
  SolverOptions o = c.options(false, 1e-3, 4);
  o.scheme = nbm::TimeScheme::kExplicit;
  expect_throw_with<nbm::InputError>([&] { make(o); }, {"modes: given with scheme \"explicit\""});
  o.scheme = nbm::TimeScheme::kMoreauJean;
  expect_throw_with<nbm::InputError>([&] { make(o); }, {"modes: given with scheme \"moreau-jean\""});
  for (const int m : {0, -3, c.interior() + 1}) {
    o = c.options(false, 1e-3, m);
    expect_throw_with<nbm::InputError>([&] { make(o); }, {"modes: " + std::to_string(m)});
  }
  // A frame that follows the body moves every component of a contact node.
  o = c.options(true, 1e-3, 4);
  nbm::ObstacleDescription ground;
  ground.kind = "plane";
  ground.point = {0.0, -0.01};
  ground.axis = {0.0, 1.0};
  o.obstacle = ground;
  expect_throw_with<nbm::InputError>([&] { make(o); }, {"modes: given with obstacle="});
  // A body free to slide along the ground: K_OO (contact dofs clamped) is
  // singular, so there are no fixed-interface modes.
  o = c.options(false, 1e-3, 4);
  o.fixed.clear();
  expect_throw_with<nbm::NumericalError>([&] { make(o); }, {"K_OO"});
  // The basis is built on the contact nodes: no replacing them.
  o = c.options(false, 1e-3, 4);
  Solver s(M, K, c.contact, o);
  const StdVec F = nbm_test::to_std(c.a.F);
  StdVec u(F.size(), 0.0), v(F.size(), 0.0);
  s.initialize(u, v, F);
  expect_throw_with<nbm::InputError>([&] { s.replace_contacts(c.contact, u, v, F); },
                                     {"replace contacts: the solver integrates a reduced model"});
}

}  // namespace
