#include "time/implicit_scheme.hpp"

#include <string>

#include "base/errors.hpp"

namespace nbm {

void check_newmark_parameters(double beta, double gamma) {
  if (!(beta > 0 && beta <= 0.5))
    throw InputError("beta: " + std::to_string(beta) +
                     ", expected 0 < beta <= 1/2 (beta = 0 is the explicit scheme)");
  if (!(gamma >= 0.5 && gamma <= 1))
    throw InputError("gamma: " + std::to_string(gamma) + ", expected 1/2 <= gamma <= 1");
}

SchemeParameters SchemeParameters::newmark(double beta, double gamma) {
  check_newmark_parameters(beta, gamma);
  SchemeParameters p;
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

namespace {

// beta' = beta (1 - alpha_f) / (1 - alpha_m) and gamma' likewise (method.md
// §5.4); Newmark's own beta and gamma, bit for bit, when alpha_m = alpha_f = 0.
double effective(double coefficient, const SchemeParameters& p) {
  return p.weighted() ? coefficient * (1 - p.alpha_f) / (1 - p.alpha_m) : coefficient;
}

}  // namespace

ImplicitScheme::ImplicitScheme(const ContactProblem& problem, double dt,
                               const SchemeParameters& parameters, const SparseMatrix& C)
    : problem_(problem),
      parameters_(parameters),
      dt_(dt),
      beta_dt2_(effective(parameters.beta, parameters) * dt * dt),
      gamma_dt_(effective(parameters.gamma, parameters) * dt) {
  if (!parameters.weighted()) check_newmark_parameters(parameters.beta, parameters.gamma);
  // Factored for the constrained solves with B = [K_{:,C} E_C]: CHOLMOD
  // orders for B in both mass treatments; MUMPS condenses on the rows of the
  // columns the steps use, E_C alone in the massless step (method.md §5),
  // whose stiffness columns would add the contact nodes' neighbours.
  const SparseMatrix& B = problem.constraint_basis();
  const SparseFactorizer& factorizer = problem.factorizer();
  const SparseMatrix E_C = B.rightCols(problem.n_contact());
  const SparseMatrix& columns =
      factorizer.solver() == SparseSolver::kMumps && problem.massless_boundary() ? E_C : B;
  if (C.size() == 0)
    S_ = factorizer.factor(problem.M() + beta_dt2_ * problem.K(), "M + beta dt^2 K", columns);
  else
    S_ = factorizer.factor(problem.M() + gamma_dt_ * C + beta_dt2_ * problem.K(),
                           "M + gamma dt C + beta dt^2 K", columns);
  if (parameters.weighted()) b_ = Vector::Zero(problem.size());
}

void ImplicitScheme::start(const Vector& a) {
  if (parameters_.weighted()) b_ = a;
}

void ImplicitScheme::predict(const Vector& u, const Vector& v, const Vector& a, Vector& u_pred,
                             Vector& v_pred) {
  const double beta = parameters_.beta, gamma = parameters_.gamma;
  if (!parameters_.weighted()) {
    u_pred = u + dt_ * v + (dt_ * dt_ * (0.5 - beta)) * a;
    v_pred = v + (dt_ * (1 - gamma)) * a;
    return;
  }
  // Newmark's update in b, with b_{n+1} = (1 - alpha_f)/(1 - alpha_m) a_{n+1}
  // + history, history = (alpha_f a_n - alpha_m b_n) / (1 - alpha_m):
  // the history joins the predictors, a_{n+1} the effective coefficients.
  const double am = parameters_.alpha_m, af = parameters_.alpha_f;
  history_ = (af / (1 - am)) * a - (am / (1 - am)) * b_;
  u_pred = u + dt_ * v + (dt_ * dt_ * (0.5 - beta)) * b_ + (dt_ * dt_ * beta) * history_;
  v_pred = v + (dt_ * (1 - gamma)) * b_ + (dt_ * gamma) * history_;
}

void ImplicitScheme::finish(const Vector& a) {
  if (!parameters_.weighted()) return;
  const double am = parameters_.alpha_m, af = parameters_.alpha_f;
  b_ = ((1 - af) / (1 - am)) * a + history_;
}

void ImplicitScheme::restore_state(const Vector& state) {
  if (state.size() != b_.size())
    throw InputError("scheme state: size " + std::to_string(state.size()) + ", expected " +
                     std::to_string(b_.size()) +
                     (parameters_.weighted()
                          ? " (generalized-alpha's algorithmic acceleration, one per dof)"
                          : " (the scheme has no state of its own)"));
  b_ = state;
}

bool keeps_contact_columns(ContactColumns choice, const CholeskyInverse& S,
                           const SparseMatrix& E) {
  if (choice != ContactColumns::kAuto) return choice == ContactColumns::kKept;
  constexpr double kCachedColumnEntries = 1 << 18;
  const double entries = S.forward_entries(E);
  return entries <= kCachedColumnEntries || 8 * entries <= S.factor_entries();
}

SparseMatrix ImplicitScheme::contact_columns(Matrix* compliance) const {
  // Columns E_C of the constraint basis B = [K_{:,C}  E_C].
  return S_->forward(problem_.constraint_basis().rightCols(problem_.n_contact()), compliance);
}

Matrix ImplicitScheme::contact_compliance() const {
  return S_->gram(problem_.constraint_basis().rightCols(problem_.n_contact()));
}

}  // namespace nbm
