// What a contact frame that follows the body costs (method.md §10): a P1
// plate (bench/plate.hpp, cells of 0.02 x 0.02) whose bottom edge slides in a
// circular bowl of radius 2 W, released touching it at one corner, so that
// every contact node's normal changes at every step. Prints, in one process:
//   - the plain contact-free Newmark step (plain_step.hpp) and its factorization;
//   - the massless boundary with the bowl linearised once (fixed frame,
//     MasslessNewmarkStepper): setup and mean step;
//   - the same with the frame following the body (FollowingFrameStepper):
//     setup, mean step, frame iterations per step;
// and the ratios: following / fixed step (the target is 1.5 for n_c <= 500),
// following / fixed setup (target 1.3), each step / plain step. CPU times of
// this thread; run with OPENBLAS_NUM_THREADS=1.
//   nbm_frame_cost NX NY STEPS
//   OPENBLAS_NUM_THREADS=1 build/bench/nbm_frame_cost 400 40 50
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "contact/contact_problem.hpp"
#include "obstacle/rigid_obstacle.hpp"
#include "plain_step.hpp"
#include "plate.hpp"
#include "time/following_frame_stepper.hpp"
#include "time/massless_newmark_stepper.hpp"

namespace {

using nbm::Index;
using nbm::Vector;

constexpr double kDt = 1e-3;

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Mean CPU time of `step` over `steps` calls after two warm-up calls.
template <class Step>
double mean_step(Step&& step, int steps) {
  step();
  step();
  const double start = cpu_seconds();
  for (int s = 0; s < steps; ++s) step();
  return (cpu_seconds() - start) / steps;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s NX NY STEPS\n", argv[0]);
    return 2;
  }
  const nbm_bench::Plate p = nbm_bench::Plate::of_cells(std::atoi(argv[1]), std::atoi(argv[2]));
  const int steps = std::atoi(argv[3]);
  const nbm_bench::Assembled a = nbm_bench::assemble(p);
  const Eigen::MatrixXd X = nbm_bench::dof_positions(p);
  const Index n = a.K.rows();

  // The bowl: radius 2 W, centre at 0.4 W, high enough that every bottom node
  // is inside it; the farthest corner (x = W) touches.
  const double R = 2 * p.W, cx = 0.4 * p.W, cy = std::sqrt(R * R - 0.36 * p.W * p.W);
  const auto bowl = std::shared_ptr<const nbm::RigidObstacle>(
      nbm::make_ball(Eigen::Vector2d(cx, cy), R, nbm::Side::kInside));
  std::vector<Index> dofs;
  std::vector<double> normals, gaps;
  for (int i = 0; i < p.nodes_x(); ++i) {
    const Index node = p.node(i, 0);
    dofs.insert(dofs.end(), {2 * node, 2 * node + 1});
    const Eigen::Vector2d x = p.position(i, 0);
    const nbm::ObstaclePoint o = bowl->at(x.data(), 0);
    normals.insert(normals.end(), {-o.grad(0), -o.grad(1)});
    gaps.push_back(o.phi);
  }
  const Vector F = a.F, zero = Vector::Zero(n);

  double start = cpu_seconds();
  auto S = nbm::make_cholesky_inverse(a.M + (0.25 * kDt * kDt) * a.K, "S");
  const double factorization = cpu_seconds() - start;
  nbm_bench::PlainNewmark plain(*S, a, kDt);
  const double plain_step = mean_step([&] { plain.step(); }, steps);
  S.reset();

  // Fixed frame: the bowl linearised at the reference configuration.
  start = cpu_seconds();
  const nbm::ContactProblem fixed_problem(
      a.M, a.K, nbm::ContactSet(n, dofs, normals, Eigen::Map<const Vector>(gaps.data(), gaps.size())),
      {}, &X);
  nbm::MasslessNewmarkStepper fixed(fixed_problem, kDt);
  const double fixed_setup = cpu_seconds() - start;
  fixed.initialize(zero, zero, fixed_problem.to_internal(F));
  const Vector F_fixed = fixed_problem.to_internal(F);
  const double fixed_step = mean_step([&] { fixed.step(F_fixed); }, steps);

  // The frame following the plate.
  start = cpu_seconds();
  const nbm::ContactProblem follow_problem(a.M, a.K, nbm::ContactSet::in_user_axes(n, dofs, 2), {});
  nbm::FollowingFrameStepper follow(follow_problem, a.M, X, bowl, kDt);
  const double follow_setup = cpu_seconds() - start;
  follow.initialize(zero, zero, F);
  long iterations = 0;
  const double follow_step =
      mean_step([&] { iterations += follow.step(F).active_set_iterations; }, steps);
  int closed = 0;
  for (bool c : follow.active()) closed += c;

  std::printf("dofs %ld, contact nodes %ld (%d closed at the end), factorization %.4f s, "
              "plain step %.6f s\n",
              static_cast<long>(n), static_cast<long>(dofs.size() / 2), closed, factorization,
              plain_step);
  std::printf("fixed frame:     setup %.4f s (%.2f factorizations), step %.6f s (%.2f plain)\n",
              fixed_setup, fixed_setup / factorization, fixed_step, fixed_step / plain_step);
  std::printf("following frame: setup %.4f s (%.2f factorizations), step %.6f s (%.2f plain), "
              "%.2f frame iterations per step\n",
              follow_setup, follow_setup / factorization, follow_step, follow_step / plain_step,
              static_cast<double>(iterations) / (steps + 2));
  std::printf("following / fixed: step %.2f (target 1.5), setup %.2f (target 1.3)\n",
              follow_step / fixed_step, follow_setup / fixed_setup);
  return 0;
}
