#include "periodic/reduced_basis.hpp"

#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "linalg/sparse_eigen.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {
namespace {
// The lowest fixed-interface frequency^2 relative to the mesh's frequency
// scale below which K_OO is taken as singular: round-off pivots give
// 1e-16 to 1e-13, the slenderest meshes' lowest modes far more.
constexpr double kRigidMotionTolerance = 1e-12;


SparseMatrix block(const SparseMatrix& A, const std::vector<Index>& rows,
                   const std::vector<Index>& cols) {
  std::vector<Index> col_pos(A.cols(), -1), row_pos(A.rows(), -1);
  for (std::size_t k = 0; k < cols.size(); ++k) col_pos[cols[k]] = static_cast<Index>(k);
  for (std::size_t k = 0; k < rows.size(); ++k) row_pos[rows[k]] = static_cast<Index>(k);
  std::vector<Triplet> t;
  for (Index j = 0; j < A.outerSize(); ++j)
    if (col_pos[j] >= 0)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
        if (row_pos[it.row()] >= 0)
          t.emplace_back(static_cast<int>(row_pos[it.row()]), static_cast<int>(col_pos[j]),
                         it.value());
  SparseMatrix B(static_cast<Index>(rows.size()), static_cast<Index>(cols.size()));
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

}  // namespace

ReducedBasis::ReducedBasis(const ContactProblem& problem, const Vector& F, int modes)
    : problem_(problem), F_(F) {
  const Index N = problem.size();
  contact_ = problem.contact_index();
  std::vector<char> is_contact(N, 0);
  for (Index c : contact_) is_contact[c] = 1;
  for (Index i = 0; i < N; ++i)
    if (!is_contact[i]) interior_.push_back(i);
  const Index n = static_cast<Index>(interior_.size()), nc = static_cast<Index>(contact_.size());
  if (modes < 1 || modes > n)
    throw InputError("modes: " + std::to_string(modes) + "; expected 1 .. " + std::to_string(n) +
                     " (the number of interior dofs)");

  const SparseMatrix KOO = block(problem.K(), interior_, interior_);
  const SparseMatrix MOO = block(problem.M(), interior_, interior_);
  const SparseMatrix KOC = block(problem.K(), interior_, contact_);
  const auto KOO_inv = make_cholesky_inverse(KOO, "reduced basis: K_OO (contact dofs clamped)");

  // Lowest fixed-interface modes: Lanczos in shift-invert mode on the factor.
  const SymmetricEigen eig = lowest_eigenpairs(KOO, MOO, *KOO_inv, modes);
  const Matrix& Phi = eig.vectors;
  const Vector& w2 = eig.values;
  // A rigid motion with the contact dofs clamped (a body free to slide along
  // its obstacle) leaves K_OO singular, which its factorization may not see
  // (round-off pivots): the lowest frequency is then zero to round-off
  // against the mesh's frequency scale max K_ii / max M_ii.
  const double scale = KOO.diagonal().maxCoeff() / MOO.diagonal().maxCoeff();
  if (!(w2.minCoeff() > kRigidMotionTolerance * scale))
    throw NumericalError("reduced basis: K_OO (contact dofs clamped) is singular: a rigid "
                         "motion (lowest frequency^2 " + std::to_string(w2.minCoeff()) +
                         ") moves the interior with the contact dofs held; fix the body "
                         "(fixed=) so that clamping its contact dofs holds it in place");
  cutoff_ = std::sqrt(w2.maxCoeff());

  // V = [Phi, Psi], made M_OO-orthonormal (dependent columns dropped).
  Matrix V(n, modes + nc);
  V.leftCols(modes) = Phi;
  Matrix Psi = -Matrix(KOC);
  KOO_inv->solve_in_place(Psi);
  V.rightCols(nc) = Psi;
  const Matrix G = V.transpose() * (MOO * V);
  const SymmetricEigen gram = symmetric_eigen(0.5 * (G + G.transpose()));
  if (!gram.ok)
    throw NumericalError("reduced basis: the eigenvalue solver of the Gram matrix failed");
  const double top = gram.values.maxCoeff();
  Index kept = 0;
  for (Index k = 0; k < gram.values.size(); ++k) kept += gram.values(k) > 1e-12 * top;
  V_ = V * gram.vectors.rightCols(kept) *
       gram.values.tail(kept).cwiseSqrt().cwiseInverse().asDiagonal();
  VtM_ = (MOO * V_).transpose();

  // Reduced contact problem: coordinates (q, u_C).
  const Index r = V_.cols();
  Matrix T = Matrix::Zero(N, r + nc);
  T(interior_, Eigen::seqN(0, r)) = V_;
  for (Index k = 0; k < nc; ++k) T(contact_[k], r + k) = 1;
  const Matrix Mr = T.transpose() * (problem.M() * T), Kr = T.transpose() * (problem.K() * T);
  std::vector<Index> contact(nc);
  for (Index k = 0; k < nc; ++k) contact[k] = r + k;
  M_ = 0.5 * (Mr + Mr.transpose());
  K_ = 0.5 * (Kr + Kr.transpose());
  field_ = std::make_unique<ReducedField>(M_, K_, T.transpose() * F, contact, problem.gaps());
}

Vector ReducedBasis::reduce(const Vector& u_interior) const {
  return VtM_ * u_interior;
}

ContactProblem ReducedBasis::contact_problem() const {
  const Index n = M_.rows(), nc = static_cast<Index>(contact_.size());
  std::vector<Index> dofs(nc);
  for (Index k = 0; k < nc; ++k) dofs[k] = n - nc + k;
  ContactSet contacts(n, std::move(dofs), std::vector<double>(nc, 1.0), problem_.gaps());
  const SparseMatrix M = M_.sparseView(), K = K_.sparseView();
  if (problem_.massless_boundary())
    return ContactProblem::with_massless_boundary(M, K, std::move(contacts));
  return ContactProblem(M, K, std::move(contacts), {});
}

Vector ReducedBasis::reduce_state(const Vector& x) const {
  Vector y(V_.cols() + static_cast<Index>(contact_.size()));
  y << reduce(x(interior_)), x(contact_);
  return y;
}

Vector ReducedBasis::expand_state(const Vector& y) const { return expand_states(y).col(0); }

Matrix ReducedBasis::expand_states(const Matrix& Y) const {
  const Index m = V_.cols();
  Matrix X(problem_.size(), Y.cols());
  X(interior_, Eigen::all) = V_ * Y.topRows(m);
  X(contact_, Eigen::all) = Y.bottomRows(static_cast<Index>(contact_.size()));
  return X;
}

Vector ReducedBasis::reduce_load(const Vector& F) const {
  Vector y(V_.cols() + static_cast<Index>(contact_.size()));
  y << V_.transpose() * F(interior_), F(contact_);
  return y;
}

Damping ReducedBasis::reduce(const Damping& d) const {
  Damping r = d;
  if (!d.has_matrix()) return r;
  // T^T C T: C vanishes on the contact normal components (checked where it
  // comes in), so only the interior block is projected.
  // Sparse blocks: the full matrix is never made dense.
  const Index m = V_.cols(), nc = static_cast<Index>(contact_.size());
  const SparseMatrix& U = d.C_user;
  Matrix C = Matrix::Zero(m + nc, m + nc);
  C.topLeftCorner(m, m) = V_.transpose() * (block(U, interior_, interior_) * V_);
  C.topRightCorner(m, nc) = V_.transpose() * Matrix(block(U, interior_, contact_));
  C.bottomLeftCorner(nc, m) = Matrix(block(U, contact_, interior_)) * V_;
  C.bottomRightCorner(nc, nc) = Matrix(block(U, contact_, contact_));
  r.C_user = C.sparseView();
  return r;
}

HarmonicLoad ReducedBasis::reduce(const HarmonicLoad& load) const {
  HarmonicLoad r = load;
  for (Vector& F : r.cos) F = reduce_load(F);
  for (Vector& F : r.sin) F = reduce_load(F);
  return r;
}

double ReducedBasis::full_residual(const Vector& q, const Vector& a) const {
  return full_residual(q, Vector::Zero(q.size()), a, 0, ExactFlow(*field_), Damping{},
                       HarmonicLoad{});
}

double ReducedBasis::full_residual(const Vector& q, const Vector& v, const Vector& a, double t,
                                   const ExactFlow& flow, const Damping& damping,
                                   const HarmonicLoad& load) const {
  // Full internal state x = (V q, u_C), its rate and acceleration, u_C from
  // the reduced model's nodal boundary relation (the full model's on
  // range(V)) with the contacts moved to time t (method.md §8).
  const ReducedField& f = *field_;
  const FlowForcing& forcing = flow.forcing();
  const auto reg_held = f.region(f.active_set(q, forcing.shift(t)));
  const Region& reg = *reg_held;
  const Index N = problem_.size();
  Vector x(N), xv(N), xa(N);
  x(interior_) = V_ * q;
  xv(interior_) = V_ * v;
  xa(interior_) = V_ * a;
  x(contact_) = reg.A * q + reg.e + offset_shift(reg, forcing.shift(t));
  xv(contact_) = reg.A * v + offset_shift(reg, forcing.shift(t, 1));
  xa(contact_) = reg.A * a + offset_shift(reg, forcing.shift(t, 2));
  // The load at t: F0 and the harmonics of the excitation.
  Vector F = F_;
  for (std::size_t k = 0; k < load.cos.size(); ++k) F += std::cos((k + 1) * load.omega * t) * load.cos[k];
  for (std::size_t k = 0; k < load.sin.size(); ++k) F += std::sin((k + 1) * load.omega * t) * load.sin[k];
  return equation_residual(x, xv, xa, F, damping, reg.active);
}

double ReducedBasis::equation_residual(const Vector& x, const Vector& xv, const Vector& xa,
                                       const Vector& F, const Damping& damping,
                                       const ActiveSet& active) const {
  const SparseMatrix C = damping_matrix(damping, problem_.M(), problem_.K());
  Vector r = problem_.M() * xa + problem_.K() * x - F;
  Vector terms = problem_.M().cwiseAbs() * xa.cwiseAbs() + problem_.K().cwiseAbs() * x.cwiseAbs() +
                 F.cwiseAbs();
  if (C.size() != 0) {
    r += C * xv;
    terms += C.cwiseAbs() * xv.cwiseAbs();
  }
  // P^T r of the full model: r_O + A_full^T r_C, with A_full from the full
  // nodal boundary relation (open contacts: u_I = K_II^-1 (F_I - K_IO u_O ...)).
  Vector R = r(interior_);
  std::vector<Index> open_dofs;
  for (std::size_t k = 0; k < contact_.size(); ++k)
    if (!active[k]) open_dofs.push_back(contact_[k]);
  if (!open_dofs.empty()) {
    const Matrix KII = Matrix(block(problem_.K(), open_dofs, open_dofs));
    const Vector y = KII.llt().solve(r(open_dofs));
    R -= block(problem_.K(), interior_, open_dofs) * y;
  }
  return R.norm() / std::max(terms(interior_).norm(), 1e-300);
}

}  // namespace nbm
