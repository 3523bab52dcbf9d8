#include "exact_flow.hpp"

#include <cmath>
#include <string>

#include "errors.hpp"

namespace nbm {
namespace {

constexpr long kMaxSwitches = 100'000;

// cos(w t), sin(w t)/w and (1 - cos(w t))/w^2, continuous down to w = 0.
struct ModalFunctions {
  double c, s, r;
  ModalFunctions(double w2, double t) {
    if (w2 == 0) {
      c = 1, s = t, r = 0.5 * t * t;
      return;
    }
    const double w = std::sqrt(w2), half = std::sin(0.5 * w * t);
    c = std::cos(w * t), s = std::sin(w * t) / w, r = 2 * half * half / w2;
  }
};

}  // namespace

RegionFlow::RegionFlow(const Region& region, const Vector& u0, const Vector& v0) : r_(region) {
  const Matrix PhiTM = r_.modes.transpose() * r_.M;
  q0_ = PhiTM * u0;
  w0_ = PhiTM * v0;
  p_ = r_.modes.transpose() * r_.f;

  // h(t) = d + G q(t), G = H Phi; oscillating modes give the trig terms,
  // rigid ones (w = 0) the quadratic.
  const Matrix G = r_.H * r_.modes;
  const Index n = q0_.size(), rows = G.rows();
  Index terms = 0;
  for (Index k = 0; k < n; ++k) terms += r_.omega2(k) > 0;
  h_.c = r_.d;
  h_.p = Vector::Zero(rows);
  h_.q = Vector::Zero(rows);
  h_.a.resize(rows, terms);
  h_.b.resize(rows, terms);
  h_.nu.resize(terms);
  Index j = 0;
  for (Index k = 0; k < n; ++k) {
    const double w2 = r_.omega2(k);
    if (w2 == 0) {
      h_.c += q0_(k) * G.col(k);
      h_.p += w0_(k) * G.col(k);
      h_.q += (0.5 * p_(k)) * G.col(k);
      continue;
    }
    const double w = std::sqrt(w2), rest = p_(k) / w2;
    h_.c += rest * G.col(k);
    h_.a.col(j) = (q0_(k) - rest) * G.col(k);
    h_.b.col(j) = (w0_(k) / w) * G.col(k);
    h_.nu(j++) = w;
  }
}

void RegionFlow::state(double t, Vector& u, Vector& v) const {
  const Index n = q0_.size();
  Vector q(n), qd(n);
  for (Index k = 0; k < n; ++k) {
    const ModalFunctions m(r_.omega2(k), t);
    q(k) = m.c * q0_(k) + m.s * w0_(k) + m.r * p_(k);
    qd(k) = -r_.omega2(k) * m.s * q0_(k) + m.c * w0_(k) + m.s * p_(k);
  }
  u = r_.modes * q;
  v = r_.modes * qd;
}

Matrix RegionFlow::transition(double t) const {
  const Index n = q0_.size();
  Vector c(n), s(n), ls(n);
  for (Index k = 0; k < n; ++k) {
    const ModalFunctions m(r_.omega2(k), t);
    c(k) = m.c, s(k) = m.s, ls(k) = -r_.omega2(k) * m.s;
  }
  const Matrix PhiTM = r_.modes.transpose() * r_.M;
  Matrix X(2 * n, 2 * n);
  X.topLeftCorner(n, n) = r_.modes * c.asDiagonal() * PhiTM;
  X.topRightCorner(n, n) = r_.modes * s.asDiagonal() * PhiTM;
  X.bottomLeftCorner(n, n) = r_.modes * ls.asDiagonal() * PhiTM;
  X.bottomRightCorner(n, n) = X.topLeftCorner(n, n);
  return X;
}

FlowResult ExactFlow::integrate(const Vector& u0, const Vector& v0, double T, bool sensitivity,
                                const std::vector<double>& sample_times) const {
  const Index n = field_.size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("exact flow: initial state of size " + std::to_string(u0.size()) +
                     ", expected " + std::to_string(n));
  if (!(T >= 0) || !std::isfinite(T)) throw InputError("exact flow: the time span must be >= 0");
  FlowResult out;
  out.u = u0;
  out.v = v0;
  out.active = field_.active_set(u0);
  if (sensitivity) out.monodromy = Matrix::Identity(2 * n, 2 * n);
  out.samples.resize(2 * n, static_cast<Index>(sample_times.size()));
  std::size_t next_sample = 0;

  double t = 0;
  for (long switches = 0;; ++switches) {
    if (switches > kMaxSwitches)
      throw NumericalError("exact flow: more than " + std::to_string(kMaxSwitches) +
                           " switches (Zeno behaviour?)");
    const auto held = field_.region(out.active);
    const Region& region = *held;
    const RegionFlow piece(region, out.u, out.v);
    const auto crossing = first_crossing(piece.switching(), 0, T - t);
    const double tau = crossing ? crossing->t : T - t;
    for (; next_sample < sample_times.size() && sample_times[next_sample] <= t + tau;
         ++next_sample) {
      Vector us, vs;
      piece.state(sample_times[next_sample] - t, us, vs);
      out.samples.col(static_cast<Index>(next_sample)) << us, vs;
    }
    piece.state(tau, out.u, out.v);
    if (sensitivity) out.monodromy = piece.transition(tau) * out.monodromy;
    t += tau;
    if (!crossing) break;

    const ActiveSet next = field_.switched(region, out.u, out.v, crossing->row);
    if (sensitivity) {
      // Saltation (Leine & Nijmeijer): S = I + (f+ - f-) n^T / (n^T f-) with
      // n = (H_j, 0), f = (v, a); only the acceleration jumps.
      const Vector jump = field_.region(next)->acceleration(out.u) - region.acceleration(out.u);
      const double rate = region.H.row(crossing->row).dot(out.v);
      if (jump.norm() > 0 && rate != 0)
        out.monodromy.bottomRows(n) +=
            (jump / rate) * (region.H.row(crossing->row) * out.monodromy.topRows(n));
    }
    out.switches.push_back({t, crossing->row, next});
    out.active = next;
  }
  out.a = field_.region(out.active)->acceleration(out.u);
  return out;
}

}  // namespace nbm
