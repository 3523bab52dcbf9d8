// The forced-orbit front end on user dofs (user_forced_orbit.hpp): the linear
// limit against the frequency response of the damped bar computed here by a
// dense solve, the report on user dofs, and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <string>

#include "bars.hpp"
#include "base/errors.hpp"
#include "periodic/user_forced_orbit.hpp"

namespace {

using nbm::Matrix;
using nbm::Vector;
using Complex = std::complex<double>;

// The fixed-gap bar (paper NBM, N = 12) with the obstacle out of reach, Rayleigh
// damping and a load whose harmonics vanish at the tip (the contact dof).
struct ForcedBar {
  nbm_test::GapBar bar;
  std::unique_ptr<nbm::ContactProblem> problem;
  std::vector<double> F0, Fc, Fs, zero;
  nbm::ForcedOrbitOptions o;
  ForcedBar() {
    bar.N = 12;
    bar.g = 1e6;
    problem = bar.problem();
    const int n = bar.N + 1;
    zero.assign(n, 0.0);
    F0 = Fc = Fs = zero;
    for (int i = 1; i < bar.N; ++i) {
      const double x = i * bar.h();
      F0[i] = 0.3 * x, Fc[i] = std::sin(2 * x), Fs[i] = 0.5 * x * x;
    }
    F0[bar.N] = 0.1;  // a constant load on the contact dof is allowed
    o.omega = 2.1;    // between the bar's first two modes (pi/2, 3 pi/2)
    o.rayleigh_mass = 0.05, o.rayleigh_stiffness = 2e-3;
    o.probe = bar.N - 1;
  }
  nbm::OrbitReport solve() const {
    return nbm::forced_orbit(*problem, F0, {Fc}, {Fs}, zero, zero, o);
  }
};

// The reference: the paper NBM with the contact open is the bar constrained
// to u = P u_O + e, the tip following (K u)_N = F_N (method.md §3), so the
// steady response is u_O = Re(X e^{i w t}) + static part with
// P^T (K - w^2 M + i w C) P X = P^T (Fc - i Fs), C = a_M M + b_K K.
// Dofs 1..N of the bar (dof 0 is clamped).
struct BarResponse {
  Vector us, u, v;    // static part, u(0), v(0)
  Eigen::VectorXcd X;
};
BarResponse bar_reference(const ForcedBar& b) {
  nbm::SparseMatrix Ms, Ks;
  b.bar.assemble(Ms, Ks);
  const int N = b.bar.N, n = N - 1;  // interior dofs 1..N-1
  const Matrix M = Matrix(Ms).block(1, 1, N, N), K = Matrix(Ks).block(1, 1, N, N);
  Matrix P = Matrix::Zero(N, n);
  P.topRows(n).setIdentity();
  P.row(n) = -K.block(n, 0, 1, n) / K(n, n);
  Vector F0(N), Fc(N), Fs(N);
  for (int i = 0; i < N; ++i) F0(i) = b.F0[i + 1], Fc(i) = b.Fc[i + 1], Fs(i) = b.Fs[i + 1];
  // Static part: u = P u_O + e with e the tip's response to F0 alone.
  Vector e = Vector::Zero(N);
  e(n) = F0(n) / K(n, n);
  BarResponse r;
  r.us = P * (P.transpose() * K * P).ldlt().solve(P.transpose() * (F0 - K * e)) + e;
  const double w = b.o.omega;
  const Matrix C = b.o.rayleigh_mass * M + b.o.rayleigh_stiffness * K;
  const Eigen::MatrixXcd Z = (P.transpose() * (K - w * w * M) * P).cast<Complex>() +
                             Complex(0, w) * (P.transpose() * C * P).cast<Complex>();
  r.X = P.cast<Complex>() * Z.partialPivLu().solve(P.transpose().cast<Complex>() *
                                                   (Fc.cast<Complex>() - Complex(0, 1) * Fs.cast<Complex>()));
  r.u = r.us + r.X.real(), r.v = (Complex(0, w) * r.X).real();
  return r;
}

TEST(UserForcedOrbit, LinearLimitIsTheDampedFrequencyResponseOnUserDofs) {
  ForcedBar b;
  const auto r = b.solve();
  const BarResponse ref = bar_reference(b);
  const int N = b.bar.N;
  const double w = b.o.omega;
  const Vector &u_ref = ref.u, &v_ref = ref.v, &us = ref.us;
  const Eigen::VectorXcd& X = ref.X;
  ASSERT_EQ(r.u0.size(), static_cast<std::size_t>(N + 1));
  EXPECT_EQ(r.u0[0], 0.0);
  const double us_scale = u_ref.cwiseAbs().maxCoeff(), vs_scale = v_ref.cwiseAbs().maxCoeff();
  for (int i = 0; i < N; ++i) {
    EXPECT_NEAR(r.u0[i + 1], u_ref(i), 1e-10 * us_scale) << i;
    EXPECT_NEAR(r.v0[i + 1], v_ref(i), 1e-10 * vs_scale) << i;
  }
  EXPECT_NEAR(r.period, 2 * M_PI / w, 1e-15);
  EXPECT_EQ(r.switches, 0);
  EXPECT_TRUE(r.stable);
  EXPECT_LE(r.periodicity_residual, 1e-12);
  // The probe's amplitude is |X| (one harmonic), up to the sampling (512).
  const int p = b.o.probe;
  EXPECT_EQ(r.probe, p);
  EXPECT_NEAR(r.amplitude, std::abs(X(p - 1)), 1e-4 * std::abs(X(p - 1)));
  EXPECT_NEAR(0.5 * (r.probe_max + r.probe_min), us(p - 1), 1e-4 * std::abs(X(p - 1)));
  EXPECT_EQ(r.omega, w);
  EXPECT_NE(r.summary.find("forced orbit: omega"), std::string::npos);
  // Every multiplier of the linear orbit is a damped mode's exp(lambda T):
  // modulus exp(-c_j T / 2) < 1.
  for (std::size_t k = 0; k < r.multipliers_re.size(); ++k)
    EXPECT_LT(std::hypot(r.multipliers_re[k], r.multipliers_im[k]), 1.0);
  // The state after one period (orbit_states follows the forced flow).
  std::vector<std::vector<double>> us_t, vs_t;
  nbm::orbit_states(r, {r.period}, us_t, vs_t);
  for (int i = 0; i <= N; ++i) EXPECT_NEAR(us_t[0][i], r.u0[i], 1e-10 * us_scale);
}

// Harmonic balance through the front end: one harmonic is the frequency
// response (the series' coefficients on user dofs: a_1 = Re X, b_1 = -Im X).
TEST(UserForcedOrbit, HarmonicBalanceOfTheLinearBarIsItsFrequencyResponse) {
  ForcedBar b;
  b.o.method = "harmonic-balance";
  b.o.harmonics = 1;
  const auto r = b.solve();
  const BarResponse ref = bar_reference(b);
  const int N = b.bar.N;
  const double us_scale = ref.u.cwiseAbs().maxCoeff(), vs_scale = ref.v.cwiseAbs().maxCoeff();
  ASSERT_EQ(r.harmonics, 1);
  ASSERT_EQ(r.coefficients.size(), static_cast<std::size_t>(3 * (N + 1)));
  for (int i = 0; i < N; ++i) {
    EXPECT_NEAR(r.u0[i + 1], ref.u(i), 1e-10 * us_scale) << i;
    EXPECT_NEAR(r.v0[i + 1], ref.v(i), 1e-10 * vs_scale) << i;
    if (i + 1 == N) continue;  // the contact dof: slaved, its coefficients left at zero
    EXPECT_NEAR(r.coefficients[3 * (i + 1) + 1], ref.X(i).real(), 1e-10 * us_scale) << i;
    EXPECT_NEAR(r.coefficients[3 * (i + 1) + 2], -ref.X(i).imag(), 1e-10 * us_scale) << i;
  }
  EXPECT_LE(r.balance_residual, 1e-12);
  EXPECT_LE(r.truncation, 1e-12);
  EXPECT_LE(r.periodicity_residual, 1e-12);
  EXPECT_TRUE(r.stable);
  EXPECT_NE(r.summary.find("method harmonic balance"), std::string::npos);
}

TEST(UserForcedOrbit, SubharmonicOfALinearOrbitIsTheHarmonicOrbit) {
  ForcedBar b;
  const auto one = b.solve();
  b.o.subharmonic = 3;
  const auto three = b.solve();
  EXPECT_NEAR(three.period, 3 * one.period, 1e-14 * three.period);
  for (std::size_t i = 0; i < one.u0.size(); ++i) EXPECT_NEAR(three.u0[i], one.u0[i], 1e-10);
}

TEST(UserForcedOrbit, DefaultProbeIsTheDofOfLargestAmplitude) {
  ForcedBar b;
  b.o.probe = -1;
  const auto r = b.solve();
  std::vector<std::vector<double>> us, vs;
  std::vector<double> times;
  for (int k = 0; k < 512; ++k) times.push_back(r.period * k / 512);
  nbm::orbit_states(r, times, us, vs);
  double best = 0;
  for (std::size_t i = 0; i < r.u0.size(); ++i) {
    double lo = 1e300, hi = -1e300;
    for (const auto& u : us) lo = std::min(lo, u[i]), hi = std::max(hi, u[i]);
    best = std::max(best, 0.5 * (hi - lo));
  }
  EXPECT_NEAR(r.amplitude, best, 1e-12 * best);
  // The largest total energy at those samples (no switch: the same times),
  // computed here from the bar's own matrices: 1/2 v'Mv + 1/2 u'Ku - F0'u.
  nbm::SparseMatrix M, K;
  b.bar.assemble(M, K);
  double energy = -1e300;
  for (std::size_t k = 0; k < us.size(); ++k) {
    const Vector u = Eigen::Map<const Vector>(us[k].data(), us[k].size());
    const Vector v = Eigen::Map<const Vector>(vs[k].data(), vs[k].size());
    const Vector F0 = Eigen::Map<const Vector>(b.F0.data(), b.F0.size());
    energy = std::max(energy, 0.5 * v.dot(M * v) + 0.5 * u.dot(K * u) - F0.dot(u));
  }
  EXPECT_NEAR(r.energy_max, energy, 1e-10 * std::abs(energy));
}

// The bar's damped frequency response at the probe, |X_p(w)| (one harmonic
// Fc - i Fs), by the dense Guyan solve of the linear-limit test.
double bar_response(const ForcedBar& b, double w, int p) {
  nbm::SparseMatrix Ms, Ks;
  b.bar.assemble(Ms, Ks);
  const int N = b.bar.N, n = N - 1;
  const Matrix M = Matrix(Ms).block(1, 1, N, N), K = Matrix(Ks).block(1, 1, N, N);
  Matrix P = Matrix::Zero(N, n);
  P.topRows(n).setIdentity();
  P.row(n) = -K.block(n, 0, 1, n) / K(n, n);
  Vector Fc(N), Fs(N);
  for (int i = 0; i < N; ++i) Fc(i) = b.Fc[i + 1], Fs(i) = b.Fs[i + 1];
  const Matrix C = b.o.rayleigh_mass * M + b.o.rayleigh_stiffness * K;
  const Eigen::MatrixXcd Z = (P.transpose() * (K - w * w * M) * P).cast<Complex>() +
                             Complex(0, w) * (P.transpose() * C * P).cast<Complex>();
  const Eigen::VectorXcd X = P.cast<Complex>() *
      Z.partialPivLu().solve(P.transpose().cast<Complex>() *
                             (Fc.cast<Complex>() - Complex(0, 1) * Fs.cast<Complex>()));
  return std::abs(X(p - 1));
}

// A frequency sweep through the first resonance of the linear bar: every
// point's amplitude is the direct frequency response (to the 512-sample
// resolution of the extremes), all stable, no event, the curve ends at `to`.
TEST(UserForcedOrbit, ResponseCurveOfTheLinearBarIsItsFrequencyResponse) {
  ForcedBar b;
  b.o.omega = 1.0;
  nbm::ForcedResponseOptions r;
  r.to = 2.2;
  r.step = 0.05;
  r.max_step = 2;  // the arclength counts displacements in units of the first orbit's
  const auto curve = nbm::forced_response(*b.problem, b.F0, {b.Fc}, {b.Fs}, b.zero, b.zero,
                                          b.o, r);
  ASSERT_GE(curve.points.size(), 5u) << curve.stop_reason;
  EXPECT_EQ(curve.probe, b.o.probe);
  EXPECT_NE(curve.stop_reason.find("bound"), std::string::npos) << curve.stop_reason;
  EXPECT_TRUE(curve.events.empty());
  EXPECT_NEAR(curve.points.back().omega, 2.2, 1e-9);
  double top = 0;
  for (const auto& p : curve.points) {
    const double ref = bar_response(b, p.omega, b.o.probe);
    EXPECT_NEAR(p.amplitude, ref, 1e-4 * ref) << "omega " << p.omega;
    EXPECT_TRUE(p.stable);
    EXPECT_EQ(p.switches, 0);
    top = std::max(top, p.amplitude);
  }
  EXPECT_GT(top, 3 * curve.points.front().amplitude);  // it crossed the resonance (pi/2)
  // Every point as an orbit, by index: the forced orbit at the point's
  // frequency, whose probe amplitude is the closed form's too.
  ASSERT_EQ(curve.orbits->size(), curve.points.size());
  for (std::size_t k : {std::size_t{0}, curve.points.size() / 2, curve.points.size() - 1}) {
    const nbm::OrbitReport o = curve.orbits->report(k);
    const double ref = bar_response(b, curve.points[k].omega, b.o.probe);
    EXPECT_EQ(o.omega, curve.points[k].omega);
    EXPECT_NEAR(o.period, 2 * M_PI / o.omega, 1e-14 * o.period);
    EXPECT_NEAR(o.amplitude, ref, 1e-4 * ref) << "point " << k;
    EXPECT_LT(o.periodicity_residual, 1e-10);
    EXPECT_NE(o.summary.find("pseudo-arclength continuation in omega (point " + std::to_string(k)),
              std::string::npos);
  }
  EXPECT_THROW(curve.orbits->report(curve.points.size()), nbm::InputError);
  // The CSV: a header and a row per point.
  const std::string path = testing::TempDir() + "forced-response.csv";
  nbm::write_forced_response(curve, path);
  std::ifstream f(path);
  std::string line;
  int rows = 0;
  std::getline(f, line);
  EXPECT_EQ(line.rfind("point,omega,scale,", 0), 0u);
  while (std::getline(f, line)) ++rows;
  EXPECT_EQ(rows, static_cast<int>(curve.points.size()));
  std::remove(path.c_str());
}

// In the amplitude factor the linear response grows in proportion.
TEST(UserForcedOrbit, AmplitudeCurveOfTheLinearBarIsProportional) {
  ForcedBar b;
  nbm::ForcedResponseOptions r;
  r.parameter = "amplitude";
  r.to = 3;
  r.from = 0.5;
  const auto curve = nbm::forced_response(*b.problem, b.F0, {b.Fc}, {b.Fs}, b.zero, b.zero,
                                          b.o, r);
  ASSERT_GE(curve.points.size(), 3u);
  const double unit = curve.points.front().amplitude;
  for (const auto& p : curve.points) EXPECT_NEAR(p.amplitude, p.scale * unit, 1e-9 * p.amplitude);
  EXPECT_NEAR(curve.points.back().scale, 3, 1e-9);
}

template <class F>
void expect_input_error(F&& f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no error, expected: " << text;
  } catch (const nbm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

// Forced orbits on the reduced basis (modes > 0) of a bar that strikes its
// wall: with every fixed-interface mode the reduced model is the full one
// (the same orbit to round-off, a zero reduction residual); with fewer, the
// orbit approaches the full model's as modes are added, and the reported
// reduction residual (the full model's equations, damping and excitation
// included, along the reduced orbit) falls with the error. Variants: the
// massless boundary, the paper's NBM, a moving wall, an assembled damping
// matrix.
TEST(UserForcedOrbit, ReducedBasisOrbitsConvergeToTheFullModels) {
  for (int variant = 0; variant < 4; ++variant) {
    nbm_test::GapBar bar;
    bar.N = 40, bar.g = 0.02, bar.massless = variant != 1;
    const auto problem = bar.problem();
    const int n = bar.N + 1;
    std::vector<double> zero(n, 0.0), Fc(n, 0.0);
    for (int i = 1; i < bar.N; ++i) Fc[i] = 0.02 * std::sin(0.5 * M_PI * i * bar.h());
    nbm::ForcedOrbitOptions o;
    o.omega = 1.45;  // below the first mode, pi / 2: the tip strikes the wall
    o.rayleigh_mass = 0.05, o.rayleigh_stiffness = 1e-3;
    o.probe = bar.N - 1;
    o.transient_periods = 20;
    if (variant == 2) o.gap_cos = {{0.005}};  // the wall moves
    if (variant == 3) {
      // An assembled damping matrix on the first half of the bar.
      o.damping.rows = o.damping.cols = n;
      for (long i = 1; i < bar.N / 2; ++i)
        o.damping.i.push_back(i), o.damping.j.push_back(i), o.damping.value.push_back(0.02 * bar.h());
    }
    const nbm::OrbitReport full = nbm::forced_orbit(*problem, zero, {Fc}, {}, zero, zero, o);
    ASSERT_GE(full.switches, 2) << variant << ": the tip should strike the wall";
    const Vector u_full = Eigen::Map<const Vector>(full.u0.data(), n);
    std::vector<double> errors, residuals;
    for (int modes : {2, 4, 8, 39}) {
      nbm::ForcedOrbitOptions r = o;
      r.modes = modes;
      const nbm::OrbitReport red = nbm::forced_orbit(*problem, zero, {Fc}, {}, full.u0, full.v0, r);
      const Vector u = Eigen::Map<const Vector>(red.u0.data(), n);
      errors.push_back((u - u_full).norm() / u_full.norm());
      residuals.push_back(red.reduction_residual);
      std::printf("forced bar, variant %d, %2d modes: state error %.2e, reduction residual %.2e, "
                  "switches %ld (full %ld)\n", variant, modes, errors.back(), residuals.back(),
                  red.switches, full.switches);
      EXPECT_LE(red.periodicity_residual, 1e-9) << variant << " " << modes;
      EXPECT_NE(red.summary.find("reduced basis: " + std::to_string(modes)), std::string::npos);
    }
    EXPECT_LT(errors[3], 1e-8) << variant;      // every mode: the full model
    EXPECT_LT(residuals[3], 1e-10) << variant;  // and no reduction error
    for (int k = 1; k < 3; ++k) {
      EXPECT_LT(errors[k], errors[k - 1]) << variant << " " << k;
      EXPECT_LT(residuals[k], residuals[k - 1]) << variant << " " << k;
    }
    EXPECT_GT(residuals[0], 1e-6) << variant;  // the residual sees a real reduction error
  }
}

TEST(UserForcedOrbit, BadInputIsNamed) {
  ForcedBar b;
  auto with = [&](auto change, const std::string& text) {
    ForcedBar c;
    change(c);
    expect_input_error([&] { c.solve(); }, text);
  };
  with([](ForcedBar& c) { c.o.omega = 0; }, "omega: expected a finite excitation frequency > 0");
  with([](ForcedBar& c) { c.o.omega = NAN; }, "omega: expected");
  with([](ForcedBar& c) { c.o.subharmonic = 0; }, "subharmonic: expected m >= 1");
  with([](ForcedBar& c) { c.o.rayleigh_mass = -1; }, "rayleighM: -1");
  with([](ForcedBar& c) { c.o.rayleigh_stiffness = INFINITY; }, "rayleighK: inf");
  with([](ForcedBar& c) { c.o.probe = 0; }, "probe: dof 0 is fixed");
  with([](ForcedBar& c) { c.o.probe = 99; }, "probe: dof 99 out of range");
  with([](ForcedBar& c) { c.o.transient_periods = -1; }, "transient: expected");
  with([](ForcedBar& c) { c.o.max_iterations = 0; }, "iterations: expected >= 1");
  with([](ForcedBar& c) { c.o.modes = -1; }, "modes: -1; expected >= 0");
  with([](ForcedBar& c) { c.o.modes = 12; }, "modes: 12; expected 1 .. 11");
  with([](ForcedBar& c) { c.o.gap_cos = {{0.1, 0.2}}; },
       "gapCos (harmonic 1): size 2, expected 1 (one value per contact node)");
  with([](ForcedBar& c) { c.o.gap_sin = {{0}, {NAN}}; },
       "gapSin (harmonic 2): non-finite entries");
  with([](ForcedBar& c) { c.Fs.pop_back(); }, "Fs (harmonic 1): size 12, expected 13");
  with([](ForcedBar& c) { c.Fs[3] = NAN; }, "Fs (harmonic 1): non-finite");
  with([](ForcedBar& c) { c.F0.push_back(0); }, "F0: size 14, expected 13");
  with([](ForcedBar& c) { c.o.method = "newton"; },
       "method: \"newton\"; expected \"shooting\" or \"harmonic-balance\"");
  with([](ForcedBar& c) { c.o.method = "harmonic-balance", c.o.harmonics = 0; },
       "harmonics: 0; expected m .. 320");
  with([](ForcedBar& c) { c.o.method = "harmonic-balance", c.o.subharmonic = 3, c.o.harmonics = 2; },
       "harmonics: 2; expected m .. 320 (m = 3");
  expect_input_error(
      [&] { nbm::forced_orbit(*b.problem, b.F0, {}, {}, b.zero, b.zero, b.o); },
      "Fc, Fs, gapCos, gapSin: no harmonic");
  auto response = [&](nbm::ForcedResponseOptions r, const std::string& text) {
    expect_input_error(
        [&] { nbm::forced_response(*b.problem, b.F0, {b.Fc}, {b.Fs}, b.zero, b.zero, b.o, r); },
        text);
  };
  nbm::ForcedResponseOptions r;
  response(r, "to: expected a finite end of the omega range");
  r.to = b.o.omega;
  response(r, "to: expected a finite end");
  r.to = 3;
  r.from = 2.5;
  response(r, "from: expected the other end of the omega range");
  r.from = NAN;
  r.parameter = "force";
  response(r, "parameter: \"force\"; expected \"omega\" or \"amplitude\"");
  r.parameter = "omega";
  r.step = 0;
  response(r, "step, maxStep: expected 0 < step <= maxStep");
  r.step = 0.02;
  r.max_points = 0;
  response(r, "points: expected >= 1");
  // Branch switching needs a period doubling: the linear bar has none.
  r.max_points = 3;
  r.doubling = true;
  r.doubling_amplitude = -1;
  response(r, "doublingAmplitude: expected a finite amplitude > 0");
  r.doubling_amplitude = 1e-3;
  response(r, "doubling: no period doubling on the curve (3 points, 0 events");
  r.doubling = false;
  r.max_points = 5;
  b.o.method = "harmonic-balance";
  response(r, "method: \"harmonic-balance\"; the continuation of forced orbits corrects by shooting");
  b.o.method = "shooting";
  // Autonomous continuation refuses forced orbits.
  const auto orbit = b.solve();
  expect_input_error([&] { nbm::continue_orbit(orbit, orbit, 0.1); },
                     "continuation follows autonomous orbits");
}

}  // namespace
