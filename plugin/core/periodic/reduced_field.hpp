// The reduced NBM equations (method.md §3-4) as a piecewise-linear ODE in the
// interior unknowns u_O, the setting of the periodic-orbit solvers (§6).
//
// On the region of an active set S (closed contacts), u_C = A u_O + e and
//
//     M_S u_O'' + K_S u_O = f_S,   M_S = P^T M P,  K_S = P^T K P,
//                                  f_S = P^T (F - K [0; e]),   P = [I; A],
//
// valid while h_S(u_O) = H_S u_O + d_S >= 0, where h_S collects the gaps
// g_i - u_i of the open contacts and the reactions lambda_i of the closed
// ones. K_S is the Schur complement K_OO - K_OI K_II^-1 K_IO (I: open
// contacts), so the reduced force is the gradient of a C^1 potential and is
// continuous across region boundaries. M_S jumps there unless the boundary
// is massless (M_CC = 0, M_CO = 0), when M_S = M_OO for every S.
//
// Moving obstacles and time-varying loads on the contact dofs (method.md §8)
// shift the gaps and the contact loads by (dg(t), dF_C(t)) (ContactShift):
// e, f_S and d move linearly with them (Region::E_g, E_F, B_K, B_M, D_g, D_F),
// A, H, M_S and K_S do not. The region stays the one of the fixed setup
// (g, F); whoever integrates adds the shift (exact_flow.hpp).
//
// Matrices are dense: the periodic-orbit solvers are meant for models of up
// to a few thousand interior dofs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <Eigen/Cholesky>

#include "base/types.hpp"
#include "contact/contact_problem.hpp"
#include "linalg/active_set.hpp"

namespace nbm {

/// Everything constant on the region of one active set.
struct Region {
  ActiveSet active;
  Matrix A;        ///< u_C = A u_O + e (n_contact x n)
  Vector e;
  Matrix M, K;     ///< M_S, K_S (n x n)
  Vector f;        ///< f_S
  Matrix H;        ///< switching functions h = H u_O + d (n_contact rows):
  Vector d;        ///< gap on open contacts, reaction on closed ones
  Matrix modes;    ///< Phi: K_S Phi = M_S Phi diag(omega2), Phi^T M_S Phi = I
  Vector omega2;   ///< squared circular frequencies, >= 0
  Eigen::LLT<Matrix> mass;  ///< Cholesky factor of M_S
  /// The response of the relation to shifted gaps dg and contact loads dF_C
  /// (method.md §8): e moves by E_g dg + E_F dF_C, d by D_g dg + D_F dF_C
  /// (n_contact x n_contact each), and P^T K [0; de] = B_K de,
  /// P^T M [0; de] = B_M de (n x n_contact; B_M = 0 with the massless
  /// boundary, stored empty then).
  Matrix E_g, E_F, D_g, D_F, B_K, B_M;

  /// u_O'' = M_S^-1 (f_S - K_S u_O).
  Vector acceleration(const Vector& u) const { return mass.solve(f - K * u); }
};

/// Shifts of the gaps and of the loads on the contact dofs from those of the
/// ReducedField (one entry per contact, in the order of contact()); an empty
/// vector is no shift.
struct ContactShift {
  Vector gap, load;
  bool empty() const { return gap.size() == 0 && load.size() == 0; }
};

/// The shift of a region's switching offset d (or, with `offset`, of its
/// relation offset e) under a contact shift.
Vector switching_shift(const Region& region, const ContactShift& shift);
Vector offset_shift(const Region& region, const ContactShift& shift);

class ReducedField {
 public:
  /// Internal coordinates: M, K (N x N, symmetric), F (N), the indices of
  /// the contact dofs (normal displacements, obstacle at u_i <= g_i) and
  /// their gaps. Every other index is an interior dof. Throws InputError on
  /// inconsistent sizes, NumericalError if M_S or K_CC is not definite.
  ReducedField(const Matrix& M, const Matrix& K, const Vector& F, std::vector<Index> contact,
               const Vector& gaps);

  /// The field of a contact problem (its mass, so massless if the boundary
  /// was made massless) under the load F (internal coordinates).
  static ReducedField from(const ContactProblem& problem, const Vector& F);

  Index size() const { return static_cast<Index>(interior_.size()); }  ///< n = dim u_O
  Index n_contact() const { return static_cast<Index>(contact_.size()); }
  Index n_internal() const { return size() + n_contact(); }
  bool massless_boundary() const { return massless_; }
  const std::vector<Index>& interior() const { return interior_; }
  const std::vector<Index>& contact() const { return contact_; }
  const Vector& gaps() const { return g_; }

  /// The region of an active set, built on first use, then cached while the
  /// cached regions fit in region_cache_budget() bytes (their dense
  /// matrices): building a region that does not fit evicts the least
  /// recently used ones (a region larger than the whole budget is not
  /// cached). The returned pointer keeps the region alive after eviction:
  /// hold it, not a reference into it, across further calls.
  std::shared_ptr<const Region> region(const ActiveSet& active) const;
  /// Default budget of the region cache: 256 MiB, e.g. 8 regions of
  /// n = 2000 interior dofs (four dense n x n matrices, 32 MB each).
  static constexpr std::size_t default_region_cache_budget = std::size_t{256} << 20;
  std::size_t region_cache_budget() const { return cache_budget_; }
  /// Sets the budget, evicting least recently used regions down to it.
  void set_region_cache_budget(std::size_t bytes);
  std::size_t region_cache_bytes() const { return cache_bytes_; }  ///< in use
  std::size_t region_cache_size() const { return regions_.size(); }  ///< regions cached
  /// Bytes of a region's dense matrices and vectors (what the budget counts).
  static std::size_t bytes_of(const Region& r);
  /// The active set of the nodal boundary relation (LCP) at u_O, with the
  /// gaps and contact loads shifted by `shift`.
  ActiveSet active_set(const Vector& u, const ContactShift& shift = {}) const;
  /// The active set entered when the switching function `row` of the region
  /// `before` reaches zero at u_O moving along v_O (v_O may be any tangent,
  /// e.g. du/dtau): `row` flips, with every other row at zero and decreasing;
  /// if that set is not entered along v_O (a degenerate switch), the LCP just
  /// past u_O decides. Throws NumericalError if no new set is found. With
  /// moving obstacles, `shift` and its time derivative `shift_rate` at the
  /// switch: the rates of the switching functions are H v + d'(t).
  ActiveSet switched(const Region& before, const Vector& u, const Vector& v, Index row,
                     const ContactShift& shift = {}, const ContactShift& shift_rate = {}) const;
  /// u_O'' at u_O, on the region of the LCP's active set.
  Vector acceleration(const Vector& u) const;

  /// Internal vector (size N) from u_O: u_C = A u_O + e on the region of
  /// u_O's active set (e and the set shifted by `shift`). With `velocity`,
  /// the same for v_O (v_C = A v_O + e', e' from the shift's rate).
  Vector expand(const Vector& u, const ContactShift& shift = {}) const;
  Vector expand_velocity(const Vector& u, const Vector& v, const ContactShift& shift = {},
                         const ContactShift& shift_rate = {}) const;
  /// u_O from an internal vector.
  Vector restrict(const Vector& u_internal) const;

  /// Kinetic, elastic and load-potential energy (method.md §7) of the
  /// internal state (u, v) = (P u_O + e, P v_O + e'), and their sum (the
  /// load potential of the field's constant load F).
  Eigen::Vector4d energies(const Vector& u, const Vector& v, const ContactShift& shift = {},
                           const ContactShift& shift_rate = {}) const;
  /// Complementarity residual of the nodal boundary relation at u_O (gaps
  /// and contact loads shifted by `shift`): max_i |min(gap_i, lambda_i)|
  /// relative to the scales of g and lambda (zero up to round-off by
  /// construction; reported as a check).
  double complementarity_residual(const Vector& u, const ContactShift& shift = {}) const;

 private:
  Matrix M_, K_;
  Matrix K_C_, K_CC_, K_CO_;  // contact rows of K, and their C and O columns
  Vector F_, g_;
  std::vector<Index> interior_, contact_;
  bool massless_ = false;
  struct CachedRegion {
    std::shared_ptr<const Region> region;
    std::size_t bytes = 0;
    std::uint64_t last_use = 0;
  };
  mutable std::map<ActiveSet, CachedRegion> regions_;
  mutable std::size_t cache_budget_ = default_region_cache_budget, cache_bytes_ = 0;
  mutable std::uint64_t cache_clock_ = 0;
  void evict_down_to(std::size_t bytes) const;
};

}  // namespace nbm
