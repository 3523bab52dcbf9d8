#include "periodic/state_space_flow.hpp"

#include <cmath>
#include <string>

#include <Eigen/LU>

#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"

namespace nbm {
namespace {

using Complex = std::complex<double>;

// Below this reciprocal condition number the eigenvectors of A do not form a
// usable basis: A is (nearly) defective, as at exactly critical damping, where
// the computed eigenvalues split by sqrt(eps) and V amplifies round-off by
// 1 / rcond (1e-6: at most 1e6 eps = 2e-10 relative error in the flow).
constexpr double kMinEigenvectorRcond = 1e-6;

}  // namespace

StateSpaceModes::StateSpaceModes(const Region& region, const Matrix& C_S) {
  const Index n = region.omega2.size();
  const double largest = n > 0 ? region.omega2.maxCoeff() : 0.0;
  for (Index j = 0; j < n; ++j)
    if (!(region.omega2(j) > 1e-12 * largest))
      throw NumericalError("exact flow with a damping matrix: mode " + std::to_string(j) +
                           " of the region is a rigid mode (omega^2 = " +
                           std::to_string(region.omega2(j)) +
                           "); the state-space flow needs every mode restrained");
  omega = region.omega2.cwiseSqrt();
  C_modal = region.modes.transpose() * C_S * region.modes;
  Matrix A = Matrix::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = omega.asDiagonal();
  A.bottomLeftCorner(n, n) = -omega.asDiagonal().toDenseMatrix();
  A.bottomRightCorner(n, n) = -C_modal;
  const GeneralEigen eig = general_eigen(A, true);
  if (!eig.ok)
    throw NumericalError("exact flow with a damping matrix: the eigenvalue solver of the "
                         "region's first-order system failed");
  lambda = eig.values;
  V = eig.vectors;
  const double scale = lambda.cwiseAbs().maxCoeff();
  if (lambda.real().maxCoeff() > 1e-10 * scale)
    throw NumericalError("exact flow with a damping matrix: the region's motion has a growing "
                         "mode (eigenvalue with real part " +
                         std::to_string(lambda.real().maxCoeff()) +
                         "); the damping matrix must be positive semidefinite");
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(V);
  if (!(lu.rcond() > kMinEigenvectorRcond))
    throw NumericalError("exact flow with a damping matrix: the region's first-order system is "
                         "nearly defective (a mode close to critical damping; eigenvector "
                         "condition " + std::to_string(1 / lu.rcond()) + ")");
  V_inv = lu.inverse();
}

StateSpaceRegionFlow::StateSpaceRegionFlow(const Region& region,
                                           std::shared_ptr<const StateSpaceModes> modes,
                                           const FlowForcing& forcing, const Vector& u0,
                                           const Vector& v0, double t0)
    : r_(region), m_(std::move(modes)), Omega_(forcing.Omega) {
  const Index n = u0.size(), harmonics = static_cast<Index>(Omega_.size());
  const Vector& w = m_->omega;
  PhiTM_ = r_.modes.transpose() * r_.M;
  const Vector q0 = PhiTM_ * u0, qd0 = PhiTM_ * v0;
  stationary_ = (r_.modes.transpose() * r_.f).cwiseQuotient(r_.omega2);

  // Steady response to each harmonic (method.md §9): modal amplitudes
  // U_k = (Omega^2 - W^2 + i W Phi^T C_S Phi)^-1 Phi^T F_k, at local time 0.
  Q_.resize(n, harmonics);
  Vector zu = q0 - stationary_, zv = qd0;
  for (Index k = 0; k < harmonics; ++k) {
    const double W = Omega_[k];
    Eigen::MatrixXcd Z = Complex(0, W) * m_->C_modal.cast<Complex>();
    Z.diagonal() += (r_.omega2.array() - W * W).matrix().cast<Complex>();
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Z);
    if (!(lu.rcond() > 1e-14))
      throw NumericalError("exact flow: the region's damped system is singular at harmonic " +
                           std::to_string(k + 1) +
                           " of the load (an undamped mode in resonance: no periodic response)");
    Q_.col(k) = lu.solve(r_.modes.transpose().cast<Complex>() * forcing.load[k]) *
                std::exp(Complex(0, W * t0));
    zu -= Q_.col(k).real();
    zv += W * Q_.col(k).imag();  // minus Re(i W Q)
  }
  Eigen::VectorXcd zh(2 * n);
  zh << w.cwiseProduct(zu).cast<Complex>(), zv.cast<Complex>();
  c_ = m_->V_inv * zh;

  G_ = r_.H * r_.modes;
  G_abs_ = G_.cwiseAbs();
  const Eigen::MatrixXcd Gc = G_.cast<Complex>();
  GV_abs_ = (Gc * m_->V.bottomRows(n)).cwiseAbs();
  GVq_abs_ = (Gc * w.cwiseInverse().cast<Complex>().asDiagonal() * m_->V.topRows(n)).cwiseAbs();
  forced_bound_ = Vector::Zero(r_.d.size());
  for (Index k = 0; k < harmonics; ++k)
    forced_bound_ += (Omega_[k] * Omega_[k]) * (Gc * Q_.col(k)).cwiseAbs();
}

const StateSpaceRegionFlow::ModalState& StateSpaceRegionFlow::modal(double t) const {
  if (t == last_.t) return last_;
  ModalState& s = last_;
  const Index n = stationary_.size();
  s.t = t;
  s.e = ((m_->lambda * t).array().exp() * c_.array()).matrix();
  const Eigen::VectorXcd le = m_->lambda.cwiseProduct(s.e);
  s.q = stationary_ + (m_->V.topRows(n) * s.e).real().cwiseQuotient(m_->omega);
  s.qd = (m_->V.bottomRows(n) * s.e).real();
  s.qdd = (m_->V.bottomRows(n) * le).real();
  for (Index k = 0; k < Q_.cols(); ++k) {
    const double W = Omega_[k];
    const Eigen::VectorXcd Qt = Q_.col(k) * std::exp(Complex(0, W * t));
    s.q += Qt.real();
    s.qd -= W * Qt.imag();
    s.qdd -= (W * W) * Qt.real();
  }
  return s;
}

void StateSpaceRegionFlow::state(double t, Vector& u, Vector& v) const {
  const ModalState& s = modal(t);
  u = r_.modes * s.q;
  v = r_.modes * s.qd;
}

Vector StateSpaceRegionFlow::value(double t) const { return r_.d + G_ * modal(t).q; }

Vector StateSpaceRegionFlow::rate(double t) const { return G_ * modal(t).qd; }

Vector StateSpaceRegionFlow::curvature(double t) const { return G_ * modal(t).qdd; }

Vector StateSpaceRegionFlow::curvature_bound(double t) const {
  const ModalState& s = modal(t);
  return forced_bound_ + GV_abs_ * m_->lambda.cwiseAbs().cwiseProduct(s.e.cwiseAbs());
}

Vector StateSpaceRegionFlow::magnitude(double /*span*/) const {
  // |exp(lambda_j s)| <= 1 for s >= 0: the free response never exceeds |c|.
  Vector m = stationary_.cwiseAbs() + Q_.cwiseAbs().rowwise().sum();
  return r_.d.cwiseAbs() + G_abs_ * m + GVq_abs_ * c_.cwiseAbs();
}

Matrix StateSpaceRegionFlow::transition(double t) const {
  // z(t) = E z(0) with E = Re(V exp(Lambda t) V^-1), z = (Omega q, q'),
  // q = Phi^T M_S u: X = diag(Phi Omega^-1, Phi) E diag(Omega Phi^T M_S, Phi^T M_S).
  const Index n = stationary_.size();
  const Eigen::VectorXcd e = (m_->lambda * t).array().exp().matrix();
  const Matrix E = (m_->V * e.asDiagonal() * m_->V_inv).real();
  const Vector& w = m_->omega;
  const Matrix left_u = r_.modes * w.cwiseInverse().asDiagonal();
  const Matrix right_u = w.asDiagonal() * PhiTM_;
  Matrix X(2 * n, 2 * n);
  X.topLeftCorner(n, n) = left_u * E.topLeftCorner(n, n) * right_u;
  X.topRightCorner(n, n) = left_u * E.topRightCorner(n, n) * PhiTM_;
  X.bottomLeftCorner(n, n) = r_.modes * E.bottomLeftCorner(n, n) * right_u;
  X.bottomRightCorner(n, n) = r_.modes * E.bottomRightCorner(n, n) * PhiTM_;
  return X;
}

}  // namespace nbm
