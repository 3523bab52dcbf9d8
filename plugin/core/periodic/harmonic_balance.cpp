#include "periodic/harmonic_balance.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "base/errors.hpp"
#include "periodic/trig_galerkin.hpp"

namespace nbm {
namespace {

// The harmonic load on the test basis: (1/pi) int psi_j F_h dtau. Harmonic
// k of the excitation, Re(load_k e^{i Omega_k t}) = Fc_k cos + Fs_k sin with
// Fc_k = Re(load_k), Fs_k = -Im(load_k), is harmonic Omega_k / nu of the
// series: its amplitudes are its two coefficients (none beyond the basis).
Matrix projected_load(const FlowForcing& forcing, double nu, const TrigBasis& test, Index n) {
  Matrix L = Matrix::Zero(n, test.size());
  for (std::size_t k = 0; k < forcing.load.size(); ++k) {
    const int h = static_cast<int>(std::lround(forcing.Omega[k] / nu));
    if (h > test.H) continue;
    L.col(2 * h - 1) = forcing.load[k].real();
    L.col(2 * h) = -forcing.load[k].imag();
  }
  return L;
}

void check(const PeriodicProblem& problem, const Vector& u0, const Vector& v0, double T,
           const HarmonicBalanceOptions& o, const std::string& name) {
  problem.check_guess(u0, v0, T, name);
  const Index n = problem.field().size();
  if (o.harmonics < 1 || o.harmonics > o.max_harmonics)
    throw InputError(name + ": harmonics must be in [1, max_harmonics]");
  if (o.integration == HarmonicBalanceOptions::Integration::aft && o.aft_samples < 0)
    throw InputError(name + ": aft_samples must be >= 0, got " + std::to_string(o.aft_samples));
  if (!(o.tolerance > 0)) throw InputError(name + ": tolerance must be > 0");
  if (o.max_iterations < 1) throw InputError(name + ": max_iterations must be >= 1");
  if (o.transient_periods < 0)
    throw InputError(name + ": transient_periods must be >= 0, got " +
                     std::to_string(o.transient_periods));
  if (!problem.forced()) {
    if (o.probe < 0 || o.probe >= n)
      throw InputError(name + ": probe " + std::to_string(o.probe) + " out of range [0, " +
                       std::to_string(n) + ")");
    return;
  }
  const FlowForcing& forcing = problem.flow().forcing();
  if (forcing.moves_contacts())
    throw InputError(name + ": moving gaps or loads on the contact dofs are not supported (the "
                     "Galerkin residual has fixed regions' loads); use shooting");
  if (forcing.C_interior)
    throw InputError(name + ": an assembled damping matrix is not supported (the Galerkin "
                     "operator carries Rayleigh damping only); use shooting");
  if (o.harmonics < problem.subharmonic())
    throw InputError(name + ": harmonics H = " + std::to_string(o.harmonics) +
                     ", expected H >= the subharmonic order m = " +
                     std::to_string(problem.subharmonic()) +
                     " (the load's first harmonic is harmonic m of the series)");
  if (o.cosine_only)
    throw InputError(name + ": cosine_only is an autonomous orbit's (a forced orbit's time "
                     "origin is the excitation's)");
  if (!std::isnan(o.amplitude))
    throw InputError(name + ": the amplitude condition is an autonomous orbit's (the "
                     "excitation fixes a forced orbit's period)");
}

}  // namespace

HarmonicBalanceResult harmonic_balance(const PeriodicProblem& problem, const Vector& u0,
                                       const Vector& v0, double T,
                                       const HarmonicBalanceOptions& o) {
  const bool forced = problem.forced();
  const std::string name = forced ? "forced harmonic balance" : "harmonic balance";
  check(problem, u0, v0, T, o, name);
  const ReducedField& field = problem.field();
  const ExactFlow& flow = problem.flow();
  const FlowForcing& forcing = flow.forcing();
  const Index n = field.size();

  // Initial coefficients: Fourier series of the exact flow from the guess
  // over one period, or for cosine-only series over half a period, mirrored.
  Vector u_start = u0, v_start = v0;
  if (o.transient_periods > 0) {
    const FlowResult settled = flow.integrate(u0, v0, o.transient_periods * T, false);
    u_start = settled.u, v_start = settled.v;
  }
  TrigBasis basis{o.harmonics, o.cosine_only};
  Matrix C = fourier_coefficients(flow, u_start, v_start, T, basis);
  // tau = omega t: omega is an autonomous orbit's unknown frequency, a
  // forced one's nu = (excitation frequency) / m.
  double omega = 2 * M_PI / T;

  HarmonicBalanceResult out;
  const double target = forced ? 0
                        : std::isnan(o.amplitude)
                            ? amplitude_value(field, o.kind, o.probe, u_start, v_start, T)
                            : o.amplitude;
  const double amp_scale = std::max(std::abs(target), periodic_tiny);

  for (;;) {
    const Index nb = basis.size(), N = n * nb;
    const bool phase = !forced && !basis.cosine_only;
    auto weights = [&](const Matrix& C, const TrigBasis& test) {
      return o.integration == HarmonicBalanceOptions::Integration::exact
                 ? exact_weights(field, C, basis, test)
                 : sampled_weights(field, C, basis, test,
                                   o.aft_samples > 0 ? o.aft_samples : 32 * test.H);
    };
    // M_S u'' + C_S u' + K_S u on the coefficients (trig_galerkin.hpp),
    // D1 = d/dtau, D2 = d^2/dtau^2: K_S C (I + b_K omega D1) + M_S C
    // (a_M omega D1 + omega^2 D2) forced; undamped, K_S C + omega^2 M_S C D2.
    const Matrix D2 = second_derivative_matrix(basis);
    const Matrix D1 = forced ? derivative_matrix(basis) : Matrix();
    auto op = [&](double omega) {
      if (forced)
        return SeriesOperator{Matrix::Identity(nb, nb) + (forcing.b_K * omega) * D1,
                              (forcing.a_M * omega) * D1 + (omega * omega) * D2};
      return SeriesOperator{Matrix::Identity(nb, nb), omega * omega * D2};
    };
    auto load = [&](const TrigBasis& test) {
      return forced ? projected_load(forcing, omega, test, n) : Matrix();
    };
    const Matrix load_on_basis = load(basis);
    // Jacobian of the scaled equations with the switching times frozen; an
    // autonomous orbit's omega column projects the omega derivative of the
    // operator, and its phase and amplitude rows follow.
    auto jacobian_of = [&](const Matrix& C, double omega, const RegionWeights& w, double scale) {
      if (forced) return galerkin_jacobian(field, w, op(omega), scale);
      Matrix J = Matrix::Zero(N + (phase ? 2 : 1), N + 1);
      J.topLeftCorner(N, N) = galerkin_jacobian(field, w, op(omega), scale);
      const SeriesOperator d_omega{Matrix::Zero(nb, nb), 2 * omega * D2};
      const Matrix dR = galerkin_product(field, w, C, d_omega) / scale;
      J.col(N).head(N) = Eigen::Map<const Vector>(dR.data(), N);
      const Vector u = series(C, basis, 0), du = series(C, basis, 0, true);
      if (phase) {
        const double vs = std::max(std::max(u.norm(), C.norm()) * omega, periodic_tiny);
        for (Index k = 0; k < nb; ++k) J(N, k * n + o.probe) = omega * basis.slope(k, 0) / vs;
        J(N, N) = du(o.probe) / vs;
      }
      const Index a = J.rows() - 1;
      // The amplitude condition's gradient in (u, v, T) (shooting.hpp), with
      // u = sum_k C_k psi_k(0), v = omega sum_k C_k psi_k'(0), T = 2 pi / omega.
      const Vector g = amplitude_gradient(field, o.kind, o.probe, u, omega * du);
      const auto gu = g.head(n), gv = g.segment(n, n);
      for (Index k = 0; k < nb; ++k)
        J.block(a, k * n, 1, n) =
            (basis.value(k, 0) * gu + omega * basis.slope(k, 0) * gv).transpose() / amp_scale;
      J(a, N) = (gv.dot(du) + g(2 * n) * (-2 * M_PI / (omega * omega))) / amp_scale;
      return J;
    };

    // Equations: the Galerkin residual, and for an autonomous orbit the
    // phase and the amplitude condition, of the unknowns y = (C column by
    // column[, omega]); merit = size = |E|. The region weights of the last
    // evaluation are kept: the Jacobian is asked for at the accepted trial
    // point.
    Vector last_y;
    RegionWeights last_w;
    auto evaluate = [&](const Vector& y, bool jacobian) {
      GaussNewtonEvaluation e;
      const Matrix C = Eigen::Map<const Matrix>(y.data(), n, nb);
      const double w_y = forced ? omega : y(N);
      if (!(w_y > 0) || !y.allFinite()) return e;
      RegionWeights w = last_y.size() == y.size() && last_y == y ? std::move(last_w)
                                                                 : weights(C, basis);
      const Balance b = galerkin_residual(field, w, C, op(w_y), load_on_basis);
      e.R.resize(N + (forced ? 0 : phase ? 2 : 1));
      e.R.head(N) = Eigen::Map<const Vector>(b.R.data(), N) / b.scale;
      if (!forced) {
        const Vector u = series(C, basis, 0), v = w_y * series(C, basis, 0, true);
        const double amp =
            amplitude_value(field, o.kind, o.probe, u, v, 2 * M_PI / w_y) - target;
        const double vs = std::max(u.norm(), C.norm()) * w_y;
        if (phase) e.R(N) = v(o.probe) / std::max(vs, periodic_tiny);
        e.R(e.R.size() - 1) = amp / amp_scale;
      }
      e.merit = e.size = e.R.norm();
      if (jacobian) e.J = jacobian_of(C, w_y, w, b.scale);
      last_y = y, last_w = std::move(w);
      return e;
    };

    // Damped Gauss-Newton (gauss_newton.hpp), the trust region on an
    // autonomous orbit's omega.
    GaussNewtonOptions gn;
    gn.period_index = forced ? -1 : N;
    gn.tolerance = o.tolerance;
    gn.max_iterations = o.max_iterations;
    gn.solver = GaussNewtonOptions::Solver::householder;
    gn.name = name;
    gn.context = "at H = " + std::to_string(basis.H) +
                 (forced ? ", omega = " + std::to_string(forcing.Omega.front()) : "") + " ";
    Vector y(N + (forced ? 0 : 1));
    y.head(N) = Eigen::Map<const Vector>(C.data(), N);
    if (!forced) y(N) = omega;
    const GaussNewtonResult solution = gauss_newton(evaluate, std::move(y), gn);
    C = Eigen::Map<const Matrix>(solution.y.data(), n, nb);
    if (!forced) omega = solution.y(N);
    out.orbit.residual_history.insert(out.orbit.residual_history.end(),
                                      solution.merits.begin(), solution.merits.end());
    out.orbit.iterations += solution.iterations;
    out.residual = solution.last.merit;

    // Truncation: what the solution leaves unbalanced on harmonics H+1 .. 2H
    // (the load's harmonics there included).
    const TrigBasis wide{2 * basis.H, basis.cosine_only};
    const Balance high = galerkin_residual(field, weights(C, wide), C, op(omega), load(wide));
    out.truncation = high.R.rightCols(wide.size() - nb).norm() / std::max(high.scale, periodic_tiny);
    out.harmonics_tried.push_back(basis.H);
    if (!o.adaptive || out.truncation <= o.truncation_tolerance ||
        2 * basis.H > o.max_harmonics)
      break;
    // Double H, starting from the current coefficients.
    const TrigBasis next{2 * basis.H, basis.cosine_only};
    Matrix Cn = Matrix::Zero(n, next.size());
    Cn.leftCols(basis.size()) = C;
    basis = next, C = std::move(Cn);
  }

  out.harmonics = basis.H;
  out.coefficients = Matrix::Zero(n, 2 * basis.H + 1);
  for (Index k = 0; k < basis.size(); ++k) out.coefficients.col(basis.full_column(k)) = C.col(k);
  out.orbit.u0 = series(C, basis, 0);
  out.orbit.v0 = omega * series(C, basis, 0, true);
  out.orbit.period = forced ? T : 2 * M_PI / omega;
  analyse_orbit(flow, out.orbit, !forced);
  return out;
}

}  // namespace nbm
