#include "contact/nodal_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"

namespace nbm {
namespace {

// A contact node whose gap exceeds this many times the displacement scale is
// given a nearer obstacle in the LCP (NodalBoundary::enforce).
constexpr double kFarGap = 1e3;

}  // namespace

NodalBoundary::NodalBoundary(const ContactProblem& problem)
    : problem_(problem),
      K_C_(problem.constraint_basis().leftCols(problem.n_contact()).transpose()),
      lcp_(problem.K_CC()),
      q_(problem.n_contact()),
      work_(problem.n_contact()),
      Kx_(problem.n_contact()),
      shift_(problem.n_contact()),
      K_CC_diagonal_(problem.K_CC().diagonal()) {
  std::vector<Index> all(static_cast<std::size_t>(problem.n_contact()));
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<Index>(k);
  if (!PrincipalBlockFactor(lcp_.matrix(), all).positive_definite())
    throw InputError(
        "K: the contact block K_CC is not positive definite; the contact nodes must not "
        "carry a rigid motion of their own (check the contact dofs and the Dirichlet dofs)");
  open_.reserve(problem.n_contact());
}

const LcpResult& NodalBoundary::enforce(Vector& u, const Vector& F, const Vector& g,
                                        const ActiveSet& guess) const {
  const auto& c = problem_.contact_index();
  const Index nc = static_cast<Index>(c.size());
  // lambda = F_C - K_CO u_O - K_CC u_C and z = s - u_C give lambda = q + K_CC z
  // with q = F_C - (K u)_C + K_CC (u_C - s), for an obstacle at s.
  //
  // s = g, except at nodes far from their obstacle: a gap of 1e15 beside
  // displacements of 0.1 would enter q of every neighbour as K g and u_C as
  // g - z, losing every digit of both (all nodes of the body then move
  // wrongly). Those nodes get a nearer obstacle, s_k = u_k + 4 D (D the
  // displacement scale, header); if the solution leaves all of them open
  // (z_k > 0), it is also the solution against g (the LCP's solution is
  // unique and s <= g), with no digit lost. Otherwise D grows and the LCP is
  // solved again.
  double D = u.cwiseAbs().maxCoeff();
  for (Index k = 0; k < nc; ++k)
    D = std::max(D, std::abs(F(c[k])) / K_CC_diagonal_(k));
  while (true) {
    bool shifted = false;
    for (Index k = 0; k < nc; ++k) {
      const double s = u(c[k]) + 4 * D;
      shift_(k) = D > 0 && g(k) - u(c[k]) > kFarGap * D && s < g(k) ? s : g(k);
      shifted = shifted || shift_(k) != g(k);
    }
    for (Index k = 0; k < nc; ++k) work_(k) = u(c[k]) - shift_(k);
    reactions(u, F, q_);
    lcp_.matrix().add_product(work_, q_);
    const LcpResult& r = lcp_.solve(q_, guess);
    bool reached = false;
    for (Index k = 0; k < nc && shifted; ++k)
      reached = reached || (shift_(k) != g(k) && !(r.z(k) > 0));
    if (reached) {
      D *= 16;
      continue;
    }
    for (Index k = 0; k < nc; ++k) u(c[k]) = shift_(k) - r.z(k);
    if (!shifted) return r;
    result_ = r;  // z: the gaps to the true obstacle
    for (Index k = 0; k < nc; ++k)
      if (shift_(k) != g(k)) result_.z(k) = g(k) - u(c[k]);
    return result_;
  }
}

void NodalBoundary::project(Vector& x, const ActiveSet& active, const Vector& h) const {
  const auto& c = problem_.contact_index();
  open_.clear();
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (active[k])
      x(c[k]) = h(k);
    else
      open_.push_back(static_cast<Index>(k));
  }
  if (open_.empty()) return;
  const Index m = static_cast<Index>(open_.size());
  const PrincipalBlockFactor& open_block = lcp_.principal_factor(active, open_);
  Kx_.noalias() = K_C_ * x;
  auto delta = work_.head(m);
  for (Index a = 0; a < m; ++a) delta(a) = h(open_[a]) - Kx_(open_[a]);
  open_block.solve_in_place(delta);
  for (Index a = 0; a < m; ++a) x(c[open_[a]]) += delta(a);
}

Vector NodalBoundary::reactions(const Vector& u, const Vector& F) const {
  Vector lambda(problem_.n_contact());
  reactions(u, F, lambda);
  return lambda;
}

void NodalBoundary::reactions(const Vector& u, const Vector& F, Vector& lambda) const {
  const auto& c = problem_.contact_index();
  lambda.noalias() = K_C_ * u;
  for (std::size_t k = 0; k < c.size(); ++k) lambda(k) = F(c[k]) - lambda(k);
}

Vector NodalBoundary::gaps(const Vector& u, const Vector& g) const {
  const auto& c = problem_.contact_index();
  Vector gap = g;
  for (std::size_t k = 0; k < c.size(); ++k) gap(k) -= u(c[k]);
  return gap;
}

double NodalBoundary::violation(const Vector& u, const Vector& F, const Vector& g,
                                const ActiveSet& active) const {
  const auto& c = problem_.contact_index();
  reactions(u, F, q_);  // lambda
  // Scales: displacements (|u|, and per node |g_k|) and the forces they
  // produce (|K_C| |u|).
  const double u_scale = u.cwiseAbs().maxCoeff();
  double f_scale = 0;
  for (std::size_t k = 0; k < c.size(); ++k) f_scale = std::max(f_scale, std::abs(F(c[k])));
  for (Index k = 0; k < K_C_.outerSize(); ++k) {
    double row = 0;
    for (decltype(K_C_)::InnerIterator it(K_C_, k); it; ++it)
      row += std::abs(it.value()) * std::abs(u(it.col()));
    Kx_(k) = row;
  }
  f_scale = std::max(f_scale, Kx_.maxCoeff());
  double v = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double gap = g(k) - u(c[k]), lambda = q_(k);
    if (active[k] && lambda < 0) v = std::max(v, -lambda / f_scale);
    if (!active[k] && gap < 0) v = std::max(v, -gap / std::max(u_scale, std::abs(g(k))));
  }
  return v;
}

}  // namespace nbm
