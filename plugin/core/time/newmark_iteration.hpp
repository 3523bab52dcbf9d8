// Newmark's update and iteration matrix, shared by the implicit schemes
// (method.md §5): the paper's NBM (NewmarkStepper), the massless boundary
// (MasslessNewmarkStepper) and Moreau-Jean, whose theta = 1/2 step has the
// matrix of beta = 1/4. S = M + gamma dt C + beta dt^2 K (C the damping,
// method.md §9; none by default) is factored here, once, and the contact
// blocks built on it come from here too.
#pragma once

#include <memory>

#include "contact/contact_problem.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

/// Throws InputError unless 0 < beta <= 1/2 and 1/2 <= gamma <= 1.
void check_newmark_parameters(double beta, double gamma);

class NewmarkIteration {
 public:
  /// Factors S = M + gamma dt C + beta dt^2 K (C: 0 x 0 for none). Throws
  /// InputError on beta, gamma out of (0, 1/2] x [1/2, 1], NumericalError if
  /// S is not positive definite.
  NewmarkIteration(const ContactProblem& problem, double dt, double beta, double gamma,
                   const SparseMatrix& C = SparseMatrix());

  double beta() const { return beta_; }
  double gamma() const { return gamma_; }
  double beta_dt2() const { return beta_ * dt_ * dt_; }
  double gamma_dt() const { return gamma_ * dt_; }

  /// The predictors from the state at t_n: u~ = u + dt v + dt^2 (1/2 - beta) a
  /// and v~ = v + dt (1 - gamma) a (no allocation once sized).
  void predict(const Vector& u, const Vector& v, const Vector& a, Vector& u_pred,
               Vector& v_pred) const {
    u_pred = u + dt_ * v + (dt_ * dt_ * (0.5 - beta_)) * a;
    v_pred = v + (dt_ * (1 - gamma_)) * a;
  }
  /// The velocity corrector v = v~ + gamma dt a. (The displacement's,
  /// u = u~ + beta dt^2 a, is the schemes' acceleration form.)
  void correct_velocity(const Vector& v_pred, const Vector& a, Vector& v) const {
    v = v_pred + (gamma_ * dt_) * a;
  }

  /// S = P' L L' P, shared with what is built on it.
  const std::shared_ptr<const CholeskyInverse>& S() const { return S_; }
  /// Y_E = L^-1 P E_C (sparse) and the contact compliance
  /// *compliance = E_C' S^-1 E_C = Y_E' Y_E: the columns of the unit rows of
  /// the contact dofs (supernodal_forward.hpp).
  SparseMatrix contact_columns(Matrix* compliance) const;
  /// E_C' S^-1 E_C alone (Y_E is never held whole).
  Matrix contact_compliance() const;

 private:
  const ContactProblem& problem_;
  double dt_, beta_, gamma_;
  std::shared_ptr<const CholeskyInverse> S_;
};

}  // namespace nbm
