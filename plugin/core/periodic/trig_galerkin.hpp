// The Galerkin machinery of harmonic balance on the reduced NBM equations
// (method.md §6, §9), shared by the autonomous solver (harmonic_balance.cpp)
// and the forced one (forced_harmonic_balance.cpp). Internal to the core.
//
// A trajectory is a trigonometric series in tau in [0, 2 pi] (tau = omega t
// for an autonomous orbit, tau = (omega / m) t for a forced one),
//     u(tau) = sum_k C_k psi_k(tau),  psi = 1, cos tau, sin tau, cos 2 tau, ...
// (or 1, cos tau, cos 2 tau, ... for series even in tau). On the region of an
// active set S the left-hand side of the reduced equations,
// M_S u'' + C_S u' + K_S u with C_S = a_M M_S + b_K K_S (method.md §9), is a
// series with the coefficients K_S C A_K + M_S C A_M for two fixed matrices
// A_K, A_M on the coefficients (the SeriesOperator): its Galerkin residual
// against psi_j is a sum over the regions of exact weights
//     Psi_S(j, k) = (1/pi) int_S psi_j psi_k,   phi_S(j) = (1/pi) int_S psi_j,
// integrated between the switching times along the series (exact_weights),
// or by sampling the region at every sample (sampled_weights, AFT).
#pragma once

#include <map>

#include "periodic/exact_flow.hpp"
#include "periodic/reduced_field.hpp"

namespace nbm {

/// The trigonometric basis psi_j(tau) of H harmonics.
struct TrigBasis {
  int H;
  bool cosine_only;
  Index size() const { return cosine_only ? H + 1 : 2 * H + 1; }
  int harmonic(Index j) const {
    return cosine_only ? static_cast<int>(j) : static_cast<int>((j + 1) / 2);
  }
  bool sine(Index j) const { return !cosine_only && j > 0 && j % 2 == 0; }
  double value(Index j, double tau) const;
  double slope(Index j, double tau) const;  ///< d psi_j / d tau
  /// Column of the full layout (c0, a1, b1, ...) of basis function j.
  Index full_column(Index j) const { return cosine_only ? (j == 0 ? 0 : 2 * j - 1) : j; }
};

/// Psi_S (test x trial) and phi_S (test) of one region.
struct GalerkinWeights {
  Matrix Psi;
  Vector phi;
};
using RegionWeights = std::map<ActiveSet, GalerkinWeights>;

/// u(tau) (or du/dtau) from the coefficients C (n x b.size()).
Vector series(const Matrix& C, const TrigBasis& b, double tau, bool derivative = false);

/// The weights of the regions the series C visits, integrated exactly
/// between its switching times (roots of the switching functions along the
/// series, switching.hpp). Throws NumericalError beyond 100000 switches.
RegionWeights exact_weights(const ReducedField& field, const Matrix& C, const TrigBasis& trial,
                            const TrigBasis& test);
/// The same by sampling (alternating frequency-time): the region is decided
/// at each of `samples` equidistant tau.
RegionWeights sampled_weights(const ReducedField& field, const Matrix& C, const TrigBasis& trial,
                              const TrigBasis& test, int samples);

/// d/dtau on the coefficients: C * derivative_matrix(b) are the coefficients
/// of du/dtau (a basis with sines only: the derivative of a cosine-only
/// series is not one).
Matrix derivative_matrix(const TrigBasis& b);
/// d^2/dtau^2 on the coefficients: diag(-h^2) (any basis).
Matrix second_derivative_matrix(const TrigBasis& b);

/// M_S u'' + C_S u' + K_S u has the coefficients K_S C A_K + M_S C A_M
/// (trial x trial matrices).
struct SeriesOperator {
  Matrix A_K, A_M;
};

struct Balance {
  Matrix R;      ///< n x test.size(): the Galerkin residual
  double scale;  ///< size of its terms (stiffness, inertia and damping, load)
};

/// sum_S (K_S C A_K + M_S C A_M) Psi_S^T: the projection of the operator's
/// series (n x test.size()), linear in the operator.
Matrix galerkin_product(const ReducedField& field, const RegionWeights& w, const Matrix& C,
                        const SeriesOperator& op);

/// R = sum_S (K_S C A_K + M_S C A_M) Psi_S^T - f_S phi_S^T - load, with
/// `load` the projection of any load beyond the regions' constant f_S on
/// the test basis (n x test.size(), or empty).
Balance galerkin_residual(const ReducedField& field, const RegionWeights& w, const Matrix& C,
                          const SeriesOperator& op, const Matrix& load = Matrix());

/// dR / dC (columns of C stacked) with the weights frozen, divided by
/// `scale`: (n test.size()) x (n trial.size()).
Matrix galerkin_jacobian(const ReducedField& field, const RegionWeights& w,
                         const SeriesOperator& op, double scale);

/// The Fourier coefficients (basis b over tau in [0, 2 pi] <-> t in [0, T])
/// of the flow from (u0, v0): sampled over one period, or for a cosine-only
/// basis over half a period from (u0, 0) and mirrored (an even extension,
/// continuous even when the guess is not periodic).
Matrix fourier_coefficients(const ExactFlow& flow, const Vector& u0, const Vector& v0, double T,
                            const TrigBasis& b);

}  // namespace nbm
