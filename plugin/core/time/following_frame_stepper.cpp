#include "time/following_frame_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"
#include "contact/mass_redistribution.hpp"
#include "linalg/lcp.hpp"
#include "linalg/mass_solve.hpp"
#include "time/implicit_scheme.hpp"

namespace nbm {
namespace {

void check_options(const FollowingFrameOptions& o, const Damping& damping) {
  check_newmark_parameters(o.beta, o.gamma);
  if (!(o.frame_tolerance > 0 && o.frame_tolerance < 1e-3))
    throw InputError("frame tolerance: " + std::to_string(o.frame_tolerance) +
                     ", expected a value in (0, 1e-3)");
  if (o.max_frame_iterations < 1)
    throw InputError("frame iterations: " + std::to_string(o.max_frame_iterations) +
                     ", expected at least 1");
  if (damping.has_matrix())
    throw InputError("damping matrix: a contact frame that follows the body takes Rayleigh "
                     "damping only (rayleighM, rayleighK)");
}

// Row k of a positions matrix as a point (no heap: called per node and
// frame iteration).
Eigen::Vector3d point(const Matrix& p, Index k) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (Index j = 0; j < p.cols(); ++j) x(j) = p(k, j);
  return x;
}

}  // namespace

FollowingFrameStepper::FollowingFrameStepper(const ContactProblem& problem,
                                             const SparseMatrix& M_user, const Matrix& positions,
                                             std::shared_ptr<const RigidObstacle> obstacle,
                                             double dt, const FollowingFrameOptions& options,
                                             const Damping& damping)
    : Stepper(problem, dt, damping),
      obstacle_(std::move(obstacle)),
      options_(options),
      n_c_(problem.n_contact()),
      d_(problem.contacts().dim()) {
  check_options(options_, damping);
  if (!obstacle_) throw InputError("obstacle: none given");
  if (obstacle_->dim() != d_)
    throw InputError("obstacle: dimension " + std::to_string(obstacle_->dim()) +
                     ", expected " + std::to_string(d_) + " (the contact nodes' dofs)");
  if (positions.rows() != problem.n_dofs() || positions.cols() != d_)
    throw InputError("positions: " + std::to_string(positions.rows()) + " x " +
                     std::to_string(positions.cols()) + ", expected " +
                     std::to_string(problem.n_dofs()) + " x " + std::to_string(d_) +
                     " (the coordinates of every dof's node)");
  // The redistribution rejects a rotated problem (its M' would depend on the
  // normals).
  M_ = redistributed_mass(problem, M_user, positions, MasslessPart::kAllComponents);
  C_ = damping_matrix(damping, M_, problem.K());

  const ContactSet& contacts = problem.contacts();
  node_dofs_.resize(n_c_ * d_);
  X_.resize(n_c_, d_);
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) {
      node_dofs_[k * d_ + j] = problem.internal_index(contacts.dof(k, j));
      X_(k, j) = positions(contacts.dof(k, j), j);
    }
  // The nodes outside the contact set, watched for crossings: the free dofs
  // grouped by position, d per node, components in the order of their dofs.
  {
    std::vector<char> skip(problem.n_dofs(), 0);
    for (Index k = 0; k < n_c_; ++k)
      for (int j = 0; j < d_; ++j) skip[contacts.dof(k, j)] = 1;
    std::vector<Index> order;
    for (Index i = 0; i < problem.n_dofs(); ++i)
      if (!skip[i] && problem.internal_index(i) >= 0) order.push_back(i);
    const auto row_less = [&](Index a, Index b) {
      for (int j = 0; j < d_; ++j)
        if (positions(a, j) != positions(b, j)) return positions(a, j) < positions(b, j);
      return a < b;
    };
    std::sort(order.begin(), order.end(), row_less);
    std::vector<std::vector<Index>> nodes;
    for (std::size_t a = 0; a < order.size();) {
      std::size_t b = a + 1;
      while (b < order.size() && positions.row(order[b]) == positions.row(order[a])) ++b;
      if (static_cast<int>(b - a) == d_) nodes.emplace_back(order.begin() + a, order.begin() + b);
      a = b;
    }
    watch_X_.resize(static_cast<Index>(nodes.size()), d_);
    for (std::size_t w = 0; w < nodes.size(); ++w)
      for (int j = 0; j < d_; ++j) {
        watch_dofs_.push_back(problem.internal_index(nodes[w][j]));
        watch_X_(static_cast<Index>(w), j) = positions(nodes[w][j], j);
      }
  }
  watch_at_ = watch_X_;
  watch_phi_ = Vector::Constant(watch_X_.rows(), -1.0);  // none evaluated yet
  size_ = (positions.colwise().maxCoeff() - positions.colwise().minCoeff()).norm();
  if (!(size_ > 0)) size_ = 1;

  // S = M' + gamma dt C + beta dt^2 K (method.md §5, §9).
  SparseMatrix S = M_ + (options_.beta * dt * dt) * problem.K();
  if (damped()) S += (options_.gamma * dt) * C_;
  std::vector<Triplet> e;
  for (Index i = 0; i < n_c_ * d_; ++i) e.emplace_back(node_dofs_[i], i, 1.0);
  SparseMatrix E(problem.size(), n_c_ * d_);
  E.setFromTriplets(e.begin(), e.end());
  // Factored for the solves with the columns E_N (every component of the
  // contact nodes: the frame turns with them).
  S_ = problem.factorizer().factor(S, "M' + gamma dt C + beta dt^2 K (massless contact nodes)", E);
  // Y = L^-1 P E_N kept where it is small next to L (as the massless step of
  // method.md §5 does): a step is then one substitution each way plus the
  // products with Y, instead of two whole solves.
  keep_columns_ = keeps_contact_columns(options_.columns, *S_, E);
  if (keep_columns_)
    Y_ = S_->forward(E, &Z_);
  else
    Z_ = S_->gram(E);

  // K_NN (sparse: the contact nodes couple to their neighbours on the
  // boundary) for the start's static relation and the rates of the nodes.
  std::vector<Index> position_in_N(problem.size(), -1);
  for (Index i = 0; i < n_c_ * d_; ++i) position_in_N[node_dofs_[i]] = i;
  std::vector<Triplet> k_nn;
  for (Index j = 0; j < n_c_ * d_; ++j)
    for (SparseMatrix::InnerIterator it(problem.K(), node_dofs_[j]); it; ++it)
      if (const Index i = position_in_N[it.row()]; i >= 0)
        k_nn.emplace_back(static_cast<int>(i), static_cast<int>(j), it.value());
  K_NN_matrix_.resize(n_c_ * d_, n_c_ * d_);
  K_NN_matrix_.setFromTriplets(k_nn.begin(), k_nn.end());
  K_NN_.compute(K_NN_matrix_);
  // K_N: the rows of the contact nodes' dofs (K symmetric: its columns).
  std::vector<Triplet> k_n;
  for (Index i = 0; i < n_c_ * d_; ++i)
    for (SparseMatrix::InnerIterator it(problem.K(), node_dofs_[i]); it; ++it)
      k_n.emplace_back(static_cast<int>(i), static_cast<int>(it.row()), it.value());
  K_N_.resize(n_c_ * d_, problem.size());
  K_N_.setFromTriplets(k_n.begin(), k_n.end());
  if (K_NN_.info() != Eigen::Success)
    throw NumericalError("K: its block of the contact nodes is not positive definite (a "
                         "contact node moves freely when all others are held)");
  lambda_.setZero(n_c_);
  normals_.setZero(n_c_, d_);
  open_guess_.assign(n_c_, true);
  active_.assign(n_c_, false);
}

void FollowingFrameStepper::positions_of(const Vector& u, Matrix& p) const {
  p = X_;
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) p(k, j) += u(node_dofs_[k * d_ + j]);
}

void FollowingFrameStepper::place_nodes(const Matrix& p, Vector& u) const {
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) u(node_dofs_[k * d_ + j]) = p(k, j) - X_(k, j);
}

int FollowingFrameStepper::solve_frame(const Matrix& p_free, const Matrix* Z, double scale,
                                       double t, Matrix& p) {
  int iterations = 0;
  const Index m = n_c_ * d_;
  q_.resize(n_c_);
  shift_.resize(m);
  // The LCP runs on the candidates only: the nodes closed before and those
  // the step would bring into the obstacle. A node left out has lambda = 0
  // and must end with a gap >= 0 under the candidates' forces, which is
  // checked; any that does not joins them and the LCP is solved again, so
  // the result is the LCP's on all nodes, at a cost that grows with the
  // candidates, not with n_c (header).
  // Both the candidates and the LCP's warm start come from the state's
  // closed contacts (active_), so that a restored state steps on bit for bit.
  candidate_.resize(n_c_);
  for (Index k = 0; k < n_c_; ++k) {
    candidate_[k] = active_[k];
    open_guess_[k] = !active_[k];
  }
  double last_move = std::numeric_limits<double>::infinity();
  const double tolerance = options_.frame_tolerance * size_;
  for (int it = 0; it < options_.max_frame_iterations; ++it) {
    ++iterations;
    // The obstacle linearised at p: normal n_k, gap h_k (method.md §8, §10).
    for (Index k = 0; k < n_c_; ++k) {
      const Eigen::Vector3d x = point(p, k);
      const ObstaclePoint o = obstacle_->at(x.data(), t);
      const double g = o.grad.norm();
      if (!(g > 0) || !std::isfinite(o.phi))
        throw NumericalError("obstacle (" + obstacle_->describe() + "): no normal at contact node " +
                             std::to_string(k) + " (zero or non-finite gradient)");
      for (int j = 0; j < d_; ++j) normals_(k, j) = -o.grad(j) / g;
      q_(k) = o.phi / g - normals_.row(k).dot(p_free.row(k) - p.row(k));
      if (q_(k) <= 0) candidate_[k] = 1;
    }
    LcpResult lcp;
    for (bool grown = true; grown;) {
      C_nodes_.clear();
      for (Index k = 0; k < n_c_; ++k)
        if (candidate_[k]) C_nodes_.push_back(k);
      const Index c = static_cast<Index>(C_nodes_.size());
      // Z N_C and N_C' Z N_C with N block diagonal: d m c and d c^2 work.
      ZN_.resize(m, c);
      A_.resize(c, c);
      q_C_.resize(c);
      guess_.resize(c);
      for (Index b = 0; b < c; ++b) {
        const Index node = C_nodes_[b];
        if (Z) {
          ZN_.col(b).noalias() = Z->middleCols(node * d_, d_) * normals_.row(node).transpose();
        } else {  // the start only: K_NN^-1 N e_b, one column
          e_N_.setZero(m);
          e_N_.segment(node * d_, d_) = normals_.row(node).transpose();
          ZN_.col(b) = K_NN_.solve(e_N_);
        }
        q_C_(b) = q_(node);
        guess_[b] = open_guess_[node];
      }
      for (Index a = 0; a < c; ++a)
        for (Index b = 0; b < c; ++b)
          A_(a, b) = scale * normals_.row(C_nodes_[a]).dot(ZN_.col(b).segment(C_nodes_[a] * d_, d_));
      for (Index a = 0; a < c; ++a)  // symmetric to the last bit
        for (Index b = a + 1; b < c; ++b) A_(a, b) = A_(b, a) = 0.5 * (A_(a, b) + A_(b, a));
      lcp = c > 0 ? LcpSolver::solve(A_, q_C_, guess_) : LcpResult{};
      shift_.setZero();
      if (c > 0) shift_.noalias() = scale * (ZN_ * lcp.z);
      grown = false;
      for (Index k = 0; k < n_c_; ++k)
        if (!candidate_[k] && q_(k) + normals_.row(k).dot(shift_.segment(k * d_, d_)) < 0)
          candidate_[k] = 1, grown = true;
    }
    // lcp.active: z = lambda = 0 (open contacts), the warm start of the
    // next iteration and step.
    lambda_.setZero(n_c_);
    std::fill(open_guess_.begin(), open_guess_.end(), true);
    for (std::size_t b = 0; b < C_nodes_.size(); ++b) {
      lambda_(C_nodes_[b]) = lcp.z(b);
      open_guess_[C_nodes_[b]] = lcp.active[b];
    }
    double move = 0;
    for (Index k = 0; k < n_c_; ++k)
      for (int j = 0; j < d_; ++j) {
        const double next = p_free(k, j) - shift_(k * d_ + j);
        move = std::max(move, std::abs(next - p(k, j)));
        p(k, j) = next;
      }
    if (move <= tolerance) return iterations;
    // Round-off floor: the update stopped shrinking well below the body
    // size, so the linearisation point is as good as the arithmetic allows.
    if (it > 1 && move >= last_move && move <= 1e3 * tolerance) return iterations;
    last_move = move;
  }
  throw NumericalError("contact frame: no fixed point of the obstacle's normals in " +
                       std::to_string(options_.max_frame_iterations) + " iterations at t = " +
                       std::to_string(t) + " (" + obstacle_->describe() +
                       "); a smaller dt follows the obstacle more closely");
}

void FollowingFrameStepper::start(const ContactLoad& load) {
  // Against the true obstacle: every contact node outside it (a state a run
  // reached, continued under a new contact set, may bring nodes that crossed
  // it: they are pushed out by the relation below).
  Matrix p0;
  positions_of(u_, p0);
  for (Index k = 0; k < n_c_ && fresh_start(); ++k) {
    const Eigen::Vector3d x = point(p0, k);
    const double phi = obstacle_->at(x.data(), t_).phi;
    if (phi < -options_.frame_tolerance * size_)
      throw InputError("u: initial penetration at contact node " + std::to_string(k) +
                       " (distance " + std::to_string(phi) + " to the " + obstacle_->describe() +
                       ")");
  }
  // u_N from the static relation at u_O: K_NN u_N = (F - K u)_N + K_NN u_N - N lambda.
  const Vector r = load.F - problem_.K() * u_;
  Vector free_shift(n_c_ * d_);
  for (Index i = 0; i < n_c_ * d_; ++i) free_shift(i) = r(node_dofs_[i]);
  free_shift = K_NN_.solve(free_shift).eval();
  Matrix p = p0, p_free = p0;
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) p_free(k, j) += free_shift(k * d_ + j);
  std::fill(active_.begin(), active_.end(), false);
  solve_frame(p_free, nullptr, 1.0, t_, p);
  place_nodes(p, u_);
  for (Index k = 0; k < n_c_; ++k) active_[k] = lambda_(k) != 0;
  // a_O = M_OO^-1 (F - K u - C v)_O; the massless nodes' a_N are Newmark's
  // own (they carry no inertia and do not enter the next step's positions).
  Vector rhs = load.F - problem_.K() * u_;
  if (damped()) rhs -= C_ * v_;
  SparseMatrix M_reg = M_;
  for (Index i : node_dofs_) {
    M_reg.coeffRef(i, i) += 1.0;
    rhs(i) = 0;
  }
  a_ = solve_mass(M_reg, rhs, "M' (interior block)");
  if (!damped()) boundary_rates(t_);
}

double FollowingFrameStepper::obstacle_power(const Vector& lambda, const Vector& u, double t) const {
  // -lambda . g'(t), g' = (d phi / dt) / |grad phi| at each node (method.md §8).
  if (obstacle_->fixed()) return 0;
  double power = 0;
  for (Index k = 0; k < n_c_; ++k) {
    if (lambda(k) == 0) continue;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int j = 0; j < d_; ++j) x(j) = X_(k, j) + u(node_dofs_[k * d_ + j]);
    const ObstaclePoint o = obstacle_->at(x.data(), t);
    power -= lambda(k) * o.phi_t / o.grad.norm();
  }
  return power;
}

StepReport FollowingFrameStepper::advance(const ContactLoad& next) {
  const double dt = dt_, bdt2 = options_.beta * dt * dt;
  const double t1 = t_ + dt;
  const double power_before = obstacle_power(lambda_, u_, t_);

  u_hat_ = u_ + dt * v_ + (dt * dt * (0.5 - options_.beta)) * a_;
  v_pred_ = v_ + (dt * (1 - options_.gamma)) * a_;
  Vector& a = accel_;  // the new acceleration, built in place
  a = next.F;
  a.noalias() -= problem_.K() * u_hat_;
  if (damped()) a.noalias() -= C_ * v_pred_;
  // The free step's acceleration on the contact nodes, (S^-1 r)_N: Y' y with
  // y = L^-1 P r, or from the whole solve.
  free_N_.resize(n_c_ * d_);
  if (keep_columns_) {
    S_->forward_in_place(a);
    free_N_.noalias() = Y_.transpose() * a;
  } else {
    S_->solve_in_place(a);
    for (Index i = 0; i < n_c_ * d_; ++i) free_N_(i) = a(node_dofs_[i]);
  }
  positions_of(u_hat_, p_free_);
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) p_free_(k, j) += bdt2 * free_N_(k * d_ + j);
  // The frame starts where the nodes are now.
  positions_of(u_, p_);
  StepReport report;
  report.active_set_iterations = solve_frame(p_free_, &Z_, bdt2, t1, p_);
  // a = S^-1 (r - E_N N lambda).
  force_.resize(n_c_ * d_);
  for (Index k = 0; k < n_c_; ++k)
    for (int j = 0; j < d_; ++j) force_(k * d_ + j) = lambda_(k) * normals_(k, j);
  const bool pressed = (lambda_.array() != 0.0).any();
  if (keep_columns_) {
    if (pressed) a.noalias() -= Y_ * force_;
    S_->backward_in_place(a);
  } else if (pressed) {
    correction_.setZero(problem_.size());
    for (Index i = 0; i < n_c_ * d_; ++i) correction_(node_dofs_[i]) = -force_(i);
    S_->solve_in_place(correction_);
    a += correction_;
  }
  u_ = u_hat_ + bdt2 * a;
  v_ = v_pred_ + (options_.gamma * dt) * a;
  a_.swap(a);  // accel_: a workspace again
  // Closed contacts onto the surface: one Newton step along the gradient
  // removes the solves' round-off (the frame iteration's own error is
  // already of second order in its last update).
  for (Index k = 0; k < n_c_; ++k) {
    active_[k] = lambda_(k) != 0;
    if (!active_[k]) continue;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int j = 0; j < d_; ++j) x(j) = X_(k, j) + u_(node_dofs_[k * d_ + j]);
    const ObstaclePoint o = obstacle_->at(x.data(), t1);
    const double g2 = o.grad.squaredNorm();
    for (int j = 0; j < d_; ++j) u_(node_dofs_[k * d_ + j]) -= o.phi * o.grad(j) / g2;
  }
  add_obstacle_work(0.5 * dt * (power_before + obstacle_power(lambda_, u_, t1)));
  if (!damped()) boundary_rates(t1);
  report.crossings = count_crossings(t1);
  return report;
}

void FollowingFrameStepper::prepare_closed_relation() {
  closed_.clear();
  for (Index k = 0; k < n_c_; ++k)
    if (active_[k]) closed_.push_back(k);
  const Index m = static_cast<Index>(closed_.size());
  if (m == 0) return;
  // K_NN^-1 N_A: one solve with a column per closed node (its normal).
  N_A_.setZero(n_c_ * d_, m);
  for (Index c = 0; c < m; ++c)
    N_A_.col(c).segment(closed_[c] * d_, d_) = normals_.row(closed_[c]).transpose();
  KN_ = K_NN_.solve(N_A_);
  G_.compute(N_A_.transpose() * KN_);
}

void FollowingFrameStepper::boundary_relation(Vector& x, const Vector& h) {
  // Free part: K_NN x_N = -(K_NO x_O) = K_NN x_N - (K x)_N, from the contact
  // rows of K alone (K_N: a few rows, not a product with the whole K).
  x_N_.resize(n_c_ * d_);
  for (Index i = 0; i < n_c_ * d_; ++i) x_N_(i) = x(node_dofs_[i]);
  r_N_.noalias() = K_NN_matrix_ * x_N_;
  r_N_.noalias() -= K_N_ * x;
  x_N_ = K_NN_.solve(r_N_);
  // Closed contacts: n_k . x_k = h_k, by a multiplier per closed node.
  const Index m = static_cast<Index>(closed_.size());
  if (m > 0) {
    b_.resize(m);
    for (Index a = 0; a < m; ++a)
      b_(a) = normals_.row(closed_[a]).dot(x_N_.segment(closed_[a] * d_, d_)) - h(closed_[a]);
    x_N_.noalias() -= KN_ * G_.solve(b_);
  }
  for (Index i = 0; i < n_c_ * d_; ++i) x(node_dofs_[i]) = x_N_(i);
}

void FollowingFrameStepper::boundary_rates(double t) {
  // d/dt phi(p(t), t) = 0 on a closed contact: n . v = phi_t / |grad phi|;
  // twice: n . a = (phi_tt + 2 grad phi_t . v + v' H v) / |grad phi|, the
  // second derivatives by central differences of the obstacle (H v along v).
  Vector& h_v = h_v_;
  Vector& h_a = h_a_;
  h_v.setZero(n_c_);
  h_a.setZero(n_c_);
  Matrix& p = p_now_;
  positions_of(u_, p);
  const double step = 1e-6 * size_;
  for (Index k = 0; k < n_c_; ++k) {
    if (!active_[k]) continue;
    const Eigen::Vector3d x = point(p, k);
    const ObstaclePoint o = obstacle_->at(x.data(), t);
    const double g = o.grad.norm();
    for (int j = 0; j < d_; ++j) normals_(k, j) = -o.grad(j) / g;
    h_v(k) = o.phi_t / g;
  }
  prepare_closed_relation();  // the normals at u_, for v and a alike
  boundary_relation(v_, h_v);
  for (Index k = 0; k < n_c_; ++k) {
    if (!active_[k]) continue;
    const Eigen::Vector3d x = point(p, k);
    Eigen::Vector3d vk = Eigen::Vector3d::Zero();
    for (int j = 0; j < d_; ++j) vk(j) = v_(node_dofs_[k * d_ + j]);
    const double speed = vk.norm();
    double curvature_term = 0;
    if (speed > 0) {
      const Eigen::Vector3d e = vk / speed;
      const Eigen::Vector3d xp = x + step * e, xm = x - step * e;
      const ObstaclePoint op = obstacle_->at(xp.data(), t), om = obstacle_->at(xm.data(), t);
      // v' H v + 2 grad phi_t . v with grad phi_t . e = (phi_t(x+) - phi_t(x-)) / 2 step.
      curvature_term = speed * speed * (op.grad - om.grad).dot(e) / (2 * step) +
                       2 * speed * (op.phi_t - om.phi_t) / (2 * step);
    }
    double phi_tt = 0;
    if (!obstacle_->fixed()) {
      const double tau = 1e-6 * std::max(1.0, std::abs(t));
      phi_tt = (obstacle_->at(x.data(), t + tau).phi_t - obstacle_->at(x.data(), t - tau).phi_t) /
               (2 * tau);
    }
    const ObstaclePoint o = obstacle_->at(x.data(), t);
    h_a(k) = (phi_tt + curvature_term) / o.grad.norm();
  }
  boundary_relation(a_, h_a);
}

int FollowingFrameStepper::count_crossings(double t) {
  int crossings = 0;
  const double tolerance = options_.frame_tolerance * size_;
  // A fixed signed distance bounds itself: a node that was at distance
  // phi_w from the obstacle at x_w cannot be inside it while it is nearer
  // than phi_w to x_w, whatever happened since (restarts included), so
  // phi is evaluated only when a node has moved that far (method.md §10).
  const bool bounded = obstacle_->fixed() && obstacle_->is_distance();
  for (Index w = 0; w < watch_X_.rows(); ++w) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    double moved2 = 0;
    for (int j = 0; j < d_; ++j) {
      x(j) = watch_X_(w, j) + u_(watch_dofs_[w * d_ + j]);
      moved2 += (x(j) - watch_at_(w, j)) * (x(j) - watch_at_(w, j));
    }
    if (bounded && watch_phi_(w) > 0 && moved2 < watch_phi_(w) * watch_phi_(w)) continue;
    const double phi = obstacle_->at(x.data(), t).phi;
    watch_phi_(w) = phi;
    for (int j = 0; j < d_; ++j) watch_at_(w, j) = x(j);
    if (phi < -tolerance) ++crossings;
  }
  return crossings;
}

Vector FollowingFrameStepper::gaps() const {
  Matrix p;
  positions_of(u_, p);
  Vector phi(n_c_);
  for (Index k = 0; k < n_c_; ++k) {
    const Eigen::Vector3d x = point(p, k);
    phi(k) = obstacle_->at(x.data(), t_).phi;
  }
  return phi;
}

Matrix FollowingFrameStepper::normals() const {
  Matrix p;
  positions_of(u_, p);
  Matrix n(n_c_, d_);
  for (Index k = 0; k < n_c_; ++k) {
    const Eigen::Vector3d x = point(p, k);
    const ObstaclePoint o = obstacle_->at(x.data(), t_);
    for (int j = 0; j < d_; ++j) n(k, j) = -o.grad(j) / o.grad.norm();
  }
  return n;
}



}  // namespace nbm
