#include "periodic/reduced_field.hpp"

#include <algorithm>
#include <cmath>
#include <string>


#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "linalg/lcp.hpp"

namespace nbm {
namespace {

// Switching functions within this fraction of their scale count as zero.
constexpr double kSwitchZeroTolerance = 1e-11;

std::vector<Index> select(const std::vector<Index>& from, const ActiveSet& active, bool closed) {
  std::vector<Index> out;
  for (std::size_t k = 0; k < from.size(); ++k)
    if (active[k] == closed) out.push_back(static_cast<Index>(k));
  return out;
}

std::vector<Index> at(const std::vector<Index>& indices, const std::vector<Index>& positions) {
  std::vector<Index> out;
  out.reserve(positions.size());
  for (Index p : positions) out.push_back(indices[p]);
  return out;
}

// A shift's part, or zeros (an empty vector is no shift).
Vector part(const Vector& x, Index n) {
  if (x.size() == 0) return Vector::Zero(n);
  return x;
}

}  // namespace

Vector switching_shift(const Region& r, const ContactShift& s) {
  const Index nc = r.d.size();
  if (s.empty()) return Vector::Zero(nc);
  return r.D_g * part(s.gap, nc) + r.D_F * part(s.load, nc);
}

Vector offset_shift(const Region& r, const ContactShift& s) {
  const Index nc = r.e.size();
  if (s.empty()) return Vector::Zero(nc);
  return r.E_g * part(s.gap, nc) + r.E_F * part(s.load, nc);
}

ReducedField::ReducedField(const Matrix& M, const Matrix& K, const Vector& F,
                           std::vector<Index> contact, const Vector& gaps)
    : M_(M), K_(K), F_(F), g_(gaps), contact_(std::move(contact)) {
  const Index N = M.rows();
  if (M.cols() != N || K.rows() != N || K.cols() != N || F.size() != N)
    throw InputError("reduced field: M, K and F must have the same size");
  if (g_.size() != static_cast<Index>(contact_.size()))
    throw InputError("reduced field: one gap per contact dof expected");
  if (!M.allFinite() || !K.allFinite() || !F.allFinite() || !g_.allFinite())
    throw InputError("reduced field: non-finite entries in M, K, F or the gaps");
  std::vector<char> is_contact(N, 0);
  for (Index c : contact_) {
    if (c < 0 || c >= N || is_contact[c])
      throw InputError("reduced field: contact dof " + std::to_string(c) +
                       " out of range or repeated");
    is_contact[c] = 1;
  }
  for (Index i = 0; i < N; ++i)
    if (!is_contact[i]) interior_.push_back(i);
  if (interior_.empty()) throw InputError("reduced field: no interior dof");
  // Cached: active_set and complementarity_residual run once per orbit sample.
  K_C_ = K_(contact_, Eigen::all);
  K_CC_ = K_(contact_, contact_);
  K_CO_ = K_(contact_, interior_);
  if (Eigen::LLT<Matrix>(K_CC_).info() != Eigen::Success)
    throw NumericalError("reduced field: K_CC is not positive definite");
  massless_ = M_(contact_, Eigen::all).isZero(0.0);
}

ReducedField ReducedField::from(const ContactProblem& problem, const Vector& F) {
  return ReducedField(Matrix(problem.M()), Matrix(problem.K()), F, problem.contact_index(),
                      problem.gaps());
}

std::size_t ReducedField::bytes_of(const Region& r) {
  const Index doubles = r.A.size() + r.e.size() + r.M.size() + r.K.size() + r.f.size() +
                        r.H.size() + r.d.size() + r.modes.size() + r.omega2.size() +
                        r.mass.matrixLLT().size() + r.E_g.size() + r.E_F.size() +
                        r.D_g.size() + r.D_F.size() + r.B_K.size() + r.B_M.size();
  return sizeof(Region) + sizeof(double) * static_cast<std::size_t>(doubles);
}

void ReducedField::evict_down_to(std::size_t bytes) const {
  while (cache_bytes_ > bytes && !regions_.empty()) {
    auto oldest = regions_.begin();
    for (auto it = regions_.begin(); it != regions_.end(); ++it)
      if (it->second.last_use < oldest->second.last_use) oldest = it;
    cache_bytes_ -= oldest->second.bytes;
    regions_.erase(oldest);
  }
}

void ReducedField::set_region_cache_budget(std::size_t bytes) {
  cache_budget_ = bytes;
  evict_down_to(bytes);
}

std::shared_ptr<const Region> ReducedField::region(const ActiveSet& active) const {
  auto it = regions_.find(active);
  if (it != regions_.end()) {
    it->second.last_use = ++cache_clock_;
    return it->second.region;
  }
  if (active.size() != contact_.size())
    throw InputError("reduced field: active set of the wrong size");

  auto r = std::make_shared<Region>();
  r->active = active;
  const Index n = size(), nc = n_contact();
  const auto open = select(contact_, active, false), closed = select(contact_, active, true);
  const auto I = at(contact_, open), Act = at(contact_, closed);
  const auto& O = interior_;

  // u_C = A u_O + e (method.md §3): closed contacts sit on the obstacle, open
  // ones carry no reaction. e is linear in the gaps and the contact loads,
  // e = E_g g + E_F F_C, which is also how it follows their shifts (§8).
  r->A = Matrix::Zero(nc, n);
  r->E_g = Matrix::Zero(nc, nc);
  r->E_F = Matrix::Zero(nc, nc);
  for (Index k : closed) r->E_g(k, k) = 1;
  if (!open.empty()) {
    Eigen::LLT<Matrix> KII(K_(I, I));
    const Matrix AI = -KII.solve(K_(I, O));
    // No closed contact: no columns (Eigen's triangular solve of a 0-column
    // right-hand side binds references into null storage, UBSan).
    const Matrix EgI = Act.empty() ? Matrix(open.size(), 0) : Matrix(-KII.solve(K_(I, Act)));
    const Matrix EFI = KII.solve(Matrix::Identity(open.size(), open.size()));
    for (std::size_t a = 0; a < open.size(); ++a) {
      r->A.row(open[a]) = AI.row(a);
      r->E_g(open[a], closed) = EgI.row(a);
      r->E_F(open[a], open) = EFI.row(a);
    }
  }
  r->e = r->E_g * g_ + r->E_F * F_(contact_);
  // P^T M P, P^T K P and P^T (F - K [0; e]); the open rows of (K P) and of
  // F_C - K_CC e vanish and A is zero on closed rows, hence the short forms.
  const Matrix MOC = M_(O, contact_), KOC = K_(O, contact_);
  r->M = M_(O, O) + MOC * r->A + r->A.transpose() * MOC.transpose() +
         r->A.transpose() * M_(contact_, contact_) * r->A;
  r->M = 0.5 * (r->M + r->M.transpose()).eval();
  r->K = K_(O, O) + KOC * r->A;
  r->K = 0.5 * (r->K + r->K.transpose()).eval();
  r->f = F_(O) - KOC * r->e;
  // The interior forces of an offset de: P^T K [0; de], P^T M [0; de].
  r->B_K = KOC + r->A.transpose() * K_CC_;
  if (!massless_) r->B_M = MOC + r->A.transpose() * M_(contact_, contact_);

  // Switching functions: gap on open contacts, reaction on closed ones.
  const Matrix Klambda = K_CO_ + K_CC_ * r->A;
  const Vector dlambda = F_(contact_) - K_CC_ * r->e;
  const Matrix KE_g = K_CC_ * r->E_g, KE_F = K_CC_ * r->E_F;
  r->H.resize(nc, n);
  r->d.resize(nc);
  r->D_g = Matrix::Zero(nc, nc);
  r->D_F = Matrix::Zero(nc, nc);
  for (Index k = 0; k < nc; ++k) {
    if (active[k]) {
      r->H.row(k) = -Klambda.row(k);
      r->d(k) = dlambda(k);
      r->D_g.row(k) = -KE_g.row(k);
      r->D_F.row(k) = -KE_F.row(k);
      r->D_F(k, k) += 1;
    } else {
      r->H.row(k) = -r->A.row(k);
      r->d(k) = g_(k) - r->e(k);
      r->D_g.row(k) = -r->E_g.row(k);
      r->D_g(k, k) += 1;
      r->D_F.row(k) = -r->E_F.row(k);
    }
  }

  r->mass.compute(r->M);
  if (r->mass.info() != Eigen::Success)
    throw NumericalError("reduced field: the reduced mass matrix is not positive definite");
  const SymmetricEigen eig = generalized_symmetric_eigen(r->K, r->M);
  if (!eig.ok)
    throw NumericalError("reduced field: eigenvalue problem K_S phi = w^2 M_S phi failed");
  r->omega2 = eig.values;
  // Zero is judged against the largest frequency and against K_OO / M_S:
  // when every mode of a region is rigid (a free body, one interior dof),
  // the Schur complement K_S is the round-off of K_OO's cancellation.
  const double top = std::max({r->omega2.cwiseAbs().maxCoeff(),
                               K_(O, O).norm() / std::max(r->M.norm(), 1e-300), 1e-300});
  for (Index k = 0; k < n; ++k) {
    // K_S is positive semi-definite: tiny negative eigenvalues are round-off
    // of rigid modes.
    if (r->omega2(k) < -1e-10 * top)
      throw NumericalError("reduced field: the reduced stiffness is not positive semi-definite");
    if (r->omega2(k) < 1e-13 * top) r->omega2(k) = 0;
  }
  r->modes = eig.vectors;
  // Cache it within the budget, the least recently used regions first out.
  const std::size_t bytes = bytes_of(*r);
  if (bytes > cache_budget_) return r;
  evict_down_to(cache_budget_ - bytes);
  regions_.emplace(active, CachedRegion{r, bytes, ++cache_clock_});
  cache_bytes_ += bytes;
  return r;
}

ActiveSet ReducedField::switched(const Region& before, const Vector& u, const Vector& v,
                                 Index row, const ContactShift& shift,
                                 const ContactShift& shift_rate) const {
  // Flip every contact whose switching function is at zero and decreasing
  // (usually just `row`; several at once on symmetric motions). With moving
  // obstacles h = H u + d(t), h' = H v + d'(t) (method.md §8).
  const Vector h = before.H * u + before.d + switching_shift(before, shift);
  const Vector rate = before.H * v + switching_shift(before, shift_rate);
  const double scale = (before.H.cwiseAbs() * u.cwiseAbs() + before.d.cwiseAbs()).maxCoeff();
  ActiveSet next = before.active;
  next[row] = !next[row];
  for (Index j = 0; j < h.size(); ++j)
    if (j != row && std::abs(h(j)) <= kSwitchZeroTolerance * scale && rate(j) < 0) next[j] = !next[j];
  // The new region must contain u and be entered, not left, along v.
  const auto after_region = region(next);
  const Region& after = *after_region;
  const Vector h2 = after.H * u + after.d + switching_shift(after, shift);
  const Vector rate2 = after.H * v + switching_shift(after, shift_rate);
  const double scale2 = (after.H.cwiseAbs() * u.cwiseAbs() + after.d.cwiseAbs()).maxCoeff();
  bool consistent = true;
  for (Index j = 0; j < h2.size(); ++j)
    if (h2(j) < -kSwitchZeroTolerance * scale2 ||
        (h2(j) <= kSwitchZeroTolerance * scale2 && rate2(j) < 0))
      consistent = false;
  if (consistent) return next;
  // Degenerate switch (several contacts at a common boundary): the LCP just
  // past u along v (a relative displacement of 1e-7), at the time s later,
  // decides.
  const double size = std::max({u.norm(), g_.norm(), 1e-300});
  const double s = 1e-7 * size / std::max(v.norm(), 1e-300);
  ContactShift later;
  if (!shift.empty() || !shift_rate.empty()) {
    const Index nc = n_contact();
    later.gap = part(shift.gap, nc) + s * part(shift_rate.gap, nc);
    later.load = part(shift.load, nc) + s * part(shift_rate.load, nc);
  }
  next = active_set(u + s * v, later);
  if (next == before.active)
    throw NumericalError("periodic orbits: no consistent active set after a contact switch");
  return next;
}

ActiveSet ReducedField::active_set(const Vector& u, const ContactShift& shift) const {
  // lambda = F_C - K_CO u_O - K_CC u_C with z = g - u_C: lambda = q + K_CC z.
  const Index nc = n_contact();
  Vector q = F_(contact_) - K_CO_ * u - K_CC_ * g_;
  if (!shift.empty()) q += part(shift.load, nc) - K_CC_ * part(shift.gap, nc);
  return LcpSolver::solve(K_CC_, q).active;
}

Vector ReducedField::acceleration(const Vector& u) const {
  return region(active_set(u))->acceleration(u);
}

Vector ReducedField::expand(const Vector& u, const ContactShift& shift) const {
  const auto r_held = region(active_set(u, shift));
  const Region& r = *r_held;
  Vector x(n_internal());
  x(interior_) = u;
  x(contact_) = r.A * u + r.e + offset_shift(r, shift);
  return x;
}

Vector ReducedField::expand_velocity(const Vector& u, const Vector& v, const ContactShift& shift,
                                     const ContactShift& shift_rate) const {
  const auto r_held = region(active_set(u, shift));
  const Region& r = *r_held;
  Vector x(n_internal());
  x(interior_) = v;
  x(contact_) = r.A * v + offset_shift(r, shift_rate);
  return x;
}

Vector ReducedField::restrict(const Vector& u_internal) const { return u_internal(interior_); }

Eigen::Vector4d ReducedField::energies(const Vector& u, const Vector& v, const ContactShift& shift,
                                       const ContactShift& shift_rate) const {
  const Vector x = expand(u, shift), xv = expand_velocity(u, v, shift, shift_rate);
  Eigen::Vector4d E;
  E(0) = 0.5 * xv.dot(M_ * xv);
  E(1) = 0.5 * x.dot(K_ * x);
  E(2) = -F_.dot(x);
  E(3) = E(0) + E(1) + E(2);
  return E;
}

double ReducedField::complementarity_residual(const Vector& u, const ContactShift& shift) const {
  const Index nc = n_contact();
  const Vector x = expand(u, shift);
  const Vector g = g_ + part(shift.gap, nc), FC = F_(contact_) + part(shift.load, nc);
  const Vector gap = g - x(contact_);
  const Vector Kx = K_C_ * x;
  const Vector lambda = FC - Kx;
  const double gap_scale = std::max({g.cwiseAbs().maxCoeff(), x(contact_).cwiseAbs().maxCoeff(),
                                     1e-300});
  // The size of the terms lambda is computed from, not of lambda itself
  // (which vanishes on open contacts).
  const Vector terms = K_C_.cwiseAbs() * x.cwiseAbs();
  const double force_scale = std::max({FC.cwiseAbs().maxCoeff(),
                                       terms.maxCoeff(), 1e-300});
  double r = 0;
  for (Index k = 0; k < n_contact(); ++k)
    r = std::max(r, std::abs(std::min(gap(k) / gap_scale, lambda(k) / force_scale)));
  return r;
}

}  // namespace nbm
