// Energy of the semi-discrete NBM equations over long runs, with no time
// discretisation: the exact flow (exact_flow.hpp) of the bouncing bar of
// benchmarks.md §A. It separates what the method does to the energy from
// what a time stepper adds (tests/long-run.sh reports the steppers').
//
// method.md §4: within an active set the energy is conserved; at a switch
// the kinetic energy of the contact dofs jumps, since v_C = A v_O with a
// new A. With mass on the contact dofs (the paper's NBM) the jumps have
// either sign and do not cancel: the energy is not bounded by its initial
// value. With the massless boundary there are no jumps.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_problem.hpp"
#include "contact/mass_redistribution.hpp"
#include "periodic/exact_flow.hpp"

namespace {

using Index = Eigen::Index;
using nbm::Vector;

// The bouncing bar of benchmarks.md §A: P1 bar on (0, L), consistent mass,
// node 0 against the ground (outward normal -1, gap 0), gravity, dropped
// from height h0 at rest.
struct BouncingBar {
  double L = 10, E = 900, rho = 1, g = 10, h0 = 5;
  int N = 40;
  bool massless = false;

  double period() const { return 4 * (std::sqrt(2 * h0 / g) + L / std::sqrt(E / rho)); }
  double initial_energy() const { return rho * g * L * h0; }  // potential, at rest

  nbm::ReducedField field() const {
    const double h = L / N;
    std::vector<nbm::Triplet> m, k;
    for (int e = 0; e < N; ++e)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          m.emplace_back(e + i, e + j, rho * h / 6 * (i == j ? 2 : 1));
          k.emplace_back(e + i, e + j, E / h * (i == j ? 1 : -1));
        }
    nbm::SparseMatrix M(N + 1, N + 1), K(N + 1, N + 1);
    M.setFromTriplets(m.begin(), m.end());
    K.setFromTriplets(k.begin(), k.end());
    nbm::ContactSet ground(N + 1, {0}, {-1.0}, Vector::Zero(1));
    nbm::Matrix x(N + 1, 1);
    for (int i = 0; i <= N; ++i) x(i, 0) = i * h;
    const nbm::ContactProblem problem(M, K, ground, {}, massless ? &x : nullptr);
    const Vector weight = -g * (M * Vector::Ones(N + 1));  // the FE load of rho g
    return nbm::ReducedField::from(problem, problem.to_internal(weight));
  }
};

struct EnergyHistory {
  double initial = 0, final = 0;
  double drift_within_regions = 0;  ///< largest change inside one active set
  double gained_at_release = 0, lost_at_touch_down = 0;  ///< sums of the jumps
  int switches = 0;
};

// Flows the bar over `periods` periods of the continuum solution, with the
// energy sampled at 1/3 and 2/3 of every interval between switches: equal
// within an interval, the jump at a switch is the difference across it.
EnergyHistory run(const BouncingBar& bar, int periods) {
  const nbm::ReducedField field = bar.field();
  const nbm::ExactFlow flow(field);
  const Index n = field.size();
  // Interior dofs are the nodes 1..N, all at height h0.
  Vector u = Vector::Constant(n, bar.h0), v = Vector::Zero(n);
  EnergyHistory history;
  history.initial = field.energies(u, v)(3);
  double previous = history.initial;  // energy of the current region
  for (int p = 0; p < periods; ++p) {
    const double T = bar.period();
    const auto plain = flow.integrate(u, v, T, false);
    std::vector<double> times;
    double start = 0;
    for (const auto& s : plain.switches) {
      times.push_back(start + (s.t - start) / 3), times.push_back(start + 2 * (s.t - start) / 3);
      start = s.t;
    }
    times.push_back(start + (T - start) / 3), times.push_back(start + 2 * (T - start) / 3);
    const auto sampled = flow.integrate(u, v, T, false, times);
    for (Index k = 0; k + 1 < sampled.samples.cols(); k += 2) {
      auto energy = [&](Index c) {
        return field.energies(sampled.samples.col(c).head(n), sampled.samples.col(c).tail(n))(3);
      };
      const double a = energy(k), b = energy(k + 1);
      history.drift_within_regions = std::max(history.drift_within_regions, std::abs(b - a));
      if (k > 0) {
        const auto& s = plain.switches[static_cast<std::size_t>(k / 2 - 1)];
        (s.after[static_cast<std::size_t>(s.contact)] ? history.lost_at_touch_down
                                                      : history.gained_at_release) += a - previous;
      }
      previous = b;
    }
    history.switches += static_cast<int>(plain.switches.size());
    u = plain.u, v = plain.v;
  }
  history.final = field.energies(u, v)(3);
  return history;
}

TEST(BouncingBarEnergy, PaperNbmGainsEnergyWithoutAnyTimeDiscretisation) {
  for (int N : {40, 80}) {
    BouncingBar bar;
    bar.N = N;
    const auto h = run(bar, 100);
    const double E0 = h.initial;
    EXPECT_NEAR(E0, bar.initial_energy(), 1e-6 * E0);
    std::printf("paper NBM, N = %d, 100 periods: E/E0 = %.3f, %d switches, jumps: releases %+.3f E0, "
                "touch-downs %+.3f E0, drift within regions %.1e E0\n",
                N, h.final / E0, h.switches, h.gained_at_release / E0, h.lost_at_touch_down / E0,
                h.drift_within_regions / E0);
    EXPECT_LE(h.drift_within_regions, 1e-9 * E0);
    // The jumps account for the whole change.
    EXPECT_NEAR(h.final - E0, h.gained_at_release + h.lost_at_touch_down, 1e-8 * h.final);
    // Releases give the contact dof the velocity of the bar (a gain),
    // touch-downs stop it (a loss); the gains win.
    EXPECT_GT(h.gained_at_release, 0);
    EXPECT_LT(h.lost_at_touch_down, 0);
    EXPECT_GT(h.final, 1.5 * E0);
  }
}

TEST(BouncingBarEnergy, MasslessBoundaryConservesTheEnergyAcrossSwitches) {
  for (int N : {40, 80}) {
    BouncingBar bar;
    bar.N = N, bar.massless = true;
    const auto h = run(bar, 100);
    const double E0 = h.initial;
    std::printf("massless boundary, N = %d, 100 periods: |E/E0 - 1| = %.1e, %d switches\n", N,
                std::abs(h.final / E0 - 1), h.switches);
    EXPECT_GT(h.switches, 100);
    EXPECT_LE(std::abs(h.gained_at_release) + std::abs(h.lost_at_touch_down), 1e-9 * E0);
    EXPECT_NEAR(h.final, E0, 1e-9 * E0);
  }
}

}  // namespace
