// Implicit Newmark with a massless boundary against a rigid obstacle whose
// contact frame follows the body (method.md §10).
//
// Every component of every contact node is massless (mass_redistribution.hpp,
// MasslessPart::kAllComponents), so the iteration matrix S = M' + beta dt^2 K
// does not depend on the normals: it is factored once, in the user's axes,
// together with the compliance Z = E_N^T S^-1 E_N of the d n_c displacements
// of the contact nodes (E_N their unit columns). A step then reads
//     S a = F - K u_hat - E_N N lambda,   u = u_hat + beta dt^2 a,
// (S = M' + gamma dt C + beta dt^2 K and r = F - K u_hat - C v~ with Rayleigh
// damping C), with N (d n_c x n_c) the unit normals of the contact nodes and lambda >= 0
// their contact forces, and the positions of the contact nodes are
//     p = p_free - beta dt^2 Z N lambda,   p_free = X_N + u_hat_N + beta dt^2 (S^-1 r)_N.
// The normals are those of the obstacle at p itself: a fixed point, solved by
// linearising the obstacle at the current guess p^i (normal n^i, gap h^i at
// p^i), solving the LCP
//     gap = h^i - N^i' (p_free - p^i) + beta dt^2 N^i' Z N^i lambda >= 0,
//     lambda >= 0,  gap . lambda = 0,
// and taking p^{i+1} from its lambda. Each iteration is dense work on the
// contact set (the n_c x n_c matrix N' Z N and its LCP), no sparse solve; the
// converged step costs one solve for S^-1 r and, when contact forces act, one
// for S^-1 E_N N lambda (or, where Y = L^-1 P E_N is small, one substitution
// each way and products with Y). At the fixed point the closed contacts satisfy
// phi(p) = 0 up to the square of the last update times the curvature.
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "contact/contact_problem.hpp"
#include "linalg/spd_inverse.hpp"
#include "obstacle/rigid_obstacle.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/stepper.hpp"

namespace nbm {

struct FollowingFrameOptions {
  double beta = 0.25, gamma = 0.5;
  /// The frame iteration stops when no contact node moves by more than
  /// frame_tolerance times the body size between two iterations.
  double frame_tolerance = 1e-12;
  int max_frame_iterations = 50;
  /// Whether Y = L^-1 P E_N is kept (by its size, or forced: both step
  /// alike to round-off; the tests compare them).
  ContactColumns columns = ContactColumns::kAuto;
};

/// The stepping protocol of Stepper (initialize, step, restore, energies);
/// the Obstacle (gap vector) of a ContactLoad is not used: the obstacle is
/// the RigidObstacle given here. StepReport::active_set_iterations counts the
/// frame iterations of the step, StepReport::crossings the nodes outside the
/// contact set that end the step inside the obstacle: every other node whose
/// d dofs share one position (positions), components in the order of their
/// dofs, is checked at every step (one distance per node).
class FollowingFrameStepper final : public Stepper {
 public:
  /// problem: the contact nodes in the user's axes (ContactSet::in_user_axes)
  /// and without a redistributed mass; M_user and positions (one row per user
  /// dof, d columns) make the massless nodes; the obstacle has the nodes'
  /// dimension. Damping: Rayleigh only (a_M on the massless M', b_K on K: the
  /// stiffness part damps vibrations, not rigid motion). Throws InputError on
  /// a rotated problem, a dimension mismatch, bad options or an assembled
  /// damping matrix, NumericalError if S is not positive definite.
  FollowingFrameStepper(const ContactProblem& problem, const SparseMatrix& M_user,
                        const Matrix& positions, std::shared_ptr<const RigidObstacle> obstacle,
                        double dt, const FollowingFrameOptions& options = {},
                        const Damping& damping = {});

  using Stepper::reactions;
  /// Contact forces lambda >= 0 of the last step (force -lambda n on node k).
  void reactions(Vector& lambda) const override { lambda = lambda_; }
  /// phi(x_k + u_k, t) per contact node: the true distance to the obstacle.
  Vector gaps() const override;
  /// The normal of each contact node at its current position (n_c x d).
  Matrix normals() const;
  /// The body size the tolerances are relative to (diagonal of the
  /// bounding box of the nodes).
  double body_size() const { return size_; }
  const RigidObstacle& rigid_obstacle() const { return *obstacle_; }
  const SparseMatrix& mass() const override { return M_; }

 protected:
  /// u_N from the static contact problem of the nodes at the given u_O (the
  /// nodal boundary relation with a following frame), a_O = M_OO^-1 (F - K u
  /// - C v)_O. Throws InputError if u penetrates the obstacle.
  void start(const ContactLoad& load) override;
  StepReport advance(const ContactLoad& next) override;
  /// Restored states are checked against the true obstacle in start() only:
  /// the gap vector of the base class does not describe this obstacle.
  bool exact_impenetrability() const override { return false; }

 private:
  /// Positions of the contact nodes (n_c x d, row k = x_k + u_k) for u, into p.
  void positions_of(const Vector& u, Matrix& p) const;
  /// The fixed point of the header for free positions p_free and the
  /// compliance `scale` * Z at time t (Z null: the static compliance
  /// K_NN^-1 of the start), from the linearisation point p (updated in place
  /// to the converged positions); lambda_ and normals_ set. Returns the
  /// number of iterations.
  int solve_frame(const Matrix& p_free, const Matrix* Z, double scale, double t, Matrix& p);
  /// u <- u + (p - positions_of(u)) on the contact nodes.
  void place_nodes(const Matrix& p, Vector& u) const;
  /// Nodes outside the contact set inside the obstacle at time t (above).
  int count_crossings(double t);
  /// -lambda . g' at time t, g' = (d phi / dt) / |grad phi| at each node.
  double obstacle_power(const Vector& lambda, const Vector& u, double t) const;
  /// v_N and a_N from the nodal boundary relation differentiated in time
  /// (method.md §10): the massless nodes carry no inertia, so their rates
  /// are those of the relation at the interior rates, not Newmark's. At
  /// time t, the positions u_ and closed contacts active_ of that time.
  /// Undamped runs only: with Rayleigh damping the contact rows
  /// (K u + b_K K v)_N = F_N - N lambda are a first-order equation in u_N,
  /// which Newmark's update integrates, and its v_N is the physical one.
  void boundary_rates(double t);
  /// KN_ = K_NN^-1 N_A and the factor of G = N_A' K_NN^-1 N_A for the
  /// closed contacts A (active_) and their normals_: one solve with |A|
  /// columns, shared by the relations of v and a.
  void prepare_closed_relation();
  /// x_N <- K_NN^-1 (-(K x)_O-part) constrained by n_k . x_k = h_k on the
  /// closed contacts (after prepare_closed_relation).
  void boundary_relation(Vector& x, const Vector& h);

  std::shared_ptr<const RigidObstacle> obstacle_;
  FollowingFrameOptions options_;
  Index n_c_;
  int d_;
  std::vector<Index> node_dofs_;  // internal index of component j of node k at k d + j
  Matrix X_;                      // reference positions of the contact nodes (n_c x d)
  // The other nodes: internal dofs (d per node, by component) and positions.
  std::vector<Index> watch_dofs_;
  Matrix watch_X_;
  // Where each watched node was when phi was last evaluated, and that phi
  // (count_crossings: a fixed signed distance is evaluated only for nodes
  // that have moved farther than it since).
  Matrix watch_at_;
  Vector watch_phi_;
  double size_ = 1;
  SparseMatrix M_;                // the massless mass M'
  std::unique_ptr<CholeskyInverse> S_;
  Matrix Z_;                      // E_N' S^-1 E_N
  bool keep_columns_ = false;     // Y kept (constructor)
  SparseMatrix Y_;                // L^-1 P E_N, if kept
  SparseMatrix K_NN_matrix_, K_N_;            // the contact nodes' block and rows of K
  Eigen::SimplicialLLT<SparseMatrix> K_NN_;  // K_NN's factor
  Vector lambda_;
  Matrix normals_;                // n_c x d, those lambda_ acts along
  std::vector<bool> open_guess_;  // the LCP's warm start: lambda = 0
  // Workspaces (sized by the first step, so that a step reuses them).
  // solve_frame: gaps q_, the shift of the nodes, the candidates and their
  // columns Z N_C, LCP matrix and data.
  Vector q_, shift_, q_C_, e_N_;
  std::vector<char> candidate_;
  std::vector<Index> C_nodes_;
  std::vector<bool> guess_;
  Matrix ZN_, A_;
  // advance: predictors, free accelerations of the nodes, positions, force.
  Vector u_hat_, v_pred_, accel_, free_N_, force_, correction_;
  Matrix p_free_, p_, p_now_;
  // The relation of the closed contacts (prepare_closed_relation).
  std::vector<Index> closed_;
  Matrix N_A_, KN_;
  Eigen::LDLT<Matrix> G_;
  Vector x_N_, r_N_, b_, h_v_, h_a_;
};

}  // namespace nbm
