#include "periodic/exact_flow.hpp"

#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "periodic/state_space_flow.hpp"

namespace nbm {
namespace {

constexpr long kMaxSwitches = 100'000;
using Complex = std::complex<double>;

// e^{-alpha t} C(t) and e^{-alpha t} S(t) for q'' + c q' + w2 q = 0, with
// alpha = c / 2 and delta^2 = w2 - alpha^2: C = cos(delta t) and
// S = sin(delta t) / delta (under-damped), C = 1 and S = t (critically
// damped, and the undamped rigid mode), C = cosh(kappa t) and
// S = sinh(kappa t) / kappa with kappa^2 = -delta^2 (over-damped). In every
// case C' = -delta^2 S and S' = C, so the free response is
//     z  = (ec + alpha es) z0 + es z0'
//     z' = -w2 es z0 + (ec - alpha es) z0'
// continuous in delta^2 through critical damping.
struct DampedModal {
  double ec, es;
  DampedModal(double w2, double c, double t) {
    const double alpha = 0.5 * c, d2 = w2 - alpha * alpha;
    if (d2 > 0) {
      const double d = std::sqrt(d2), E = std::exp(-alpha * t);
      ec = E * std::cos(d * t), es = E * std::sin(d * t) / d;
    } else if (d2 == 0) {
      const double E = std::exp(-alpha * t);
      ec = E, es = E * t;
    } else {
      const double kappa = std::sqrt(-d2);
      if (kappa * t < 1) {
        const double E = std::exp(-alpha * t);
        ec = E * std::cosh(kappa * t), es = E * std::sinh(kappa * t) / kappa;
      } else {
        // The two exponentials apart: e^{-alpha t} cosh(kappa t) would overflow.
        const double slow = std::exp((kappa - alpha) * t), fast = std::exp(-(kappa + alpha) * t);
        ec = 0.5 * (slow + fast), es = (slow - fast) / (2 * kappa);
      }
    }
  }
};

// Zero-state response R of R'' + c R' = 1 (a rigid mode under a unit load)
// and R'; R'' = e^{-c t}.
void rigid_response(double c, double t, double& R, double& Rd) {
  const double x = c * t;
  if (x == 0) {
    R = 0.5 * t * t, Rd = t;
    return;
  }
  Rd = -std::expm1(-x) / c;
  // R = t^2 phi(x), phi(x) = (x - 1 + e^{-x}) / x^2 = sum_n (-x)^n / (n + 2)!
  double phi = 0;
  if (x < 0.1) {
    double term = 0.5;
    for (int k = 0; k < 16; ++k) phi += term, term *= -x / (k + 3);
  } else {
    phi = (x + std::expm1(-x)) / (x * x);
  }
  R = t * t * phi;
}

}  // namespace

bool FlowForcing::moves_contacts() const {
  for (std::size_t k = 0; k < Omega.size(); ++k)
    if (!gap[k].isZero(0.0) || !contact_load[k].isZero(0.0)) return true;
  return false;
}

Eigen::VectorXcd FlowForcing::region_load(const Region& r, std::size_t k) const {
  if (gap[k].isZero(0.0) && contact_load[k].isZero(0.0)) return load[k];
  // method.md §9, "Moving obstacles": the offset e_k moves the interior by
  // P^T (K + i W C - W^2 M) [0; e_k], C = a_M M + b_K K; the load on the
  // contact dofs enters by P^T F_k = F_O + A^T F_C.
  const double W = Omega[k];
  const Eigen::VectorXcd e =
      r.E_g.cast<Complex>() * gap[k] + r.E_F.cast<Complex>() * contact_load[k];
  Eigen::VectorXcd f = load[k] + r.A.transpose().cast<Complex>() * contact_load[k] -
                       Complex(1, W * b_K) * (r.B_K.cast<Complex>() * e);
  if (r.B_M.size() > 0) f += Complex(W * W, -W * a_M) * (r.B_M.cast<Complex>() * e);
  return f;
}

Eigen::VectorXcd FlowForcing::region_switching(const Region& r, std::size_t k) const {
  return r.D_g.cast<Complex>() * gap[k] + r.D_F.cast<Complex>() * contact_load[k];
}

Vector FlowForcing::at(const Region& r, double t) const {
  Vector f = Vector::Zero(r.f.size());
  for (std::size_t k = 0; k < load.size(); ++k)
    f += (region_load(r, k) * std::exp(Complex(0, Omega[k] * t))).real();
  return f;
}

ContactShift FlowForcing::shift(double t, int derivative) const {
  ContactShift s;
  if (!moves_contacts()) return s;
  s.gap = Vector::Zero(gap.front().size());
  s.load = Vector::Zero(contact_load.front().size());
  for (std::size_t k = 0; k < Omega.size(); ++k) {
    Complex phase = std::exp(Complex(0, Omega[k] * t));
    for (int d = 0; d < derivative; ++d) phase *= Complex(0, Omega[k]);
    s.gap += (gap[k] * phase).real();
    s.load += (contact_load[k] * phase).real();
  }
  return s;
}

RegionFlow::RegionFlow(const Region& region, const FlowForcing& forcing, const Vector& u0,
                       const Vector& v0, double t0)
    : r_(region), t0_(t0), Omega_(forcing.Omega) {
  const Index n = u0.size(), harmonics = static_cast<Index>(Omega_.size());
  PhiTM_ = r_.modes.transpose() * r_.M;
  const Vector q0 = PhiTM_ * u0, qd0 = PhiTM_ * v0;
  const Vector p = r_.modes.transpose() * r_.f;
  c_ = (forcing.a_M + forcing.b_K * r_.omega2.array()).matrix();
  stationary_ = Vector::Zero(n);
  rigid_load_ = Vector::Zero(n);
  for (Index j = 0; j < n; ++j) {
    if (r_.omega2(j) > 0)
      stationary_(j) = p(j) / r_.omega2(j);
    else
      rigid_load_(j) = p(j);
  }

  // Steady response to each harmonic (method.md §9), as amplitudes at local
  // time 0: Q_jk = P_jk exp(i Omega_k t0) / (w_j^2 - Omega_k^2 + i c_j Omega_k).
  const Eigen::MatrixXcd PhiT = r_.modes.transpose().cast<Complex>();
  Q_.resize(n, harmonics);
  z0_ = q0 - stationary_;
  zd0_ = qd0;
  for (Index k = 0; k < harmonics; ++k) {
    const double W = Omega_[k];
    const Eigen::VectorXcd P = PhiT * forcing.region_load(r_, static_cast<std::size_t>(k));
    const Complex phase = std::exp(Complex(0, W * t0));
    for (Index j = 0; j < n; ++j) {
      const Complex denominator(r_.omega2(j) - W * W, c_(j) * W);
      if (std::abs(denominator) <= 1e-14 * std::max(r_.omega2(j), W * W) && P(j) != 0.0)
        throw NumericalError("exact flow: undamped mode " + std::to_string(j) +
                             " of the region is in resonance with harmonic " +
                             std::to_string(k + 1) + " of the load (no periodic response)");
      Q_(j, k) = std::abs(denominator) == 0 ? Complex(0) : P(j) * phase / denominator;
    }
    z0_ -= Q_.col(k).real();
    zd0_ += W * Q_.col(k).imag();  // minus Re(i W Q)
  }

  G_ = r_.H * r_.modes;
  G_abs_ = G_.cwiseAbs();
  forced_bound_ = G_abs_ * rigid_load_.cwiseAbs();
  const Eigen::MatrixXcd Gc = G_.cast<Complex>();
  for (Index k = 0; k < harmonics; ++k)
    forced_bound_ += (Omega_[k] * Omega_[k]) * (Gc * Q_.col(k)).cwiseAbs();
  // Moving contacts: d(t) = d + sum_k Re(D_k exp(i Omega_k t)) (method.md §9).
  if (forcing.moves_contacts()) {
    D_.resize(r_.d.size(), harmonics);
    for (Index k = 0; k < harmonics; ++k) {
      D_.col(k) = forcing.region_switching(r_, static_cast<std::size_t>(k)) *
                  std::exp(Complex(0, Omega_[k] * t0));
      forced_bound_ += (Omega_[k] * Omega_[k]) * D_.col(k).cwiseAbs();
    }
  }
}

Vector RegionFlow::offset(double t, int derivative) const {
  Vector x = Vector::Zero(r_.d.size());
  for (Index k = 0; k < D_.cols(); ++k) {
    const double W = Omega_[k];
    const Eigen::VectorXcd Dt = D_.col(k) * std::exp(Complex(0, W * t));
    if (derivative == 0) x += Dt.real();
    if (derivative == 1) x -= W * Dt.imag();
    if (derivative == 2) x -= (W * W) * Dt.real();
  }
  return x;
}

void RegionFlow::free_response(double t, Vector& z, Vector& zd) const {
  const Index n = z0_.size();
  z.resize(n);
  zd.resize(n);
  for (Index j = 0; j < n; ++j) {
    const double w2 = r_.omega2(j), alpha = 0.5 * c_(j);
    const DampedModal m(w2, c_(j), t);
    z(j) = (m.ec + alpha * m.es) * z0_(j) + m.es * zd0_(j);
    zd(j) = -w2 * m.es * z0_(j) + (m.ec - alpha * m.es) * zd0_(j);
  }
}

const RegionFlow::ModalState& RegionFlow::modal(double t) const {
  if (t == last_.t) return last_;
  ModalState& m = last_;
  m.t = t;
  free_response(t, m.z, m.zd);
  m.q = stationary_ + m.z;
  m.qd = m.zd;
  m.qdd = -(c_.cwiseProduct(m.zd) + r_.omega2.cwiseProduct(m.z));
  for (Index j = 0; j < m.q.size(); ++j) {
    if (r_.omega2(j) > 0 || rigid_load_(j) == 0) continue;
    double R, Rd;
    rigid_response(c_(j), t, R, Rd);
    m.q(j) += rigid_load_(j) * R;
    m.qd(j) += rigid_load_(j) * Rd;
    m.qdd(j) += rigid_load_(j) * std::exp(-c_(j) * t);
  }
  for (Index k = 0; k < Q_.cols(); ++k) {
    const double W = Omega_[k];
    const Eigen::VectorXcd Qt = Q_.col(k) * std::exp(Complex(0, W * t));
    m.q += Qt.real();
    m.qd -= W * Qt.imag();
    m.qdd -= (W * W) * Qt.real();
  }
  return m;
}

void RegionFlow::state(double t, Vector& u, Vector& v) const {
  const ModalState& m = modal(t);
  u = r_.modes * m.q;
  v = r_.modes * m.qd;
}

Vector RegionFlow::value(double t) const {
  Vector h = r_.d + G_ * modal(t).q;
  if (D_.size() > 0) h += offset(t, 0);
  return h;
}

Vector RegionFlow::rate(double t) const {
  Vector h = G_ * modal(t).qd;
  if (D_.size() > 0) h += offset(t, 1);
  return h;
}

Vector RegionFlow::curvature(double t) const {
  Vector h = G_ * modal(t).qdd;
  if (D_.size() > 0) h += offset(t, 2);
  return h;
}

Vector RegionFlow::curvature_bound(double t) const {
  const ModalState& m = modal(t);
  const Vector energy = m.zd.cwiseAbs2() + r_.omega2.cwiseProduct(m.z.cwiseAbs2());
  const Vector per_mode =
      (c_.cwiseAbs2() + r_.omega2).cwiseSqrt().cwiseProduct(energy.cwiseSqrt());
  return forced_bound_ + G_abs_ * per_mode;
}

Vector RegionFlow::magnitude(double span) const {
  const Index n = z0_.size();
  Vector m = stationary_.cwiseAbs() + Q_.cwiseAbs().rowwise().sum();
  for (Index j = 0; j < n; ++j) {
    const double w2 = r_.omega2(j);
    m(j) += w2 > 0 ? std::sqrt((zd0_(j) * zd0_(j) + w2 * z0_(j) * z0_(j)) / w2)
                   : std::abs(z0_(j)) + span * std::abs(zd0_(j)) +
                         0.5 * span * span * std::abs(rigid_load_(j));
  }
  Vector h = r_.d.cwiseAbs() + G_abs_ * m;
  if (D_.size() > 0) h += D_.cwiseAbs().rowwise().sum();
  return h;
}

Matrix RegionFlow::transition(double t) const {
  const Index n = z0_.size();
  Vector uu(n), uv(n), vu(n), vv(n);
  for (Index j = 0; j < n; ++j) {
    const double w2 = r_.omega2(j), alpha = 0.5 * c_(j);
    const DampedModal m(w2, c_(j), t);
    uu(j) = m.ec + alpha * m.es, uv(j) = m.es, vu(j) = -w2 * m.es, vv(j) = m.ec - alpha * m.es;
  }
  Matrix X(2 * n, 2 * n);
  X.topLeftCorner(n, n) = r_.modes * uu.asDiagonal() * PhiTM_;
  X.topRightCorner(n, n) = r_.modes * uv.asDiagonal() * PhiTM_;
  X.bottomLeftCorner(n, n) = r_.modes * vu.asDiagonal() * PhiTM_;
  X.bottomRightCorner(n, n) = r_.modes * vv.asDiagonal() * PhiTM_;
  return X;
}

ExactFlow::ExactFlow(const ReducedField& field, const Damping& damping, const HarmonicLoad& load)
    : field_(field) {
  if (!(damping.a_M >= 0) || !(damping.b_K >= 0) || !std::isfinite(damping.a_M) ||
      !std::isfinite(damping.b_K))
    throw InputError("exact flow: the Rayleigh coefficients a_M, b_K must be finite and >= 0");
  forcing_.a_M = damping.a_M;
  forcing_.b_K = damping.b_K;
  const Index N = field.n_internal();
  if (damping.has_matrix()) {
    const SparseMatrix& C = damping.C_user;
    if (C.rows() != N || C.cols() != N)
      throw InputError("exact flow: the damping matrix is " + std::to_string(C.rows()) + "x" +
                       std::to_string(C.cols()) + ", expected " + std::to_string(N) + "x" +
                       std::to_string(N) + " (internal coordinates)");
    const Matrix dense(C);
    if (!dense.allFinite()) throw InputError("exact flow: the damping matrix has non-finite entries");
    const double round_off = 1e-14 * dense.cwiseAbs().maxCoeff();
    for (Index c : field.contact())
      if (dense.row(c).cwiseAbs().maxCoeff() > round_off ||
          dense.col(c).cwiseAbs().maxCoeff() > round_off)
        throw InputError("exact flow: the damping matrix couples contact dof " +
                         std::to_string(c) +
                         "; it must vanish on the contact dofs (their reactions would depend "
                         "on the velocities, method.md §9)");
    // A zero matrix adds nothing: the modal flow stays.
    if (dense.cwiseAbs().maxCoeff() > 0) {
      forcing_.C_interior =
          std::make_shared<const Matrix>(dense(field.interior(), field.interior()));
      state_space_ = std::make_shared<StateSpaceCache>();
    }
  }
  const int harmonics = load.harmonics();
  if (harmonics > 0 && (!(load.omega > 0) || !std::isfinite(load.omega)))
    throw InputError("exact flow: the excitation frequency omega must be finite and > 0");
  const Index nc = field.n_contact();
  // Harmonic k of a list (zero if the list is shorter), checked: `size`
  // entries, finite.
  auto harmonic = [&](const std::vector<Vector>& list, const char* name, int k,
                      Index size) -> Vector {
    if (static_cast<std::size_t>(k) >= list.size()) return Vector::Zero(size);
    const Vector& x = list[k];
    const std::string which =
        std::string("exact flow: ") + name + "[" + std::to_string(k) + "]";
    if (x.size() != size)
      throw InputError(which + " has " + std::to_string(x.size()) + " entries, expected " +
                       std::to_string(size));
    if (!x.allFinite()) throw InputError(which + " has non-finite entries");
    return x;
  };
  auto amplitude = [](const Vector& c, const Vector& s) -> Eigen::VectorXcd {
    return c.cast<Complex>() - Complex(0, 1) * s.cast<Complex>();
  };
  for (int k = 0; k < harmonics; ++k) {
    const Vector c = harmonic(load.cos, "load harmonic cos", k, N),
                 s = harmonic(load.sin, "load harmonic sin", k, N);
    const Vector gc = harmonic(load.gap_cos, "gap harmonic cos", k, nc),
                 gs = harmonic(load.gap_sin, "gap harmonic sin", k, nc);
    forcing_.Omega.push_back((k + 1) * load.omega);
    forcing_.load.push_back(amplitude(c(field.interior()), s(field.interior())));
    forcing_.contact_load.push_back(amplitude(c(field.contact()), s(field.contact())));
    forcing_.gap.push_back(amplitude(gc, gs));
  }
  if (forcing_.C_interior && forcing_.moves_contacts())
    throw InputError("exact flow: moving gaps or loads on the contact dofs with an assembled "
                     "damping matrix are not supported (the state-space flow has no moving "
                     "switching offsets); use Rayleigh damping");
}

ExactFlow ExactFlow::with_load(const HarmonicLoad& load) const {
  Damping rayleigh;
  rayleigh.a_M = forcing_.a_M, rayleigh.b_K = forcing_.b_K;
  ExactFlow flow(field_, rayleigh, load);
  flow.forcing_.C_interior = forcing_.C_interior;
  flow.state_space_ = state_space_;
  return flow;
}

std::unique_ptr<FlowPiece> ExactFlow::piece(const Region& region, const Vector& u,
                                            const Vector& v, double t0) const {
  if (!forcing_.C_interior) return std::make_unique<RegionFlow>(region, forcing_, u, v, t0);
  StateSpaceCache& cache = *state_space_;
  std::shared_ptr<const StateSpaceModes> modes;
  const auto found = cache.modes.find(region.active);
  if (found != cache.modes.end()) {
    modes = found->second;
  } else {
    const Matrix C_S =
        forcing_.a_M * region.M + forcing_.b_K * region.K + *forcing_.C_interior;
    modes = std::make_shared<const StateSpaceModes>(region, C_S);
    // A few regions per orbit: a small FIFO bounds the dense 2n x 2n factors held.
    constexpr std::size_t kMaxCachedRegions = 8;
    if (cache.order.size() >= kMaxCachedRegions) {
      cache.modes.erase(cache.order.front());
      cache.order.erase(cache.order.begin());
    }
    cache.modes.emplace(region.active, modes);
    cache.order.push_back(region.active);
  }
  return std::make_unique<StateSpaceRegionFlow>(region, std::move(modes), forcing_, u, v, t0);
}

Vector ExactFlow::acceleration(const Region& region, const Vector& u, const Vector& v,
                               double t) const {
  // M_S u'' = f_S + F_h(t) - K_S u - (a_M M_S + b_K K_S + C_OO) u'.
  Vector rhs = region.f - region.K * (u + forcing_.b_K * v);
  if (forcing_.C_interior) rhs -= *forcing_.C_interior * v;
  if (!forcing_.load.empty()) rhs += forcing_.at(region, t);
  return region.mass.solve(rhs) - forcing_.a_M * v;
}

FlowResult ExactFlow::integrate(const Vector& u0, const Vector& v0, double T, bool sensitivity,
                                const std::vector<double>& sample_times, double t0) const {
  const Index n = field_.size();
  if (u0.size() != n || v0.size() != n)
    throw InputError("exact flow: initial state of size " + std::to_string(u0.size()) +
                     ", expected " + std::to_string(n));
  if (!(T >= 0) || !std::isfinite(T)) throw InputError("exact flow: the time span must be >= 0");
  if (!std::isfinite(t0)) throw InputError("exact flow: the start time must be finite");
  for (std::size_t k = 0; k < sample_times.size(); ++k)
    if (!(sample_times[k] >= (k > 0 ? sample_times[k - 1] : 0.0)) || !(sample_times[k] <= T))
      throw InputError("exact flow: sample times must be sorted within [0, T]");
  FlowResult out;
  out.u = u0;
  out.v = v0;
  out.active = field_.active_set(u0, forcing_.shift(t0));
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
    const std::unique_ptr<FlowPiece> flow = piece(region, out.u, out.v, t0 + t);
    const FlowPiece& piece = *flow;
    const auto crossing = first_crossing(piece, 0, T - t);
    const double tau = crossing ? crossing->t : T - t;
    // The last piece takes every remaining sample: they lie within T, and
    // t + tau, a sum of the pieces' durations, may end an ulp short of a
    // sample at T (a sample left unwritten is uninitialised memory).
    for (; next_sample < sample_times.size() && (sample_times[next_sample] <= t + tau || !crossing);
         ++next_sample) {
      Vector us, vs;
      piece.state(std::min(sample_times[next_sample] - t, tau), us, vs);
      out.samples.col(static_cast<Index>(next_sample)) << us, vs;
    }
    piece.state(tau, out.u, out.v);
    if (sensitivity) out.monodromy = piece.transition(tau) * out.monodromy;
    t += tau;
    if (!crossing) break;

    const ActiveSet next = field_.switched(region, out.u, out.v, crossing->row,
                                           forcing_.shift(t0 + t), forcing_.shift(t0 + t, 1));
    if (sensitivity) {
      // Saltation (Leine & Nijmeijer): S = I + (f+ - f-) n^T / (n^T f- + h_t)
      // with n = (H_j, 0), f = (v, a), h_t = d_j'(t) of moving contacts; only
      // the acceleration jumps (with the mass of the contact dofs, a
      // stiffness-proportional damping or moving contacts, method.md §9).
      const Vector jump = acceleration(*field_.region(next), out.u, out.v, t0 + t) -
                          acceleration(region, out.u, out.v, t0 + t);
      const double rate = piece.rate(tau)(crossing->row);
      if (jump.norm() > 0 && rate != 0)
        out.monodromy.bottomRows(n) +=
            (jump / rate) * (region.H.row(crossing->row) * out.monodromy.topRows(n));
    }
    out.switches.push_back({t, crossing->row, next});
    out.active = next;
  }
  out.a = acceleration(*field_.region(out.active), out.u, out.v, t0 + T);
  return out;
}

}  // namespace nbm
