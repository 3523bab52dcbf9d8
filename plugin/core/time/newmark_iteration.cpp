#include "time/newmark_iteration.hpp"

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

NewmarkIteration::NewmarkIteration(const ContactProblem& problem, double dt, double beta,
                                   double gamma, const SparseMatrix& C)
    : problem_(problem), dt_(dt), beta_(beta), gamma_(gamma) {
  check_newmark_parameters(beta, gamma);
  // Ordered for the constrained solves with B = [K_{:,C} E_C] (both mass
  // treatments solve with columns of B).
  const SparseMatrix& B = problem.constraint_basis();
  if (C.size() == 0) {
    S_ = make_cholesky_inverse(problem.M() + (beta * dt * dt) * problem.K(), "M + beta dt^2 K", B);
  } else {
    S_ = make_cholesky_inverse(problem.M() + (gamma * dt) * C + (beta * dt * dt) * problem.K(),
                               "M + gamma dt C + beta dt^2 K", B);
  }
}

SparseMatrix NewmarkIteration::contact_columns(Matrix* compliance) const {
  // Columns E_C of the constraint basis B = [K_{:,C}  E_C].
  return S_->forward(problem_.constraint_basis().rightCols(problem_.n_contact()), compliance);
}

Matrix NewmarkIteration::contact_compliance() const {
  return S_->gram(problem_.constraint_basis().rightCols(problem_.n_contact()));
}

}  // namespace nbm
