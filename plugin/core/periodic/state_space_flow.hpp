// The exact flow on one region when the damping does not decouple on the
// region's modes: an assembled damping matrix C (method.md §9, "Damping that
// is not modal"). In the scaled modal coordinates z = (Omega q, q') of the
// region (q = Phi^T M_S u, Omega = diag(omega_j) > 0) the reduced equations
// M_S u'' + C_S u' + K_S u = f_S + F_h(t) are the first-order system
//
//     z' = A z + (0, p + P(t)),   A = [ 0  Omega ; -Omega  -Phi^T C_S Phi ],
//
// whose undamped part is skew-symmetric: the eigenvectors of A are close to
// orthonormal for light damping, so the complex eigendecomposition
// A = V Lambda V^-1 is well conditioned where it matters. The flow is the
// stationary response to p, a steady response per harmonic, and the free
// response V exp(Lambda t) V^-1 z_h(0) of what remains.
#pragma once

#include <complex>
#include <memory>

#include "periodic/exact_flow.hpp"

namespace nbm {

/// The eigendecomposition of a region's first-order system (above), computed
/// once per region and damping. Throws NumericalError if the region has a
/// rigid mode (omega_j = 0: z does not contain q_j), if A has an eigenvalue
/// with a positive real part (C_S not positive semidefinite), or if A is
/// nearly defective (a mode close to critical damping: V is singular).
struct StateSpaceModes {
  Matrix C_modal;             ///< Phi^T C_S Phi
  Vector omega;               ///< sqrt(omega2), > 0
  Eigen::VectorXcd lambda;    ///< eigenvalues of A, Re <= 0
  Eigen::MatrixXcd V, V_inv;  ///< eigenvectors (columns) and their inverse

  StateSpaceModes(const Region& region, const Matrix& C_S);
};

class StateSpaceRegionFlow : public FlowPiece {
 public:
  /// The flow on `region` from (u0, v0) at absolute time t0; `modes` are the
  /// region's StateSpaceModes for the damping of `forcing` plus C_S. Throws
  /// NumericalError if a harmonic of the load is in resonance with an
  /// undamped mode (no periodic particular solution).
  StateSpaceRegionFlow(const Region& region, std::shared_ptr<const StateSpaceModes> modes,
                       const FlowForcing& forcing, const Vector& u0, const Vector& v0,
                       double t0 = 0);
  void state(double t, Vector& u, Vector& v) const override;
  Matrix transition(double t) const override;

  Index rows() const override { return r_.d.size(); }
  Vector value(double t) const override;
  Vector rate(double t) const override;
  Vector curvature(double t) const override;
  /// sum_j |(H Phi V_v)_rj| |lambda_j| |exp(lambda_j t) c_j| plus the bound of
  /// the harmonic part, non-increasing in t because Re lambda_j <= 0.
  Vector curvature_bound(double t) const override;
  Vector magnitude(double span) const override;

 private:
  /// Modal state at local time t (the last evaluation is kept: the switching
  /// search asks value, rate and bound at the same t in a row).
  struct ModalState {
    double t = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXcd e;  ///< exp(lambda_j t) c_j
    Vector q, qd, qdd;
  };
  const ModalState& modal(double t) const;

  const Region& r_;
  std::shared_ptr<const StateSpaceModes> m_;
  Vector stationary_;        ///< q_s = p / omega^2
  std::vector<double> Omega_;
  Eigen::MatrixXcd Q_;       ///< n x harmonics: steady modal amplitudes at local time 0
  Eigen::VectorXcd c_;       ///< V^-1 z_h(0)
  Matrix G_, G_abs_;         ///< H Phi and |H Phi|
  Matrix GV_abs_;            ///< |H Phi V_v| (rows: switching functions)
  Matrix GVq_abs_;           ///< |H Phi Omega^-1 V_u|
  Vector forced_bound_;      ///< per row: sum_k Omega_k^2 |(G Q_k)_r|
  Matrix PhiTM_;
  mutable ModalState last_;
};

}  // namespace nbm
