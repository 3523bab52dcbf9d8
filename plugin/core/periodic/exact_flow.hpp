// The exact flow of the reduced NBM equations (reduced_field.hpp), with
// damping and a harmonic load (method.md §6, §9): modal solution on each
// region (Rayleigh damping; state_space_flow.hpp for an assembled damping
// matrix), switching times by rigorous root finding on the switching
// functions (switching.hpp), and the state-transition (monodromy) matrix
// with saltation terms where the acceleration jumps.
#pragma once

#include <complex>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "contact/damping.hpp"
#include "periodic/harmonic_load.hpp"
#include "periodic/reduced_field.hpp"
#include "periodic/switching.hpp"

namespace nbm {

/// What the region flows need of the excitation: the Rayleigh coefficients
/// (C_S = a_M M_S + b_K K_S on every region, method.md §9), the harmonics of
/// the load on the interior dofs, F_O(t) - F0_O = sum_k Re(load_k
/// exp(i Omega_k t)) with load_k = cos_k - i sin_k, and likewise those of the
/// load on the contact dofs and of the gaps (one entry per contact; empty
/// vectors if the contacts do not move, method.md §8).
struct FlowForcing {
  double a_M = 0, b_K = 0;
  /// The interior block C_OO of an assembled damping matrix (dense n x n; it
  /// vanishes on the contact dofs, so C_S = a_M M_S + b_K K_S + C_OO on every
  /// region); null without one.
  std::shared_ptr<const Matrix> C_interior;
  std::vector<double> Omega;
  std::vector<Eigen::VectorXcd> load, contact_load, gap;

  /// Whether the gaps or the contact loads vary in time.
  bool moves_contacts() const;
  /// The complex amplitude of harmonic k of the interior load on a region:
  /// P^T (F_k - K e_k - i Omega_k C e_k + Omega_k^2 M e_k) with
  /// e_k = E_g gap_k + E_F contact_load_k (method.md §9, "Moving obstacles").
  Eigen::VectorXcd region_load(const Region& region, std::size_t k) const;
  /// The complex amplitude of harmonic k of the region's switching offset d.
  Eigen::VectorXcd region_switching(const Region& region, std::size_t k) const;
  /// The harmonic part of the interior load on a region at time t.
  Vector at(const Region& region, double t) const;
  /// The shift of the gaps and contact loads at time t, or its time
  /// derivative of the given order (1: the rate); empty if the contacts do
  /// not move.
  ContactShift shift(double t, int derivative = 0) const;
};

/// The flow on one region in closed form: the state at local time t, the
/// transition matrix d(u, v)(t) / d(u0, v0) (2n x 2n; the load does not enter
/// it) and the region's switching functions h(t) = H u(t) + d.
class FlowPiece : public SwitchingFunctions {
 public:
  virtual void state(double t, Vector& u, Vector& v) const = 0;
  virtual Matrix transition(double t) const = 0;
};

/// The flow on one region from (u0, v0) at absolute time t0 (local time 0).
/// In the modal coordinates q = Phi^T M_S u of the region every mode obeys
///     q'' + c q' + w^2 q = p + sum_k Re(P_k exp(i Omega_k t)),
/// c = a_M + b_K w^2, solved in closed form: a stationary (or, for a rigid
/// mode, zero-state) response to p, a steady harmonic response
/// P_k / (w^2 - Omega_k^2 + i c Omega_k) per harmonic, and the damped free
/// response (under-, critically or over-damped) of what remains. The
/// region's switching functions h(t) = H u(t) + d + sum_k Re(D_k
/// exp(i Omega_k t)) (D_k from moving gaps and contact loads) are this
/// object's.
class RegionFlow : public FlowPiece {
 public:
  /// Throws NumericalError if an undamped mode is in resonance with a
  /// harmonic of the load (no periodic particular solution).
  RegionFlow(const Region& region, const FlowForcing& forcing, const Vector& u0, const Vector& v0,
             double t0 = 0);
  void state(double t, Vector& u, Vector& v) const override;
  Matrix transition(double t) const override;

  Index rows() const override { return r_.d.size(); }
  Vector value(double t) const override;
  Vector rate(double t) const override;
  Vector curvature(double t) const override;
  /// sum_j |G_j| sqrt(c_j^2 + w_j^2) sqrt(E_j(t)), with E_j = z'^2 + w^2 z^2
  /// the energy of mode j's free response z (non-increasing: E' = -2 c z'^2),
  /// plus the bounds of the forced and rigid-mode parts and Omega_k^2 |D_k|
  /// of the moving contacts; G = H Phi.
  Vector curvature_bound(double t) const override;
  Vector magnitude(double span) const override;

 private:
  /// Modal state at local time t: free response (z, z') and full
  /// (q, q', q''). The switching search asks value, rate and bound at the
  /// same t in a row: the last evaluation is kept.
  struct ModalState {
    double t = std::numeric_limits<double>::quiet_NaN();
    Vector z, zd, q, qd, qdd;
  };
  const ModalState& modal(double t) const;
  /// The moving contacts' part of d(t) at local time t, or its first or
  /// second derivative.
  Vector offset(double t, int derivative) const;
  void free_response(double t, Vector& z, Vector& zd) const;

  const Region& r_;
  double t0_;
  Vector c_;                 ///< modal damping a_M + b_K w^2
  Vector stationary_;        ///< p / w^2 (0 on rigid modes)
  Vector rigid_load_;        ///< p on rigid modes (0 elsewhere)
  Vector z0_, zd0_;          ///< initial state of the free response
  std::vector<double> Omega_;
  Eigen::MatrixXcd Q_;       ///< n x harmonics: steady modal amplitudes at local time 0
  Eigen::MatrixXcd D_;       ///< rows x harmonics: switching offsets at local time 0 (or empty)
  Matrix G_, G_abs_;         ///< H Phi and |H Phi|
  /// Per row: sum_k Omega_k^2 (|(G Q_k)_r| + |D_rk|) + sum_rigid |G_rj p_j|.
  Vector forced_bound_;
  Matrix PhiTM_;
  mutable ModalState last_;
};

struct StateSpaceModes;  // state_space_flow.hpp

struct SwitchEvent {
  double t;          ///< time of the switch
  Index contact;     ///< the contact whose state changed (the first, if several)
  ActiveSet after;   ///< the active set from then on
};

struct FlowResult {
  Vector u, v;                       ///< the state at the end
  Vector a;                          ///< u'' at the end
  ActiveSet active;                  ///< the active set at the end
  Matrix monodromy;                  ///< d(u, v)(T)/d(u, v)(0), if requested
  std::vector<SwitchEvent> switches;
  /// (u, v) at the requested sample times, columns of 2n-vectors.
  Matrix samples;
};

class ExactFlow {
 public:
  /// The undamped flow under the field's constant load.
  explicit ExactFlow(const ReducedField& field) : field_(field) {}
  /// With damping and a harmonic excitation (harmonic_load.hpp: load and
  /// gaps). Throws InputError on negative or non-finite Rayleigh
  /// coefficients, on an assembled damping matrix of the wrong size,
  /// non-finite, or non-zero on a contact dof (its rows and columns there
  /// would make the reactions depend on the velocities), on harmonics of the
  /// wrong size or non-finite, on omega <= 0 with harmonics, and on moving
  /// gaps or contact loads together with an assembled matrix. With an
  /// assembled matrix the region flows are state_space_flow.hpp's.
  ExactFlow(const ReducedField& field, const Damping& damping, const HarmonicLoad& load);
  /// The same field and damping under another harmonic load (continuation
  /// in the excitation): shares the eigendecompositions already computed.
  ExactFlow with_load(const HarmonicLoad& load) const;
  /// Flows (u0, v0) from the absolute time t0 over [t0, t0 + T] (sample and
  /// switch times are counted from t0). With `sensitivity`, also the
  /// monodromy matrix. `sample_times` (sorted, in [0, T]) asks for the state
  /// there. Throws NumericalError on more than 100000 switches (Zeno
  /// behaviour).
  FlowResult integrate(const Vector& u0, const Vector& v0, double T, bool sensitivity,
                       const std::vector<double>& sample_times = {}, double t0 = 0) const;
  /// u_O'' at (u_O, v_O) and absolute time t on a given region.
  Vector acceleration(const Region& region, const Vector& u, const Vector& v, double t) const;
  const ReducedField& field() const { return field_; }
  const FlowForcing& forcing() const { return forcing_; }

 private:
  /// The flow on `region` from (u, v) at absolute time t0.
  std::unique_ptr<FlowPiece> piece(const Region& region, const Vector& u, const Vector& v,
                                   double t0) const;

  const ReducedField& field_;
  FlowForcing forcing_;
  /// With an assembled damping matrix: the state-space decompositions of the
  /// regions met so far, shared by copies and by with_load (at most
  /// kMaxCachedRegions, the oldest dropped first).
  struct StateSpaceCache {
    std::map<ActiveSet, std::shared_ptr<const StateSpaceModes>> modes;
    std::vector<ActiveSet> order;
  };
  std::shared_ptr<StateSpaceCache> state_space_;
};

}  // namespace nbm
