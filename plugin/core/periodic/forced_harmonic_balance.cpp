#include "periodic/forced_harmonic_balance.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "base/errors.hpp"
#include "periodic/forced_orbit.hpp"
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

}  // namespace

HarmonicBalanceResult forced_harmonic_balance(const ExactFlow& flow, const Vector& u0,
                                              const Vector& v0,
                                              const ForcedHarmonicBalanceOptions& o) {
  const ReducedField& field = flow.field();
  const Index n = field.size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("forced harmonic balance: initial state of size " +
                     std::to_string(u0.size()) + " and " + std::to_string(v0.size()) +
                     ", expected " + std::to_string(n) + " interior dofs");
  if (!u0.allFinite() || !v0.allFinite())
    throw InputError("forced harmonic balance: non-finite initial state");
  const double T = forced_period(flow, o.subharmonic);  // checks the load and m
  if (flow.forcing().moves_contacts())
    throw InputError("forced harmonic balance: moving gaps or loads on the contact dofs are not "
                     "supported (the Galerkin residual has fixed regions' loads); use shooting");
  if (flow.forcing().C_interior)
    throw InputError("forced harmonic balance: an assembled damping matrix is not supported "
                     "(the Galerkin operator carries Rayleigh damping only); use shooting");
  if (o.harmonics < o.subharmonic)
    throw InputError("forced harmonic balance: harmonics H = " + std::to_string(o.harmonics) +
                     ", expected H >= the subharmonic order m = " +
                     std::to_string(o.subharmonic) +
                     " (the load's first harmonic is harmonic m of the series)");
  if (o.integration == HarmonicBalanceOptions::Integration::aft && o.aft_samples < 0)
    throw InputError("forced harmonic balance: aft_samples must be >= 0, got " +
                     std::to_string(o.aft_samples));
  if (!(o.tolerance > 0)) throw InputError("forced harmonic balance: tolerance must be > 0");
  if (o.max_iterations < 1)
    throw InputError("forced harmonic balance: max_iterations must be >= 1");
  if (o.transient_periods < 0)
    throw InputError("forced harmonic balance: transient_periods must be >= 0, got " +
                     std::to_string(o.transient_periods));

  // tau = nu t over one period, nu = omega / m; d/dt = nu d/dtau.
  const double nu = 2 * M_PI / T;
  const TrigBasis basis{o.harmonics, false}, wide{2 * o.harmonics, false};
  const Index nb = basis.size(), N = n * nb;
  Vector u_start = u0, v_start = v0;
  if (o.transient_periods > 0) {
    const FlowResult settled = flow.integrate(u0, v0, o.transient_periods * T, false);
    u_start = settled.u, v_start = settled.v;
  }
  Matrix C = fourier_coefficients(flow, u_start, v_start, T, basis);

  // M_S u'' + (a_M M_S + b_K K_S) u' + K_S u on the coefficients:
  // K_S C (I + b_K nu D1) + M_S C (a_M nu D1 + nu^2 D2).
  const FlowForcing& forcing = flow.forcing();
  const Matrix D1 = derivative_matrix(basis), D2 = second_derivative_matrix(basis);
  const SeriesOperator op{Matrix::Identity(nb, nb) + (forcing.b_K * nu) * D1,
                          (forcing.a_M * nu) * D1 + (nu * nu) * D2};
  const Matrix load = projected_load(forcing, nu, basis, n);
  auto weights = [&](const Matrix& C, const TrigBasis& test) {
    return o.integration == HarmonicBalanceOptions::Integration::exact
               ? exact_weights(field, C, basis, test)
               : sampled_weights(field, C, basis, test,
                                 o.aft_samples > 0 ? o.aft_samples : 32 * test.H);
  };

  // The scaled Galerkin residual of y = C column by column, a square system;
  // the weights of the last evaluation serve its Jacobian (asked for at the
  // accepted trial point).
  Vector last_y;
  RegionWeights last_w;
  auto evaluate = [&](const Vector& y, bool jacobian) {
    GaussNewtonEvaluation e;
    if (!y.allFinite()) return e;
    const Matrix C = Eigen::Map<const Matrix>(y.data(), n, nb);
    RegionWeights w =
        last_y.size() == y.size() && last_y == y ? std::move(last_w) : weights(C, basis);
    const Balance b = galerkin_residual(field, w, C, op, load);
    e.R = Eigen::Map<const Vector>(b.R.data(), N) / b.scale;
    e.merit = e.size = e.R.norm();
    if (jacobian) e.J = galerkin_jacobian(field, w, op, b.scale);
    last_y = y, last_w = std::move(w);
    return e;
  };
  GaussNewtonOptions gn;
  gn.period_index = -1;  // the period is the excitation's
  gn.tolerance = o.tolerance;
  gn.max_iterations = o.max_iterations;
  gn.solver = GaussNewtonOptions::Solver::householder;  // square: LU
  gn.name = "forced harmonic balance";
  gn.context = "at H = " + std::to_string(o.harmonics) + ", omega = " +
               std::to_string(forcing.Omega.front()) + " ";
  const GaussNewtonResult solution =
      gauss_newton(evaluate, Eigen::Map<const Vector>(C.data(), N), gn);
  C = Eigen::Map<const Matrix>(solution.y.data(), n, nb);

  HarmonicBalanceResult out;
  out.harmonics = o.harmonics;
  out.harmonics_tried = {o.harmonics};
  out.residual = solution.last.merit;
  // Truncation: what the solution leaves unbalanced on harmonics H+1 .. 2H
  // (the load's harmonics there included).
  const Balance high = galerkin_residual(field, weights(C, wide), C, op,
                                         projected_load(forcing, nu, wide, n));
  out.truncation = high.R.rightCols(wide.size() - nb).norm() / high.scale;
  out.coefficients = C;  // the full layout already
  out.orbit.u0 = series(C, basis, 0);
  out.orbit.v0 = nu * series(C, basis, 0, true);
  out.orbit.period = T;
  out.orbit.iterations = solution.iterations;
  out.orbit.residual_history = solution.merits;
  analyse_orbit(flow, out.orbit, false);
  return out;
}

}  // namespace nbm
