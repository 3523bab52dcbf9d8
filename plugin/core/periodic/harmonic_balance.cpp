#include "harmonic_balance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <string>


#include "errors.hpp"
#include "trig_sum.hpp"

namespace nbm {
namespace {

// The trigonometric basis psi_j(tau): 1, cos tau, sin tau, cos 2tau, ... or
// 1, cos tau, cos 2tau, ... (cosine only).
struct Basis {
  int H;
  bool cosine_only;
  Index size() const { return cosine_only ? H + 1 : 2 * H + 1; }
  int harmonic(Index j) const {
    return cosine_only ? static_cast<int>(j) : static_cast<int>((j + 1) / 2);
  }
  bool sine(Index j) const { return !cosine_only && j > 0 && j % 2 == 0; }
  double value(Index j, double tau) const {
    return sine(j) ? std::sin(harmonic(j) * tau) : std::cos(harmonic(j) * tau);
  }
  double slope(Index j, double tau) const {  // d psi_j / d tau
    const int h = harmonic(j);
    return sine(j) ? h * std::cos(h * tau) : -h * std::sin(h * tau);
  }
  /// Column of the full layout (c0, a1, b1, ...) of basis function j.
  Index full_column(Index j) const {
    return cosine_only ? (j == 0 ? 0 : 2 * j - 1) : j;
  }
};

// (1/pi) int psi_j psi_k and (1/pi) int psi_j over the part of the period in
// one region (j: test basis, k: trial basis).
struct Weights {
  Matrix Psi;
  Vector phi;
};
using RegionWeights = std::map<ActiveSet, Weights>;

Weights& weights_of(RegionWeights& w, const ActiveSet& s, const Basis& test, const Basis& trial) {
  auto it = w.find(s);
  if (it == w.end())
    it = w.emplace(s, Weights{Matrix::Zero(test.size(), trial.size()), Vector::Zero(test.size())})
             .first;
  return it->second;
}

// Exact integrals over [a, b] by product-to-sum formulas.
void add_interval(Weights& w, const Basis& test, const Basis& trial, double a, double b) {
  const int top = test.H + trial.H;
  Vector Ic(top + 1), Is(top + 1);  // int cos(m tau), int sin(m tau)
  Ic(0) = b - a, Is(0) = 0;
  for (int m = 1; m <= top; ++m) {
    Ic(m) = (std::sin(m * b) - std::sin(m * a)) / m;
    Is(m) = (std::cos(m * a) - std::cos(m * b)) / m;
  }
  for (Index j = 0; j < test.size(); ++j) {
    const int p = test.harmonic(j);
    const bool sp = test.sine(j);
    w.phi(j) += (sp ? Is(p) : Ic(p)) / M_PI;
    for (Index k = 0; k < trial.size(); ++k) {
      const int q = trial.harmonic(k), d = std::abs(p - q), s = p >= q ? 1 : -1;
      const bool sq = trial.sine(k);
      double v;
      if (!sp && !sq) v = 0.5 * (Ic(d) + Ic(p + q));
      else if (sp && sq) v = 0.5 * (Ic(d) - Ic(p + q));
      else if (sp) v = 0.5 * (Is(p + q) + s * Is(d));   // sin p cos q
      else v = 0.5 * (Is(p + q) - s * Is(d));           // cos p sin q
      w.Psi(j, k) += v / M_PI;
    }
  }
}

// u(tau) and du/dtau from the coefficients C (n x trial.size()).
Vector series(const Matrix& C, const Basis& b, double tau, bool derivative = false) {
  Vector u = Vector::Zero(C.rows());
  for (Index k = 0; k < b.size(); ++k)
    u += (derivative ? b.slope(k, tau) : b.value(k, tau)) * C.col(k);
  return u;
}

RegionWeights exact_weights(const ReducedField& field, const Matrix& C, const Basis& trial,
                            const Basis& test) {
  RegionWeights w;
  double tau = 0;
  ActiveSet S = field.active_set(series(C, trial, 0));
  for (long pieces = 0; tau < 2 * M_PI; ++pieces) {
    if (pieces > 100'000)
      throw NumericalError("harmonic balance: more than 100000 contact switches per period");
    const auto r_held = field.region(S);
    const Region& r = *r_held;
    // Switching functions along the series: h(tau) = d + H u(tau).
    TrigSum h;
    h.c = r.d + r.H * C.col(0);
    h.p = h.q = Vector::Zero(r.d.size());
    h.a = Matrix::Zero(r.d.size(), trial.H);
    h.b = Matrix::Zero(r.d.size(), trial.H);
    h.nu.resize(trial.H);
    for (Index k = 1; k < trial.size(); ++k)
      (trial.sine(k) ? h.b : h.a).col(trial.harmonic(k) - 1) = r.H * C.col(k);
    for (int m = 0; m < trial.H; ++m) h.nu(m) = m + 1;
    const auto crossing = first_crossing(h, tau, 2 * M_PI);
    const double end = crossing ? crossing->t : 2 * M_PI;
    add_interval(weights_of(w, S, test, trial), test, trial, tau, end);
    if (!crossing) break;
    S = field.switched(r, series(C, trial, end), series(C, trial, end, true), crossing->row);
    tau = end;
  }
  return w;
}

RegionWeights sampled_weights(const ReducedField& field, const Matrix& C, const Basis& trial,
                              const Basis& test, int samples) {
  RegionWeights w;
  for (int m = 0; m < samples; ++m) {
    const double tau = 2 * M_PI * m / samples;
    Weights& x = weights_of(w, field.active_set(series(C, trial, tau)), test, trial);
    for (Index j = 0; j < test.size(); ++j) {
      const double pj = test.value(j, tau) * 2.0 / samples;
      x.phi(j) += pj;
      for (Index k = 0; k < trial.size(); ++k) x.Psi(j, k) += pj * trial.value(k, tau);
    }
  }
  return w;
}

struct Balance {
  Matrix R;      // n x test.size()
  double scale;  // size of the terms of R
};

// R = sum_S (K_S C - omega^2 M_S C D) Psi_S^T - f_S phi_S^T, D = diag(h^2).
Balance residual(const ReducedField& field, const RegionWeights& w, const Matrix& C,
                 const Basis& trial, double omega) {
  Vector D(trial.size());
  for (Index k = 0; k < trial.size(); ++k) D(k) = std::pow(trial.harmonic(k), 2);
  const Matrix CD = C * D.asDiagonal();
  Balance b{Matrix::Zero(C.rows(), w.begin()->second.Psi.rows()), 0};
  Matrix stiff = b.R, inertia = b.R, load = b.R;
  for (const auto& [S, x] : w) {
    const auto r_held = field.region(S);
    const Region& r = *r_held;
    stiff += r.K * C * x.Psi.transpose();
    inertia += omega * omega * (r.M * CD) * x.Psi.transpose();
    load += r.f * x.phi.transpose();
  }
  b.R = stiff - inertia - load;
  b.scale = std::max({stiff.norm(), inertia.norm(), load.norm(), periodic_tiny});
  return b;
}

}  // namespace

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
  // over one period, or for cosine-only series over half a period, mirrored
  // (an even extension, continuous even when the guess is not periodic).
  Basis basis{o.harmonics, o.cosine_only};
  Matrix C = Matrix::Zero(n, basis.size());
  {
    const int samples = std::max(64, 8 * (o.harmonics + 1));
    const double span = o.cosine_only ? 0.5 * T : T;
    std::vector<double> times(samples);
    for (int m = 0; m < samples; ++m) times[m] = span * m / samples;
    const auto flow = ExactFlow(field).integrate(u0, o.cosine_only ? Vector::Zero(n) : v0, span,
                                                 false, times);
    for (int m = 0; m < 2 * samples; ++m) {
      const int sample = m < samples ? m : 2 * samples - m;
      if (!o.cosine_only && m >= samples) break;
      const Vector u = sample < samples ? Vector(flow.samples.col(sample).head(n)) : flow.u;
      const double tau = (o.cosine_only ? M_PI : 2 * M_PI) * m / samples;
      const double weight = (o.cosine_only ? 0.5 : 1.0) / samples;
      for (Index k = 0; k < basis.size(); ++k)
        C.col(k) += (k == 0 ? 1.0 : 2.0) * weight * basis.value(k, tau) * u;
    }
  }
  double omega = 2 * M_PI / T;

  HarmonicBalanceResult out;
  const double target = std::isnan(o.amplitude)
                            ? amplitude_value(field, o.kind, o.probe, u0, v0, T)
                            : o.amplitude;
  const double amp_scale = std::max(std::abs(target), periodic_tiny);

  for (;;) {
    const Index nb = basis.size(), N = n * nb;
    const bool phase = !basis.cosine_only;
    auto weights = [&](const Matrix& C, const Basis& test) {
      return o.integration == HarmonicBalanceOptions::Integration::exact
                 ? exact_weights(field, C, basis, test)
                 : sampled_weights(field, C, basis, test,
                                   o.aft_samples > 0 ? o.aft_samples : 32 * test.H);
    };
    // Jacobian of the scaled equations with the switching times frozen.
    auto jacobian_of = [&](const Matrix& C, double omega, const RegionWeights& w, double scale) {
      Matrix J = Matrix::Zero(N + (phase ? 2 : 1), N + 1);
      Vector D(nb);
      for (Index k = 0; k < nb; ++k) D(k) = std::pow(basis.harmonic(k), 2);
      for (const auto& [S, x] : w) {
        const auto r_held = field.region(S);
        const Region& r = *r_held;
        for (Index k = 0; k < nb; ++k) {
          const Matrix block = (r.K - (omega * omega * D(k)) * r.M) / scale;
          for (Index j = 0; j < nb; ++j)
            if (x.Psi(j, k) != 0) J.block(j * n, k * n, n, n) += x.Psi(j, k) * block;
        }
        const Matrix dR = (-2 * omega / scale) * (r.M * C * D.asDiagonal()) * x.Psi.transpose();
        J.col(N).head(N) += Eigen::Map<const Vector>(dR.data(), N);
      }
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
      const Balance b = residual(field, w, C, basis, omega);
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
    const Basis wide{2 * basis.H, basis.cosine_only};
    const Balance high = residual(field, weights(C, wide), C, basis, omega);
    const Index first = basis.size();
    out.truncation =
        high.R.rightCols(wide.size() - first).norm() / std::max(high.scale, periodic_tiny);
    out.harmonics_tried.push_back(basis.H);
    if (!o.adaptive || out.truncation <= o.truncation_tolerance ||
        2 * basis.H > o.max_harmonics)
      break;
    // Double H, starting from the current coefficients.
    const Basis next{2 * basis.H, basis.cosine_only};
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
