// Implicit Newmark on the NBM equations with a massless boundary (method.md
// §4-5, M_CC = 0 and M_CO = 0, see mass_redistribution.hpp).
//
// With no mass on the contact dofs, their rows of the step system
// S u = M u_hat + beta dt^2 (F - E_C lambda), S = M + beta dt^2 K, say
// lambda = F_C - (K u)_C: the contact force of the nodal boundary relation.
// Eliminating u through one factorization of S leaves a small LCP in lambda,
//     gap = g - (S^-1 r)_C + beta dt^2 W_CC lambda >= 0,  lambda >= 0,
//     gap . lambda = 0,   W_CC = E_C^T S^-1 E_C (symmetric positive definite),
// solved exactly: the step has a unique solution, found without iterating
// over guessed active sets, and u_C satisfies the nodal boundary relation at
// u_O^{n+1}, so impenetrability is exact. The step is solved in
// acceleration form (u = u_hat + beta dt^2 a), exact at any dt, with one
// forward and one backward substitution: with S = P' L L' P and
// Y = L^-1 P E_C (sparse, kept), W_CC = Y^T Y, (S^-1 r)_C = Y^T y for
// y = L^-1 P r, and a = P' L^-T (y - Y lambda).
//
// Where Y is large next to L (a 3D body's contact face: its columns reach
// the large separators at the top of the elimination tree), Y is not kept:
// a = S^-1 r is solved whole, (S^-1 r)_C read from it, and a step with
// contact forces solves once more for S^-1 E_C lambda. A step in free
// flight is then the plain step, one with contact two; with Y every step
// costs a substitution pair plus the two products with Y (about
// 2 nnz(Y) / nnz(L) of a pair, and more in time: the products are sparse,
// the substitutions BLAS kernels on dense blocks). Y is kept when
// nnz(Y) <= nnz(L) / 8, or when it is small enough (2^18 entries) for its
// products to run from the cache. Measured on the 3D block with 2178
// contact nodes (nnz(Y) = nnz(L) / 3), without Y: free flight 1.13 plain
// steps instead of 2.6, a step of the sweeping contact front 2.6 to 3.3
// instead of 3.8 (bench/why-scale.md); and Y's memory is saved (3.4 GB on the 3D block
// of 1e6 dofs, where L holds 15 GB).
//
// Energy (method.md §5.1): with average acceleration (beta = 1/4,
// gamma = 1/2) and no stiffness-proportional damping, the energy never rises
// above its start (EnergyControl below).
// The trapezoidal rule applies the mean of the contact forces at the step's
// ends, (lambda_n + lambda_{n+1}) / 2, which does work lambda_n . gap_{n+1}
// / 2 > 0 on a node that lifts off: a body resting on its support gains
// energy wherever its contacts switch. So a switching step whose energy
// balance would rise is replaced. The step (5.2) applies one force mu / 2,
// complementary to the gap at its end (the LCP above with the contact rows
// r_C + lambda_n, lambda_n = F_C - (K u_n)_C: same matrix), and does work
// -mu . gap_n / 2 <= 0; its u_C, admissible but on the relation at the
// step's middle, is put back on the relation at u_O^{n+1}, which only
// lowers the elastic energy, and a_O made consistent with it by a solve
// with the interior mass (conjugate gradients, mass_solve.hpp). The step
// taken is the state on the way from (5.2) to the trapezoidal step, both
// returned to the relation, whose balance is the start's (regula falsi on
// the fraction of the way): the energy is conserved there, and falls only
// on the steps where the trapezoidal rule itself loses it (touchdowns).
// With EnergyControl::kBounded (the default) those losses are kept, and a
// later switching step may gain up to what is kept: the trapezoidal rule's
// gains at lift-offs offset its losses at touchdowns as far as they
// balance, and only the excess is removed, so the energy never exceeds its
// start (plus work) and the accuracy of the trapezoidal rule is kept where
// its errors cancel (the bouncing bar).
//
// Damping (method.md §9): the contact dofs carry no damping of their own
// either (C_user's rows and columns of the contact dofs must vanish; a_M M
// is redistributed with M), except Rayleigh's stiffness part b_K K, whose
// contact rows are b_K K_C: -- the Kelvin-Voigt stress of the relation. Then
// S = M + gamma dt C + beta dt^2 K has contact rows s beta dt^2 K_C:,
// s = 1 + gamma b_K / (beta dt), and the contact rows of the right-hand side
// are s (F - K u_hat)_C: the step still says (K u)_C = F_C - lambda, the
// nodal boundary relation, with lambda' = s lambda in the same LCP. The
// interior rows carry F - C v~ - K u_hat.
#pragma once

#include <memory>

#include "linalg/lcp.hpp"
#include "linalg/mass_solve.hpp"
#include "time/nbm_stepper.hpp"
#include "time/implicit_scheme.hpp"

namespace nbm {

class MasslessNewmarkStepper final : public NbmStepper {
 public:
  /// The problem must have a massless boundary (ContactProblem::
  /// make_boundary_massless). Factors S once and forms W_CC, and Y if it is
  /// kept (n_contact sparse forward substitutions).
  /// `scheme`: Newmark's or generalized-alpha's parameters
  /// (implicit_scheme.hpp; beta, gamma above stand for its effective ones).
  /// Throws InputError on a problem with boundary mass, NumericalError if S
  /// is not positive definite. Throws InputError, too, if the damping matrix
  /// C_user couples a contact dof. The energy-stable step is taken with
  /// average acceleration only.
  MasslessNewmarkStepper(const ContactProblem& problem, double dt,
                         const SchemeParameters& scheme = {}, const Damping& damping = {},
                         ContactColumns columns = ContactColumns::kAuto,
                         EnergyControl energy = EnergyControl::kBounded);

  /// Whether Y is kept.
  bool keeps_contact_columns() const { return keep_columns_; }
  using Stepper::step;

 protected:
  const SparseMatrix& mass() const override { return problem_.M(); }
  /// a_O = M_OO^-1 (F - K u - C v)_O (the contact rows carry no inertia), a_C from
  /// the nodal boundary relation.
  void solve_acceleration(const ContactLoad& load) override;
  /// Only g_{n+1} enters (the contact dofs carry no inertia, so the
  /// obstacle's rates matter only for the reported v_C, a_C).
  StepReport advance_interior(const ContactLoad& next) override;
  bool accounts_obstacle_work() const override { return energy_stable_; }

 private:
  /// a <- S^-1 (a - E_C lambda) with lambda the LCP's solution for
  /// a_free_C = (S^-1 a)_C (header), with Y or by whole solves; the LCP's
  /// result (z = lambda).
  const LcpResult& accelerate(const Vector& g, Vector& a);
  const LcpResult& contact_forces(const Vector& g);  // the LCP for a_C_
  /// After an energy-stable step that changed the active set: u_C onto the
  /// nodal boundary relation at u_O (load F, gaps g), a_O consistent with
  /// it; the new active set.
  void return_to_relation(const Vector& F, const Vector& g);
  /// The parts of the balance along the way from (5.2) to the trapezoidal
  /// step that are quadratic in theta (blend_), for the end load F.
  void prepare_blend(const Vector& F);
  /// u_, v_ at theta of the way from the step (5.2) to the trapezoidal one,
  /// returned to the relation; their balance (after prepare_blend).
  double blend(double theta, const ContactLoad& next);

  ImplicitScheme iteration_;
  const CholeskyInverse& S_;              // the iteration matrix
  bool keep_columns_;                     // Y kept (header)
  SparseMatrix Y_;                        // L^-1 P E_C, if kept
  std::unique_ptr<CachedLcpSolver> lcp_;  // of beta dt^2 W_CC
  double contact_row_scale_;              // s of the header (1 without b_K)
  SparseMatrix interior_mass_;            // M + E_C E_C' (M_CC = 0, M_CO = 0)
  std::unique_ptr<MassSolver> mass_solver_;  // of interior_mass_
  // Workspaces of a step (sized by the first one).
  Vector u_hat_, v_pred_, acceleration_, correction_, q_, a_C_, h_accel_, Cv_;
  Vector lambda_start_, u_C_before_, stiffness_change_;
  // The energy-stable step's candidates: the trapezoidal step and (5.2).
  Vector rhs_, v_mean_, u_trap_, v_trap_, a_trap_, u_mid_, v_mid_, a_mid_;
  // The way between them (prepare_blend): du, dv, K u_mid, K du, M dv, the
  // mean load, and the quadratic's coefficients.
  Vector du_, dv_, Ku_mid_, Kdu_, Mdv_, load_mean_, reactions_;
  double blend_[3] = {0, 0, 0};
  double energy_start_ = 0, work_trap_ = 0, work_mid_ = 0;
  ActiveSet open_;
};

}  // namespace nbm
