#include "nodal_boundary.hpp"

#include <limits>
#include <string>

#include "errors.hpp"

namespace nbm {
NodalBoundary::NodalBoundary(const ContactProblem& problem)
    : problem_(problem),
      K_C_(problem.constraint_basis().leftCols(problem.n_contact()).transpose()) {
  Eigen::LLT<Matrix> llt(problem.K_CC());
  if (llt.info() != Eigen::Success)
    throw InputError(
        "K: the contact block K_CC is not positive definite; the contact nodes must not "
        "carry a rigid motion of their own (check the contact dofs and the Dirichlet dofs)");
}

LcpResult NodalBoundary::enforce(Vector& u, const Vector& F, const ActiveSet& guess) const {
  const auto& c = problem_.contact_index();
  const Vector& g = problem_.gaps();
  Vector uC(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) uC(k) = u(c[k]);
  // lambda = F_C - K_CO u_O - K_CC u_C and z = g - u_C give lambda = q + K_CC z
  // with q = F_C - (K u)_C + K_CC (u_C - g).
  const Vector q = reactions(u, F) + problem_.K_CC() * (uC - g);
  LcpResult r = LcpSolver::solve(problem_.K_CC(), q, guess);
  for (std::size_t k = 0; k < c.size(); ++k) u(c[k]) = g(k) - r.z(k);
  return r;
}

void NodalBoundary::project(Vector& x, const ActiveSet& active, const Vector& h) const {
  const auto& c = problem_.contact_index();
  std::vector<Index> open;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (active[k])
      x(c[k]) = h(k);
    else
      open.push_back(static_cast<Index>(k));
  }
  if (open.empty()) return;
  const Index m = static_cast<Index>(open.size());
  const auto& llt = open_block_.get(active, [&] {
    Matrix A(m, m);
    for (Index a = 0; a < m; ++a)
      for (Index b = 0; b < m; ++b) A(a, b) = problem_.K_CC()(open[a], open[b]);
    return Eigen::LLT<Matrix>(A);
  });
  const Vector Kx = K_C_ * x;
  Vector delta(m);
  for (Index a = 0; a < m; ++a) delta(a) = h(open[a]) - Kx(open[a]);
  delta = llt.solve(delta);
  for (Index a = 0; a < m; ++a) x(c[open[a]]) += delta(a);
}

Vector NodalBoundary::displacement_constraint(const ActiveSet& active, const Vector& F) const {
  const auto& c = problem_.contact_index();
  Vector h(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) h(k) = active[k] ? problem_.gaps()(k) : F(c[k]);
  return h;
}

Vector NodalBoundary::reactions(const Vector& u, const Vector& F) const {
  const auto& c = problem_.contact_index();
  Vector lambda = -(K_C_ * u);
  for (std::size_t k = 0; k < c.size(); ++k) lambda(k) += F(c[k]);
  return lambda;
}

Vector NodalBoundary::gaps(const Vector& u) const {
  const auto& c = problem_.contact_index();
  Vector gap = problem_.gaps();
  for (std::size_t k = 0; k < c.size(); ++k) gap(k) -= u(c[k]);
  return gap;
}

bool NodalBoundary::consistent(const Vector& u, const Vector& F, const ActiveSet& active) const {
  return violation(u, F, active) <= kConsistencyTolerance;
}

double NodalBoundary::violation(const Vector& u, const Vector& F, const ActiveSet& active) const {
  const auto& c = problem_.contact_index();
  const Vector gap = gaps(u);
  const Vector lambda = reactions(u, F);
  // Scales: displacements (|u|, |g|) and the forces they produce (|K_C| |u|).
  const double u_scale = std::max(u.cwiseAbs().maxCoeff(), problem_.gaps().cwiseAbs().maxCoeff());
  double f_scale = 0;
  for (std::size_t k = 0; k < c.size(); ++k) f_scale = std::max(f_scale, std::abs(F(c[k])));
  const Vector Kabs_u = K_C_.cwiseAbs() * u.cwiseAbs();
  f_scale = std::max(f_scale, Kabs_u.maxCoeff());
  double v = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (active[k] && lambda(k) < 0) v = std::max(v, -lambda(k) / f_scale);
    if (!active[k] && gap(k) < 0) v = std::max(v, -gap(k) / u_scale);
  }
  return v;
}

}  // namespace nbm
