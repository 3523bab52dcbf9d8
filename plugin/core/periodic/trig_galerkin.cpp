#include "periodic/trig_galerkin.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/errors.hpp"
#include "periodic/periodic_defaults.hpp"
#include "periodic/trig_sum.hpp"

namespace nbm {
namespace {

GalerkinWeights& weights_of(RegionWeights& w, const ActiveSet& s, const TrigBasis& test,
                            const TrigBasis& trial) {
  auto it = w.find(s);
  if (it == w.end())
    it = w.emplace(s, GalerkinWeights{Matrix::Zero(test.size(), trial.size()),
                                      Vector::Zero(test.size())})
             .first;
  return it->second;
}

// Exact integrals over [a, b] by product-to-sum formulas.
void add_interval(GalerkinWeights& w, const TrigBasis& test, const TrigBasis& trial, double a,
                  double b) {
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

}  // namespace

double TrigBasis::value(Index j, double tau) const {
  return sine(j) ? std::sin(harmonic(j) * tau) : std::cos(harmonic(j) * tau);
}

double TrigBasis::slope(Index j, double tau) const {
  const int h = harmonic(j);
  return sine(j) ? h * std::cos(h * tau) : -h * std::sin(h * tau);
}

Vector series(const Matrix& C, const TrigBasis& b, double tau, bool derivative) {
  Vector u = Vector::Zero(C.rows());
  for (Index k = 0; k < b.size(); ++k)
    u += (derivative ? b.slope(k, tau) : b.value(k, tau)) * C.col(k);
  return u;
}

RegionWeights exact_weights(const ReducedField& field, const Matrix& C, const TrigBasis& trial,
                            const TrigBasis& test) {
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

RegionWeights sampled_weights(const ReducedField& field, const Matrix& C, const TrigBasis& trial,
                              const TrigBasis& test, int samples) {
  RegionWeights w;
  for (int m = 0; m < samples; ++m) {
    const double tau = 2 * M_PI * m / samples;
    GalerkinWeights& x = weights_of(w, field.active_set(series(C, trial, tau)), test, trial);
    for (Index j = 0; j < test.size(); ++j) {
      const double pj = test.value(j, tau) * 2.0 / samples;
      x.phi(j) += pj;
      for (Index k = 0; k < trial.size(); ++k) x.Psi(j, k) += pj * trial.value(k, tau);
    }
  }
  return w;
}

Matrix derivative_matrix(const TrigBasis& b) {
  if (b.cosine_only)
    throw std::logic_error("derivative_matrix: a cosine-only basis has no sines to hold it");
  // d/dtau (a cos h tau + b sin h tau) = h b cos h tau - h a sin h tau.
  Matrix D = Matrix::Zero(b.size(), b.size());
  for (int h = 1; h <= b.H; ++h) {
    const Index c = 2 * h - 1, s = 2 * h;
    D(s, c) = h;
    D(c, s) = -h;
  }
  return D;
}

Matrix second_derivative_matrix(const TrigBasis& b) {
  Vector d(b.size());
  for (Index k = 0; k < b.size(); ++k) d(k) = -std::pow(b.harmonic(k), 2);
  return d.asDiagonal();
}

Matrix galerkin_product(const ReducedField& field, const RegionWeights& w, const Matrix& C,
                        const SeriesOperator& op) {
  const Index tests = w.begin()->second.Psi.rows();
  Matrix P = Matrix::Zero(C.rows(), tests);
  const bool stiff = !op.A_K.isZero(0.0), inertia = !op.A_M.isZero(0.0);
  const Matrix CK = stiff ? Matrix(C * op.A_K) : Matrix(), CM = inertia ? Matrix(C * op.A_M) : Matrix();
  for (const auto& [S, x] : w) {
    const auto r_held = field.region(S);
    const Region& r = *r_held;
    if (stiff) P += r.K * CK * x.Psi.transpose();
    if (inertia) P += r.M * CM * x.Psi.transpose();
  }
  return P;
}

Balance galerkin_residual(const ReducedField& field, const RegionWeights& w, const Matrix& C,
                          const SeriesOperator& op, const Matrix& load) {
  const Index nb = op.A_K.rows();
  const Matrix stiff = galerkin_product(field, w, C, {op.A_K, Matrix::Zero(nb, nb)});
  const Matrix inertia = galerkin_product(field, w, C, {Matrix::Zero(nb, nb), op.A_M});
  Matrix constant = load.size() > 0 ? load : Matrix::Zero(stiff.rows(), stiff.cols());
  for (const auto& [S, x] : w) constant += field.region(S)->f * x.phi.transpose();
  Balance b;
  b.R = stiff + inertia - constant;
  b.scale = std::max({stiff.norm(), inertia.norm(), constant.norm(), periodic_tiny});
  return b;
}

Matrix galerkin_jacobian(const ReducedField& field, const RegionWeights& w,
                         const SeriesOperator& op, double scale) {
  const Index n = field.size(), tests = w.begin()->second.Psi.rows(), trials = op.A_K.rows();
  Matrix J = Matrix::Zero(n * tests, n * trials);
  for (const auto& [S, x] : w) {
    const auto r_held = field.region(S);
    const Region& r = *r_held;
    // Column block k of R(:, j): (A_K Psi^T)(k, j) K_S + (A_M Psi^T)(k, j) M_S.
    const Matrix GK = op.A_K * x.Psi.transpose() / scale, GM = op.A_M * x.Psi.transpose() / scale;
    for (Index k = 0; k < trials; ++k)
      for (Index j = 0; j < tests; ++j) {
        if (GK(k, j) != 0) J.block(j * n, k * n, n, n) += GK(k, j) * r.K;
        if (GM(k, j) != 0) J.block(j * n, k * n, n, n) += GM(k, j) * r.M;
      }
  }
  return J;
}

Matrix fourier_coefficients(const ExactFlow& flow, const Vector& u0, const Vector& v0, double T,
                            const TrigBasis& b) {
  const Index n = u0.size();
  Matrix C = Matrix::Zero(n, b.size());
  const int samples = std::max(64, 8 * (b.H + 1));
  const double span = b.cosine_only ? 0.5 * T : T;
  std::vector<double> times(samples);
  for (int m = 0; m < samples; ++m) times[m] = span * m / samples;
  const auto r = flow.integrate(u0, b.cosine_only ? Vector::Zero(n) : v0, span, false, times);
  // Cosine only: samples 0 .. 2 samples - 1 over [0, 2 pi), the second half
  // mirrored (sample `samples` is the end of the half period).
  const int count = b.cosine_only ? 2 * samples : samples;
  for (int m = 0; m < count; ++m) {
    const int sample = m < samples ? m : 2 * samples - m;
    const Vector u = sample < samples ? Vector(r.samples.col(sample).head(n)) : r.u;
    const double tau = 2 * M_PI * m / count;
    for (Index k = 0; k < b.size(); ++k)
      C.col(k) += (k == 0 ? 1.0 : 2.0) / count * b.value(k, tau) * u;
  }
  return C;
}

}  // namespace nbm
