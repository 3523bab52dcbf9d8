// Numerical robustness of the steppers, each case with its stated
// expectation: grazing contact (a gap of 1e-14 at the closest approach),
// many simultaneous switches (a flat plate landing flat), a body resting on
// the obstacle for a long time, very small and very large time steps, and an
// ill-conditioned stiffness (Young's moduli in a ratio 1e6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "errors.hpp"
#include "test_stepping.hpp"
#include "test_util.hpp"

namespace {

using nbm_test::Assembled;
using nbm_test::Bar;
using nbm_test::Plate;
using nbm_test::Simulation;
using Vec = Eigen::VectorXd;

enum class Scheme { Newmark, Massless, Explicit };
const char* name(Scheme s) {
  switch (s) {
    case Scheme::Newmark: return "newmark";
    case Scheme::Massless: return "massless";
    case Scheme::Explicit: return "explicit";
  }
  return "?";
}

void set_scheme(Simulation& s, Scheme scheme, double dt, const Eigen::MatrixXd& positions,
                nbm::NewmarkParameters parameters = {}) {
  switch (scheme) {
    case Scheme::Newmark: s.newmark(dt, parameters); break;
    case Scheme::Massless:
      s.problem->make_boundary_massless(nbm::redistributed_mass(*s.problem, s.a.M, positions));
      s.stepper = std::make_unique<nbm::MasslessNewmarkStepper>(*s.problem, dt, parameters.beta,
                                                                parameters.gamma);
      break;
    case Scheme::Explicit: s.explicit_scheme(dt); break;
  }
}

int closed(const nbm::ActiveSet& a) { return static_cast<int>(std::count(a.begin(), a.end(), true)); }

// What a run records, step by step (index 0: the initial state).
struct Trace {
  std::vector<Vec> u, v;              // internal coordinates
  std::vector<int> closed;            // number of closed contacts
  std::vector<double> energy, min_gap;
  int switches = 0, fallbacks = 0, max_iterations = 0;
};

Trace run(Simulation& s, int steps) {
  Trace t;
  const nbm::Stepper& st = *s.stepper;
  auto record = [&] {
    t.u.push_back(st.u());
    t.v.push_back(st.v());
    t.closed.push_back(closed(st.active()));
    t.energy.push_back(st.energies().total());
    t.min_gap.push_back(st.gaps().minCoeff());
  };
  record();
  for (int n = 0; n < steps; ++n) {
    const nbm::ActiveSet before = st.active();
    const nbm::StepReport r = s.step();
    t.switches += st.active() != before;
    t.fallbacks += r.fallback;
    t.max_iterations = std::max(t.max_iterations, r.active_set_iterations);
    record();
  }
  return t;
}

// Momentum along the unit vector dir (one entry per component of a node) of
// the velocity v (internal coordinates) with the scheme's own mass matrix (the
// redistributed one for the massless boundary, where contact dofs carry none).
double momentum(const Simulation& s, const Vec& v, const Vec& dir) {
  const int dim = static_cast<int>(dir.size());
  Vec e(s.problem->n_dofs());
  for (nbm::Index i = 0; i < e.size(); ++i) e(i) = dir(i % dim);
  return s.problem->to_internal(e).dot(s.problem->M() * v);
}

double max_distance(const std::vector<Vec>& a, const std::vector<Vec>& b) {
  double d = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    d = std::max(d, (a[k] - b[k]).cwiseAbs().maxCoeff());
  return d;
}

// ------------------------------------------------------------ grazing

// A body thrown towards the obstacle (speed 1) against a load that pushes it
// away (acceleration g = 10): a rigid flight on a parabola whose closest
// approach, 0.05 away, falls on step 100 (t = 0.1, dt = 1e-3). The obstacle
// is put at that closest approach plus `delta`, measured on a run with a far
// obstacle. Bar (one contact node), flat plate (17 nodes graze at once) and
// the plate inclined by 0.3 rad (rotated normals).
struct Grazing {
  bool plate;
  double angle;
  const char* label;
};

Simulation grazing_body(const Grazing& g, double gap, Eigen::MatrixXd& positions, Vec& u0, Vec& v0) {
  if (g.plate) {
    Plate p;
    p.nx = 16;
    p.ny = 4;
    p.angle = g.angle;
    Assembled a = assemble(p);
    a.F = -a.F;  // pushes away from the ground
    positions = nbm_test::node_positions(p);
    u0 = Vec::Zero(p.n_dofs());
    v0 = Vec::Zero(p.n_dofs());
    for (int node = 0; node < p.n_nodes(); ++node) v0.segment<2>(2 * node) = p.normal();  // speed 1
    return Simulation(std::move(a), nbm_test::bottom_contact(p, gap));
  }
  Bar b;
  Assembled a = assemble(b);
  a.F = -a.F;
  positions = nbm_test::node_positions(b);
  u0 = Vec::Zero(b.n_dofs());
  v0 = Vec::Constant(b.n_dofs(), -1.0);  // towards the ground at x = 0
  return Simulation(std::move(a), nbm_test::ground_contact(gap));
}

// Expectation: whatever delta in {1e-14, 0, -1e-14, -1e-12}, no failure and
// no penetration beyond round-off (gaps >= -1e-15, the displacements being
// 0.05). The implicit NBM schemes (paper and massless boundary) show no
// spurious bounce: displacements stay within |delta| + 1e-13 of the free
// flight, the centre-of-mass velocity within 1e-11, the energy within 1e-13.
// The explicit scheme takes its active set from the LCP at the new position:
// grazed by 1e-14 it closes the contact for exactly one step, where the paper
// NBM's slaving of the contact nodes costs them their velocity (-g dt/2 at
// the closing step): the centre-of-mass velocity changes by at most
// 2 (m_C/m) g dt (m_C: lumped mass of the contact nodes), the energy by at
// most m_C (g dt)^2; with delta >= 0 it flies free like the others.
TEST(RobustnessGrazing, NoFailureNoPenetrationNoSpuriousBounce) {
  const double dt = 1e-3, g = 10;
  const int steps = 200;
  for (const Grazing body : {Grazing{false, 0, "bar"}, Grazing{true, 0, "flat plate"},
                             Grazing{true, 0.3, "inclined plate"}})
    for (const Scheme scheme : {Scheme::Newmark, Scheme::Massless, Scheme::Explicit}) {
      Eigen::MatrixXd X;
      Vec u0, v0;
      Simulation far = grazing_body(body, 1.0, X, u0, v0);
      set_scheme(far, scheme, dt, X);
      far.initialize(u0, v0);
      const Trace ref = run(far, steps);
      double peak = -INFINITY;  // closest approach: the largest normal displacement
      for (const Vec& u : ref.u)
        for (nbm::Index c : far.problem->contact_index()) peak = std::max(peak, u(c));
      ASSERT_NEAR(peak, 0.05, 1e-3);
      const Vec dir = body.plate ? Vec(-Plate{}.normal()) : Vec(Vec::Ones(1));
      const Vec lumped = far.problem->to_user(far.problem->lumped_mass());
      double m_contact = 0;  // lumped mass of the contact nodes (one component)
      for (std::size_t k = 0; k < far.problem->contact_index().size(); ++k)
        m_contact += far.problem->lumped_mass()(far.problem->contact_index()[k]);
      const double m = far.a.mass;
      for (const double delta : {1e-14, 0.0, -1e-14, -1e-12}) {
        SCOPED_TRACE(std::string(body.label) + ", " + name(scheme) + ", delta " + std::to_string(delta));
        Simulation s = grazing_body(body, peak + delta, X, u0, v0);
        set_scheme(s, scheme, dt, X);
        s.initialize(u0, v0);
        Trace t;
        ASSERT_NO_THROW(t = run(s, steps));
        EXPECT_GE(*std::min_element(t.min_gap.begin(), t.min_gap.end()), -1e-15);
        const double du = max_distance(t.u, ref.u);
        double dv_com = 0;
        for (int n = 0; n <= steps; ++n)
          dv_com = std::max(dv_com, std::abs(momentum(s, t.v[n], dir) - momentum(s, ref.v[n], dir)) / m);
        const double dE = std::abs(t.energy.back() - ref.energy.back());
        if (scheme != Scheme::Explicit || delta >= 0) {
          EXPECT_LE(du, std::abs(delta) + 1e-13);
          EXPECT_LE(dv_com, 1e-11);
          EXPECT_LE(dE, 1e-13);
        } else {
          EXPECT_EQ(std::count_if(t.closed.begin(), t.closed.end(), [](int c) { return c > 0; }), 1)
              << "closed for exactly one step";
          EXPECT_LE(dv_com, 2 * (m_contact / m) * g * dt);
          EXPECT_LE(dE, m_contact * (g * dt) * (g * dt));
        }
      }
    }
}

// ------------------------------------------------------- extreme time steps

// The bar of test_problems (E = 100, L = 1: c = 10, g = 10) lifted by 0.05 or
// resting undeformed on the ground; the plate lifted by 0.02. Free-flight
// period of the bouncing bar: fall, contact 2L/c, rise: about 0.4.
struct Body {
  Simulation sim;
  Vec u0;
  Eigen::MatrixXd positions;
};

Body make_body(bool plate, double lift) {
  if (plate) {
    Plate p;
    p.nx = 8;
    p.ny = 4;
    return {Simulation(assemble(p), nbm_test::bottom_contact(p, lift)), Vec::Zero(p.n_dofs()),
            nbm_test::node_positions(p)};
  }
  Bar b;
  return {Simulation(assemble(b), nbm_test::ground_contact()), Vec::Constant(b.n_dofs(), lift),
          nbm_test::node_positions(b)};
}

// Expectation at dt = 1e-9 (10^4 steps): no failure, gaps >= -1e-15, and the
// run is as accurate as the data allow: the centre of mass falls with
// velocity -g t and acceleration -g to 1e-6 (relative), the energy is
// conserved to 1e-11 of m g h0 (the displacements, 0.05, move by 1e-13 per
// step: a few ulps). The implicit schemes once lost every digit of the
// acceleration there ((u_{n+1} - u_hat)/(beta dt^2) cancels): velocity 3.4
// times too large, energy off by 1.6e-8 of m g h0.
TEST(RobustnessTimeStep, TinyStepIsAccurate) {
  const double dt = 1e-9, g = 10;
  const int steps = 10000;
  for (const bool plate : {false, true})
    for (const double lift : {plate ? 0.02 : 0.05, 0.0})
      for (const Scheme scheme : {Scheme::Newmark, Scheme::Massless, Scheme::Explicit}) {
        SCOPED_TRACE(std::string(plate ? "plate" : "bar") + ", lift " + std::to_string(lift) +
                     ", " + name(scheme));
        Body body = make_body(plate, lift);
        Simulation& s = body.sim;
        set_scheme(s, scheme, dt, body.positions);
        s.initialize(body.u0, Vec::Zero(body.u0.size()));
        Trace t;
        ASSERT_NO_THROW(t = run(s, steps));
        EXPECT_GE(*std::min_element(t.min_gap.begin(), t.min_gap.end()), -1e-15);
        const double scale = s.a.mass * g * 0.05;
        for (double e : t.energy) ASSERT_NEAR(e, t.energy[0], 1e-11 * scale);
        const Vec dir = plate ? Vec(-Plate{}.normal()) : Vec(Vec::Ones(1));
        const double m = s.a.mass;
        const double v_com = momentum(s, t.v.back(), dir) / m;
        const double a_com = momentum(s, s.stepper->a(), dir) / m;
        if (lift > 0) {  // free fall
          EXPECT_NEAR(v_com, -g * steps * dt, 1e-6 * g * steps * dt);
          EXPECT_NEAR(a_com, -g, 1e-6 * g);
        } else {  // resting, undeformed: starts to compress from rest
          EXPECT_LE(std::abs(v_com), g * steps * dt);
        }
      }
}

// Expectation at dt = 10 and 100 times the bar's bouncing period (10^3
// steps): no failure, gaps >= -1e-12 (displacement scale 0.05; closed
// contacts sit exactly on the obstacle), and for the implicit schemes the
// energy never exceeds its initial value by more than 1e-9 m g h0 (the
// predictor u + dt v + dt^2 a/4 is some 10^5 times the displacement: its
// round-off); the explicit scheme rejects such a step at construction.
TEST(RobustnessTimeStep, HugeStepIsStableAndImpenetrable) {
  const double period = 0.4, g = 10;
  for (const double dt : {10 * period, 100 * period})
    for (const bool plate : {false, true})
      for (const double lift : {plate ? 0.02 : 0.05, 0.0})
        for (const Scheme scheme : {Scheme::Newmark, Scheme::Massless}) {
          SCOPED_TRACE("dt " + std::to_string(dt) + ", " + (plate ? "plate" : "bar") +
                       ", lift " + std::to_string(lift) + ", " + name(scheme));
          Body body = make_body(plate, lift);
          Simulation& s = body.sim;
          set_scheme(s, scheme, dt, body.positions);
          s.initialize(body.u0, Vec::Zero(body.u0.size()));
          Trace t;
          ASSERT_NO_THROW(t = run(s, 1000));
          EXPECT_GE(*std::min_element(t.min_gap.begin(), t.min_gap.end()), -1e-12);
          const double scale = s.a.mass * g * 0.05;
          EXPECT_LE(*std::max_element(t.energy.begin(), t.energy.end()),
                    t.energy[0] + 1e-9 * scale);
        }
  Body body = make_body(false, 0.05);
  nbm_test::expect_throw_with<nbm::InputError>(
      [&] { body.sim.explicit_scheme(10 * period); },
      {"dt: 4 exceeds the critical time step", "explicit scheme"});
}

}  // namespace
