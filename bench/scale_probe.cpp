// One case of issue 14's scale benchmarks (bench/bench_step.cpp, BM_Scale*)
// in one process, phase by phase, for the figures of bench/why-scale.md that
// the benchmarks do not print: the setup and initialize() apart, the time of
// every step of the sweep, and trajectories compared between versions of the
// core (bench/trajectory.hpp).
//   nbm_scale_probe BODY ORDER DOFS PCT SCHEME [STEPS [TRAJECTORY]] [--free] [--no-plain]
// BODY 0 plate, 1 strip, 2 block; PCT as BM_Scale* (6 ... 100, 200: two
// faces); SCHEME newmark (mass on the contact nodes), massless or explicit;
// STEPS of the sweep (default 20, the benchmarks'); --free: the obstacle out
// of reach (free flight); --no-plain: no plain factorization and step (the
// ratios are then not printed; the 1e6-dof block cannot hold both);
// --mumps: both sides factored by MUMPS instead of CHOLMOD, on the ranks of
// mpirun -np N (method.md §4), with MUMPS's estimates of the iteration
// matrix's factorization and every rank's peak resident size; --estimate:
// MUMPS's estimates only, no factorization (bench/mumps-scale.sh projects
// from them), with the order nbm gives MUMPS and with MUMPS's own.
// Wall-clock times (OpenBLAS's threads work for both sides).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_problem.hpp"
#include "linalg/mpi_ranks.hpp"
#include "linalg/mumps_inverse.hpp"
#include "measure.hpp"
#include "plain_step.hpp"
#include "scale_case.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/newmark_stepper.hpp"
#include "trajectory.hpp"

namespace {

using nbm::Index;
using nbm::Vector;

constexpr double kImplicitDt = 2e-4, kFreeGap = 1e6;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The plain step (plain_step.hpp), what the benchmarks' ratios divide by,
// and (implicit) the time of the factorization.
double plain_step_seconds(const nbm_bench::Case& c, bool explicit_scheme, double dt,
                          const nbm::SparseFactorizer& factorizer, double* factorization) {
  const int steps = 10;
  if (explicit_scheme) {
    nbm_bench::PlainCentralDifference plain(c.a, c.a.M * Vector::Ones(c.a.M.rows()), dt);
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) plain.step();
    return seconds_since(start) / steps;
  }
  auto start = std::chrono::steady_clock::now();
  const auto S = factorizer.factor(c.a.M + (0.25 * dt * dt) * c.a.K, "S");
  *factorization = seconds_since(start);
  nbm_bench::PlainNewmark plain(*S, c.a, dt);
  start = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) plain.step();
  return seconds_since(start) / steps;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<const char*> args;
  bool free_flight = false, plain = true, mumps = false, estimate = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--free") == 0)
      free_flight = true;
    else if (std::strcmp(argv[i], "--mumps") == 0)
      mumps = true;
    else if (std::strcmp(argv[i], "--estimate") == 0)
      mumps = estimate = true;
    else if (std::strcmp(argv[i], "--no-plain") == 0)
      plain = false;
    else
      args.push_back(argv[i]);
  }
  if (args.size() < 5 || args.size() > 7) {
    std::fprintf(stderr,
                 "usage: %s BODY ORDER DOFS PCT newmark|massless|explicit [STEPS [TRAJECTORY]] "
                 "[--free] [--no-plain] [--mumps] [--estimate]\n",
                 argv[0]);
    return 2;
  }
  const int body = std::atoi(args[0]), order = std::atoi(args[1]), pct = std::atoi(args[3]);
  const std::string scheme = args[4];
  const int steps = args.size() > 5 ? std::atoi(args[5]) : nbm_bench::kSweepSteps;
  if (scheme != "newmark" && scheme != "massless" && scheme != "explicit") {
    std::fprintf(stderr, "scheme: %s, expected newmark, massless or explicit\n", scheme.c_str());
    return 2;
  }
  const bool explicit_scheme = scheme == "explicit";
  const nbm_bench::Case c = nbm_bench::assemble_body(body, order, std::atof(args[2]));
  const double dt = explicit_scheme
                        ? nbm_bench::explicit_dt(c.a.K, c.a.M * Vector::Ones(c.a.M.rows()))
                        : kImplicitDt;
  const nbm::SparseFactorizer factorizer(mumps ? nbm::SparseSolver::kMumps
                                               : nbm::SparseSolver::kCholmod);
  const int rank = mumps ? nbm::mpi_rank(nbm::mpi_world()) : 0;
  const int ranks = mumps ? nbm::mpi_size(nbm::mpi_world()) : 1;
  nbm_bench::ContactRegion region = nbm_bench::sweeping(nbm_bench::scale_region(pct), c.X, dt);
  if (free_flight) region.gap = kFreeGap;
  const nbm::ContactDescription d = nbm_bench::contact_on(c.X, region);
  if (mumps) {
    // The iteration matrix condensed on the contact dofs, as the massless
    // boundary's stepper factors it (the paper's NBM adds their neighbours).
    std::vector<Index> schur(d.dofs.begin(), d.dofs.end());
    std::sort(schur.begin(), schur.end());
    const nbm::SparseMatrix S = c.a.M + (0.25 * dt * dt) * c.a.K;
    for (const auto ordering : {nbm::MumpsOrdering::kFillReducing, nbm::MumpsOrdering::kMumpsOwn}) {
      const auto start = std::chrono::steady_clock::now();
      const nbm::MumpsEstimate e =
          nbm::estimate_mumps_factorization(S, "S", schur, nbm::mpi_world(), ordering);
      if (rank == 0)
        std::printf("MUMPS %s on %d rank(s): dofs %ld, Schur variables %zu, factor entries "
                    "%.6g, flops %.6g, memory max %.0f MB, total %.0f MB (analysis %.3g s)\n",
                    ordering == nbm::MumpsOrdering::kFillReducing ? "estimate" : "own-order estimate",
                    ranks, static_cast<long>(c.a.K.rows()), schur.size(), e.factor_entries,
                    e.flops, e.memory_max_mb, e.memory_total_mb, seconds_since(start));
      if (!estimate) break;  // the comparison only with --estimate
    }
    if (estimate) {
      std::printf("rank %d: peak resident size %.0f MB\n", rank, nbm_bench::status_mb("VmHWM"));
      return 0;
    }
  }
  double factorization = 0, plain_step = 0;
  if (plain) plain_step = plain_step_seconds(c, explicit_scheme, dt, factorizer, &factorization);

  const double heap = nbm_bench::heap_mb();
  auto start = std::chrono::steady_clock::now();
  nbm::ContactProblem problem(
      c.a.M, c.a.K,
      nbm::ContactSet(c.a.K.rows(), {d.dofs.begin(), d.dofs.end()}, d.normals,
                      Eigen::Map<const Vector>(d.gaps.data(), static_cast<Index>(d.gaps.size()))),
      {}, scheme == "massless" ? &c.X : nullptr);
  problem.set_factorizer(factorizer);
  std::unique_ptr<nbm::Stepper> stepper;
  if (scheme == "newmark")
    stepper = std::make_unique<nbm::NewmarkStepper>(problem, dt);
  else if (scheme == "massless")
    stepper = std::make_unique<nbm::MasslessNewmarkStepper>(problem, dt);
  else
    stepper = std::make_unique<nbm::CentralDifferenceStepper>(problem, dt);
  const double setup = seconds_since(start);

  const Vector F = problem.to_internal(c.a.F), zero = Vector::Zero(problem.size());
  start = std::chrono::steady_clock::now();
  stepper->initialize(zero, problem.to_internal(nbm_bench::falling(c.X)), F);
  const double initialize = seconds_since(start);

  nbm_bench::Trajectory trajectory(args.size() > 6 ? args[6] : nullptr);
  std::vector<double> times;
  double all = 0, changing = 0;
  int changes = 0, solves = 0;
  for (int s = 0; s < steps; ++s) {
    const nbm::ActiveSet before = stepper->active();
    start = std::chrono::steady_clock::now();
    solves += stepper->step(F).active_set_iterations;
    const double t = seconds_since(start);
    times.push_back(t);
    all += t;
    if (stepper->active() != before) {
      changing += t;
      ++changes;
    }
    trajectory.record(stepper->u(), stepper->v(), stepper->a());
  }
  const double held = nbm_bench::heap_mb() - heap;

  std::printf("rank %d: peak resident size %.0f MB\n", rank, nbm_bench::status_mb("VmHWM"));
  if (rank > 0) return 0;  // the host prints the figures, which every rank holds
  std::printf("dofs %ld, contact nodes %ld, scheme %s%s, dt %.3g\n",
              static_cast<long>(c.a.K.rows()), static_cast<long>(problem.n_contact()),
              scheme.c_str(), free_flight ? " (free flight)" : "", dt);
  if (plain)
    std::printf("plain: %s %.4g s%s\n", explicit_scheme ? "explicit step" : "step", plain_step,
                explicit_scheme ? "" : (", factorization " + std::to_string(factorization) + " s").c_str());
  std::printf("setup %.4g s%s, initialize %.4g s, heap held %.1f MB\n", setup,
              plain && !explicit_scheme
                  ? (" (" + std::to_string(setup / factorization) + " factorizations)").c_str()
                  : "",
              initialize, held);
  std::printf("mean step %.4g s (%.2f plain), %d of %d steps change the set (mean %.4g s, "
              "%.2f plain), %.2f solves per step\n",
              all / steps, plain ? all / steps / plain_step : 0.0, changes, steps,
              changes > 0 ? changing / changes : 0.0,
              plain && changes > 0 ? changing / changes / plain_step : 0.0,
              static_cast<double>(solves) / steps);
  std::printf("step times (ms):");
  for (double t : times) std::printf(" %.1f", 1e3 * t);
  std::printf("\n|u| + |v| + |a| after %d steps: %.17g\n", steps,
              stepper->u().norm() + stepper->v().norm() + stepper->a().norm());
  if (trajectory.comparing())
    std::printf("largest difference from the recorded trajectory, relative: %.3g (%s)\n",
                trajectory.largest_difference(), trajectory.where().c_str());
  return 0;
}
