// Many contact nodes and an active set that changes at every step (bench/why.md,
// "Many contact nodes"): a long P1 plate (bench/plate.hpp, cells of 0.02 x 0.02)
// falls at 1 m/s onto a ground tilted so that the contact front sweeps the
// bottom edge in about 100 steps of dt = 2e-4. With EDGES = 2 the top edge is
// a second contact boundary 1e6 away (never closed): twice the contact nodes,
// the same motion. Prints, for the NewmarkStepper, the setup (constructor),
// initialize() and the mean step that changes the active set, each against
// one factorization of M + dt^2/4 K or one plain contact-free Newmark step of
// the same matrices (as BM_PlainNewmarkStep), the mean free-flight step (the
// same start with the obstacle 1e6 away, before the run), and the heap its objects hold
// after the run against the plain factor's. Times are CPU times of this thread,
// so that other jobs on the machine perturb them less than wall times; run with
// OPENBLAS_NUM_THREADS=1. The last line, |u| + |v| + |a| at the end, compares
// trajectories between versions of the core; with a file TRAJECTORY, a first
// run writes u, v, a after every step there and a run with the file present
// reads them back and prints the largest difference from them, step by step
// relative to the recorded vector's largest entry.
//   nbm_contact_front NX NY EDGES STEPS [TRAJECTORY]
//   OPENBLAS_NUM_THREADS=1 build/bench/nbm_contact_front 500 50 2 60
#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "contact/contact_problem.hpp"
#include "plain_step.hpp"
#include "plate.hpp"
#include "time/newmark_stepper.hpp"
#include "trajectory.hpp"

namespace {

using nbm::Index;
using nbm::Vector;

constexpr double kDt = 2e-4, kSpeed = 1.0, kFirstGap = 1e-5, kNeverGap = 1e6;

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Heap in use (glibc), MB: what the objects made since a reading hold.
double heap_mb() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<double>(mi.uordblks + mi.hblkhd) / (1024.0 * 1024.0);
}

// Bottom nodes against the tilted ground (the gap grows along x so that the
// front crosses the plate's width W in 100 steps), then the top nodes if
// `edges` is 2.
nbm::ContactSet contact_edges(const nbm_bench::Plate& p, int edges, Index dofs) {
  const double slope = 100 * kDt * kSpeed / p.W;
  std::vector<Index> contact_dofs;
  std::vector<double> normals, gaps;
  for (int j : {0, p.nodes_y() - 1}) {
    if (j > 0 && edges < 2) break;
    for (int i = 0; i < p.nodes_x(); ++i) {
      const Index node = p.node(i, j);
      contact_dofs.insert(contact_dofs.end(), {2 * node, 2 * node + 1});
      normals.insert(normals.end(), {0.0, j == 0 ? -1.0 : 1.0});
      gaps.push_back(j == 0 ? kFirstGap + slope * p.position(i, j)(0) : kNeverGap);
    }
  }
  return nbm::ContactSet(dofs, contact_dofs, normals,
                         Eigen::Map<const Vector>(gaps.data(), static_cast<Index>(gaps.size())));
}

// Mean CPU time of the plain step (plain_step.hpp).
double plain_step_seconds(const nbm::CholeskyInverse& S, const nbm_bench::Assembled& a) {
  nbm_bench::PlainNewmark plain(S, a, kDt);
  const int steps = 50;
  const double start = cpu_seconds();
  for (int s = 0; s < steps; ++s) plain.step();
  return (cpu_seconds() - start) / steps;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5 && argc != 6) {
    std::fprintf(stderr, "usage: %s NX NY EDGES(1|2) STEPS [TRAJECTORY]\n", argv[0]);
    return 2;
  }
  const nbm_bench::Plate p = nbm_bench::Plate::of_cells(std::atoi(argv[1]), std::atoi(argv[2]));
  const int edges = std::atoi(argv[3]), steps = std::atoi(argv[4]);
  const nbm_bench::Assembled a = nbm_bench::assemble(p);
  const nbm::ContactProblem problem(a.M, a.K, contact_edges(p, edges, a.K.rows()), {});

  double heap = heap_mb(), start = cpu_seconds();
  auto S = nbm::make_cholesky_inverse(a.M + (0.25 * kDt * kDt) * a.K, "S");
  const double factorization = cpu_seconds() - start, plain_heap = heap_mb() - heap;
  const double plain_step = plain_step_seconds(*S, a);
  S.reset();

  heap = heap_mb();
  start = cpu_seconds();
  nbm::NewmarkStepper stepper(problem, kDt);
  const double setup = cpu_seconds() - start;
  const Vector F = problem.to_internal(a.F), zero = Vector::Zero(problem.size());
  Vector falling = zero;
  for (int i = 0; i < p.nodes_x(); ++i)
    for (int j = 0; j < p.nodes_y(); ++j)
      falling(problem.internal_index(2 * p.node(i, j) + 1)) = -kSpeed;
  // Free flight: the same start, the obstacle out of reach (every contact
  // open); the first steps fill the caches of that set.
  const nbm::Obstacle far = nbm::Obstacle::at_rest(
      problem.gaps() + Vector::Constant(problem.n_contact(), kNeverGap));
  const int free_steps = 20, free_warm = 2;
  stepper.initialize(zero, falling, nbm::ContactLoad{F, far});
  double free_flight = 0;
  for (int s = 0; s < free_steps; ++s) {
    start = cpu_seconds();
    stepper.step(F);
    if (s >= free_warm) free_flight += cpu_seconds() - start;
  }
  free_flight /= free_steps - free_warm;

  start = cpu_seconds();
  stepper.initialize(zero, falling, F);
  const double initialize = cpu_seconds() - start;
  nbm_bench::Trajectory trajectory(argc == 6 ? argv[5] : nullptr);
  double changing = 0;
  int changes = 0, solves = 0;
  for (int s = 0; s < steps; ++s) {
    const nbm::ActiveSet before = stepper.active();
    start = cpu_seconds();
    solves += stepper.step(F).active_set_iterations;
    const double t = cpu_seconds() - start;
    trajectory.record(stepper.u(), stepper.v(), stepper.a());
    if (stepper.active() != before) {
      changing += t;
      ++changes;
    }
  }
  const double held = heap_mb() - heap;

  std::printf("dofs %ld, contact nodes %ld, factorization %.4f s, plain step %.5f s\n",
              static_cast<long>(a.K.rows()), static_cast<long>(problem.n_contact()),
              factorization, plain_step);
  std::printf("setup / factorization            %.1f\n", setup / factorization);
  std::printf("initialize / factorization       %.1f\n", initialize / factorization);
  std::printf("changing step / plain step       %.1f (%d of %d steps, %.2f solves per step)\n",
              changes > 0 ? changing / changes / plain_step : 0.0, changes, steps,
              static_cast<double>(solves) / steps);
  std::printf("free flight / plain step         %.2f\n", free_flight / plain_step);
  std::printf("heap held / plain factor's       %.1f\n", held / plain_heap);
  std::printf("|u| + |v| + |a| after %d steps   %.17g\n", steps,
              stepper.u().norm() + stepper.v().norm() + stepper.a().norm());
  if (trajectory.comparing())
    std::printf("largest difference from the recorded trajectory, relative: %.3g (%s)\n",
                trajectory.largest_difference(), trajectory.where().c_str());
  return 0;
}
