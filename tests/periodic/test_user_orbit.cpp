// The front end on user dofs (user_orbit.hpp) on the fixed-gap bar: the
// report of every method, the states along the orbit, and input errors.
#include <gtest/gtest.h>

#include <cmath>

#include "bars.hpp"
#include "periodic/user_orbit.hpp"

namespace {

using nbm::Vector;

// The fixed-gap bar (paper NBM, N = 20) and a guess on user dofs: the
// continuum orbit's rest profile with contact fraction 0.3.
struct UserBar {
  nbm_test::GapBar bar;
  std::unique_ptr<nbm::ContactProblem> problem;
  std::vector<double> F, u, v;
  UserBar() {
    bar.N = 20;
    problem = bar.problem();
    F.assign(bar.N + 1, 0.0);
    v.assign(bar.N + 1, 0.0);
    for (int i = 0; i <= bar.N; ++i)
      u.push_back(nbm_test::continuum_rest_profile(bar, 0.3, i * bar.h()));
  }
};

// Half-period shooting from the bar's guess, probe next to the tip.
nbm::OrbitReport shoot_bar(const UserBar& b) {
  nbm::OrbitOptions o;
  o.half_period = true;
  o.probe = b.bar.N - 1;
  return nbm::periodic_orbit(*b.problem, b.F, b.u, b.v, 3.7, o);
}

TEST(UserOrbit, ShootingReportsTheOrbitOnUserDofs) {
  UserBar b;
  const auto r = shoot_bar(b);
  EXPECT_LE(r.periodicity_residual, 1e-10);
  EXPECT_LE(r.complementarity_residual, 1e-12);
  EXPECT_EQ(r.switches, 2);
  EXPECT_GT(r.contact_time, 0);
  EXPECT_EQ(r.u0.size(), b.u.size());
  EXPECT_EQ(r.u0[0], 0.0);                                   // the fixed dof
  EXPECT_NEAR(r.u0[b.bar.N - 1], b.u[b.bar.N - 1], 1e-14);   // the amplitude condition
  EXPECT_LE(r.u0[b.bar.N], b.bar.g);                         // the contact dof, slaved
  EXPECT_NE(r.summary.find("method shooting"), std::string::npos);
  EXPECT_NE(r.summary.find("consistent (paper NBM)"), std::string::npos);
  EXPECT_EQ(r.multipliers_re.size(), 2u * (b.bar.N - 1));
  // The state after one period is the initial one; at half a period the
  // bar is at rest again (symmetric orbit).
  std::vector<std::vector<double>> us, vs;
  nbm::orbit_states(r, {0.5 * r.period, r.period}, us, vs);
  for (std::size_t i = 0; i < r.u0.size(); ++i) {
    EXPECT_NEAR(us[1][i], r.u0[i], 1e-10 * b.bar.g);
    EXPECT_NEAR(vs[0][i], 0, 1e-10 * b.bar.g);
  }
}

// probe is the reported dof in every call, the contact dof included; the
// conditions stay on the interior dof (phase, or an interior probe).
TEST(UserOrbit, ProbeReportsAnyDofAndPhaseCarriesTheConditions) {
  UserBar b;
  const auto interior = shoot_bar(b);
  nbm::OrbitOptions o;
  o.half_period = true;
  o.probe = b.bar.N;  // the contact dof
  o.phase = b.bar.N - 1;
  const auto r = nbm::periodic_orbit(*b.problem, b.F, b.u, b.v, 3.7, o);
  // The same orbit (same conditions), reported at the tip: it reaches the
  // gap and no further (exact impenetrability), and rests at t = 0 at its
  // other extreme.
  EXPECT_EQ(r.period, interior.period);
  EXPECT_EQ(r.u0, interior.u0);
  EXPECT_EQ(r.probe, b.bar.N);
  EXPECT_NEAR(r.probe_max, b.bar.g, 1e-12 * b.bar.g);
  EXPECT_NEAR(r.probe_min, r.u0[b.bar.N], 1e-12 * b.bar.g);
  EXPECT_NEAR(r.amplitude, 0.5 * (r.probe_max - r.probe_min), 1e-15 * b.bar.g);
  EXPECT_EQ(interior.probe, b.bar.N - 1);
  EXPECT_NE(r.summary.find("probe dof " + std::to_string(b.bar.N)), std::string::npos);
  // Without probe: the dof of largest amplitude; the conditions' dof is
  // then the guess's largest interior one.
  o = {};
  o.half_period = true;
  const auto free_probe = nbm::periodic_orbit(*b.problem, b.F, b.u, b.v, 3.7, o);
  EXPECT_GE(free_probe.amplitude, r.amplitude * (1 - 1e-12));
}

TEST(UserOrbit, HarmonicBalanceAndReducedBasisAgreeWithShooting) {
  UserBar b;
  const auto shot = shoot_bar(b);
  nbm::OrbitOptions h;
  h.probe = b.bar.N - 1;
  h.method = "harmonic-balance";
  h.cosine_only = true;
  h.harmonics = 40;
  h.amplitude = shot.u0[b.bar.N - 1];
  const auto hb = nbm::periodic_orbit(*b.problem, b.F, shot.u0, b.v, shot.period, h);
  EXPECT_NEAR(hb.period, shot.period, 1e-3 * shot.period);  // mass jump: ~1/H
  EXPECT_EQ(hb.harmonics, 40);
  EXPECT_EQ(hb.coefficients.size(), b.u.size() * 81);
  EXPECT_GT(hb.truncation, 0);
  EXPECT_NE(hb.summary.find("harmonic balance"), std::string::npos);

  nbm::OrbitOptions m;
  m.half_period = true;
  m.modes = 12;
  m.condition = "energy";
  m.amplitude = shot.energies[3];
  const auto red = nbm::periodic_orbit(*b.problem, b.F, shot.u0, b.v, shot.period, m);
  EXPECT_NEAR(red.period, shot.period, 2e-2 * shot.period);
  EXPECT_GT(red.reduction_residual, 0);
  EXPECT_GT(red.cutoff_ratio, 1);
  EXPECT_NE(red.summary.find("reduced basis: 12"), std::string::npos);
}

TEST(UserOrbit, RejectsBadInputNamingTheArgument) {
  UserBar b;
  auto expect_error = [&](nbm::OrbitOptions o, const std::string& what, double T = 3.7,
                          std::vector<double> u = {}) {
    try {
      nbm::periodic_orbit(*b.problem, b.F, u.empty() ? b.u : u, b.v, T, o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(what, 0), 0u) << e.what();
    }
  };
  nbm::OrbitOptions o;
  expect_error(o, "T:", -1);
  expect_error(o, "u:", 3.7, std::vector<double>(3, 0.0));
  o.method = "newton";
  expect_error(o, "method:");
  o = {};
  o.condition = "phase";
  expect_error(o, "condition:");
  o = {};
  o.phase = b.bar.N;  // the contact dof: slaved, it cannot carry the conditions
  expect_error(o, "phase:");
  o = {};
  o.probe = b.bar.N + 1;
  expect_error(o, "probe:");
  o = {};
  o.modes = 4;
  o.phase = 3;
  expect_error(o, "phase:");
  o = {};
  o.modes = -2;
  expect_error(o, "modes:");
  o = {};
  o.harmonics = 0;
  expect_error(o, "harmonics:");
}

}  // namespace
