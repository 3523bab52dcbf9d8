// The time scheme of the implicit steppers (method.md §5, §5.4): Newmark's
// family and generalized-alpha, composed with a contact step -- the paper's
// NBM (NewmarkStepper: active set), the massless boundary
// (MasslessNewmarkStepper: one LCP in the forces) and Moreau-Jean (impulses,
// whose theta = 1/2 step has the matrix of average acceleration).
//
// A scheme says how to predict, which effective coefficients of M, C and K
// it solves with, how to correct, and what state it restarts from. Every
// scheme here is a Newmark step in the true acceleration a_{n+1} (the one
// that satisfies the equations of motion, and the contact constraints, at
// t_{n+1}):
//     u_{n+1} = u~ + beta' dt^2 a_{n+1},   v_{n+1} = v~ + gamma' dt a_{n+1},
// solved with S = M + gamma' dt C + beta' dt^2 K, factored here once.
// Newmark: beta' = beta, gamma' = gamma, and u~, v~ its predictors.
// Generalized-alpha carries an algorithmic acceleration b besides a
// (method.md §5.4), which changes the predictors and the coefficients; b is
// the state a restart needs beyond (u, v, a).
#pragma once

#include <memory>

#include "contact/contact_problem.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

/// The parameters of a scheme of the generalized-alpha family (method.md
/// §5.4); alpha_m = alpha_f = 0 is Newmark's family. The named sets:
/// SchemeParameters::newmark() here, generalized_alpha() and hht_alpha() in
/// generalized_alpha.hpp.
struct SchemeParameters {
  double beta = 0.25;  ///< average acceleration by default: energy conserving
  double gamma = 0.5;
  double alpha_m = 0, alpha_f = 0;
  /// Newmark's beta, gamma; throws InputError unless 0 < beta <= 1/2 and
  /// 1/2 <= gamma <= 1.
  static SchemeParameters newmark(double beta, double gamma);
  /// True for the generalized-alpha schemes (alpha_m or alpha_f not 0).
  bool weighted() const { return alpha_m != 0 || alpha_f != 0; }
  /// Plain average acceleration (the trapezoidal rule; method.md §5.1).
  bool average_acceleration() const { return beta == 0.25 && gamma == 0.5 && !weighted(); }
};

/// Throws InputError unless 0 < beta <= 1/2 and 1/2 <= gamma <= 1.
void check_newmark_parameters(double beta, double gamma);

/// Whether the columns Y = L^-1 P E of the contact directions E are kept for
/// the steps (massless_newmark_stepper.hpp), by their size next to L's, or
/// forced (both paths give the same steps to round-off; tests compare them).
enum class ContactColumns { kAuto, kKept, kRecomputed };

/// The choice for E on the factor S: kAuto keeps Y when nnz(Y) <= nnz(L) / 8,
/// or when Y has at most 2^18 entries (3 MB), whose products run from the
/// cache, cheaper than a second solve.
bool keeps_contact_columns(ContactColumns choice, const CholeskyInverse& S,
                           const SparseMatrix& E);

class ImplicitScheme {
 public:
  /// Factors S = M + gamma' dt C + beta' dt^2 K (C: 0 x 0 for none). Throws
  /// NumericalError if S is not positive definite.
  ImplicitScheme(const ContactProblem& problem, double dt, const SchemeParameters& parameters,
                 const SparseMatrix& C = SparseMatrix());

  const SchemeParameters& parameters() const { return parameters_; }
  /// The effective coefficients: u = u~ + beta_dt2() a, v = v~ + gamma_dt() a.
  double beta_dt2() const { return beta_dt2_; }
  double gamma_dt() const { return gamma_dt_; }

  /// Starts the scheme's own state from the true acceleration a_0 (b_0 = a_0).
  void start(const Vector& a);
  /// The predictors from the state at t_n (a_n the true acceleration). Newmark:
  /// u~ = u + dt v + dt^2 (1/2 - beta) a, v~ = v + dt (1 - gamma) a; the
  /// weighted schemes' (method.md §5.4) remember what finish() needs. No
  /// allocation once sized.
  void predict(const Vector& u, const Vector& v, const Vector& a, Vector& u_pred,
               Vector& v_pred);
  /// The velocity corrector v = v~ + gamma' dt a. (The displacement's,
  /// u = u~ + beta' dt^2 a, is the steppers' acceleration form.)
  void correct_velocity(const Vector& v_pred, const Vector& a, Vector& v) const {
    v = v_pred + gamma_dt_ * a;
  }
  /// After a step, from its true acceleration a_{n+1}: the scheme's own
  /// state at t_{n+1} (nothing for Newmark).
  void finish(const Vector& a);

  /// The state beyond (u, v, a) that an exact restart needs: b for the
  /// weighted schemes, empty for Newmark.
  const Vector& state() const { return b_; }
  /// Sets it (restart); throws InputError unless it has the size of state().
  void restore_state(const Vector& state);

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
  SchemeParameters parameters_;
  double dt_, beta_dt2_, gamma_dt_;
  std::shared_ptr<const CholeskyInverse> S_;
  // The weighted schemes: the algorithmic acceleration b and, between
  // predict() and finish(), (alpha_f a_n - alpha_m b_n) / (1 - alpha_m).
  Vector b_, history_;
};

}  // namespace nbm
