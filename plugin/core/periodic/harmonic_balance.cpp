#include "periodic/harmonic_balance.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "base/errors.hpp"
#include "periodic/trig_galerkin.hpp"

namespace nbm {

HarmonicBalanceResult harmonic_balance(const ReducedField& field, const Vector& u0,
                                       const Vector& v0, double T,
                                       const HarmonicBalanceOptions& o) {
  const Index n = field.size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("harmonic balance: initial state of size " + std::to_string(u0.size()) +
                     ", expected " + std::to_string(n) + " interior dofs");
  if (!u0.allFinite() || !v0.allFinite())
    throw InputError("harmonic balance: non-finite initial state");
  if (!(T > 0) || !std::isfinite(T))
    throw InputError("harmonic balance: the period guess must be > 0");
  if (o.harmonics < 1 || o.harmonics > o.max_harmonics)
    throw InputError("harmonic balance: harmonics must be in [1, max_harmonics]");
  if (o.probe < 0 || o.probe >= n)
    throw InputError("harmonic balance: probe " + std::to_string(o.probe) + " out of range [0, " +
                     std::to_string(n) + ")");
  if (o.integration == HarmonicBalanceOptions::Integration::aft && o.aft_samples < 0)
    throw InputError("harmonic balance: aft_samples must be >= 0");

  // Initial coefficients: Fourier series of the exact flow from the guess
  // over one period, or for cosine-only series over half a period, mirrored.
  TrigBasis basis{o.harmonics, o.cosine_only};
  Matrix C = fourier_coefficients(ExactFlow(field), u0, v0, T, basis);
  double omega = 2 * M_PI / T;

  HarmonicBalanceResult out;
  const double target = std::isnan(o.amplitude)
                            ? amplitude_value(field, o.kind, o.probe, u0, v0, T)
                            : o.amplitude;
  const double amp_scale = std::max(std::abs(target), periodic_tiny);

  for (;;) {
    const Index nb = basis.size(), N = n * nb;
    const bool phase = !basis.cosine_only;
    auto weights = [&](const Matrix& C, const TrigBasis& test) {
      return o.integration == HarmonicBalanceOptions::Integration::exact
                 ? exact_weights(field, C, basis, test)
                 : sampled_weights(field, C, basis, test,
                                   o.aft_samples > 0 ? o.aft_samples : 32 * test.H);
    };
    // Undamped and autonomous: M_S u'' + K_S u has the coefficients
    // K_S C + omega^2 M_S C D2 (trig_galerkin.hpp), D2 = d^2/dtau^2.
    const Matrix D2 = second_derivative_matrix(basis);
    auto op = [&](double omega) {
      return SeriesOperator{Matrix::Identity(nb, nb), omega * omega * D2};
    };
    // Jacobian of the scaled equations with the switching times frozen; its
    // omega column projects the omega derivative of the operator.
    auto jacobian_of = [&](const Matrix& C, double omega, const RegionWeights& w, double scale) {
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

    // Equations: the Galerkin residual, the phase, the amplitude condition,
    // of the unknowns y = (C column by column, omega); merit = size = |E|.
    // The region weights of the last evaluation are kept: the Jacobian is
    // asked for at the accepted trial point.
    Vector last_y;
    RegionWeights last_w;
    auto evaluate = [&](const Vector& y, bool jacobian) {
      GaussNewtonEvaluation e;
      const Matrix C = Eigen::Map<const Matrix>(y.data(), n, nb);
      const double omega = y(N);
      if (!(omega > 0) || !C.allFinite()) return e;
      RegionWeights w = last_y.size() == y.size() && last_y == y ? std::move(last_w)
                                                                 : weights(C, basis);
      const Balance b = galerkin_residual(field, w, C, op(omega));
      const Vector u = series(C, basis, 0), v = omega * series(C, basis, 0, true);
      const double amp =
          amplitude_value(field, o.kind, o.probe, u, v, 2 * M_PI / omega) - target;
      const double vs = std::max(u.norm(), C.norm()) * omega;
      e.R.resize(N + (phase ? 2 : 1));
      e.R.head(N) = Eigen::Map<const Vector>(b.R.data(), N) / b.scale;
      if (phase) e.R(N) = v(o.probe) / std::max(vs, periodic_tiny);
      e.R(e.R.size() - 1) = amp / amp_scale;
      e.merit = e.size = e.R.norm();
      if (jacobian) e.J = jacobian_of(C, omega, w, b.scale);
      last_y = y, last_w = std::move(w);
      return e;
    };

    // Damped Gauss-Newton (gauss_newton.hpp), the trust region on omega.
    GaussNewtonOptions gn;
    gn.period_index = N;
    gn.tolerance = o.tolerance;
    gn.max_iterations = o.max_iterations;
    gn.solver = GaussNewtonOptions::Solver::householder;
    gn.name = "harmonic balance";
    gn.context = "at H = " + std::to_string(basis.H) + " ";
    Vector y(N + 1);
    y << Eigen::Map<const Vector>(C.data(), N), omega;
    const GaussNewtonResult solution = gauss_newton(evaluate, std::move(y), gn);
    C = Eigen::Map<const Matrix>(solution.y.data(), n, nb);
    omega = solution.y(N);
    out.orbit.residual_history.insert(out.orbit.residual_history.end(),
                                      solution.merits.begin(), solution.merits.end());
    out.orbit.iterations += solution.iterations;
    out.residual = solution.last.merit;

    // Truncation: the residual of this solution on harmonics H+1 .. 2H.
    const TrigBasis wide{2 * basis.H, basis.cosine_only};
    const Balance high = galerkin_residual(field, weights(C, wide), C, op(omega));
    const Index first = basis.size();
    out.truncation =
        high.R.rightCols(wide.size() - first).norm() / std::max(high.scale, periodic_tiny);
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
  out.orbit.period = 2 * M_PI / omega;
  analyse_orbit(field, out.orbit);
  return out;
}

}  // namespace nbm
