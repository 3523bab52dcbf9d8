// Cost of NBM against the plain contact-free schemes, on the same plane-strain
// plate matrices (bench/plate.hpp), the same factorization library (CHOLMOD
// through nbm::make_cholesky_inverse) and in the same run:
//   Plain*            contact-free Newmark / central differences: the floor
//   Nbm*              the NBM steppers, in free flight (the plate far above
//                     the ground) and through bounces (active-set changes)
//   *Setup/*Factor    construction against one plain factorization
// Arguments: {order (1, 2), dofs}. Every benchmark reports the problem size,
// the contact nodes, the memory its solver objects hold (heap growth since
// the plate was assembled) and the peak resident memory of its
// process (VmHWM: meaningful when each benchmark runs in its own process, as
// bench/run.sh does).
#include <benchmark/benchmark.h>

#include <malloc.h>

#include <chrono>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "central_difference_stepper.hpp"
#include "contact_problem.hpp"
#include "mass_redistribution.hpp"
#include "massless_newmark_stepper.hpp"
#include "newmark_stepper.hpp"
#include "plate.hpp"

namespace {

using nbm::Index;
using nbm::Vector;
using nbm_bench::Plate;

// Bouncing runs: the plate starts kBounceGap above the ground (fall 0.014)
// and is restarted after kBounceWindow (the impact lasts about 2 H / c_p =
// 0.027): every timed run covers whole windows of fall, impact and rebound.
constexpr double kBounceGap = 1e-3, kBounceWindow = 0.05, kImplicitDt = 2e-4;
constexpr int kWindowSteps = 250;
constexpr double kFreeGap = 1e6;  // never reached: free flight

// A field of /proc/self/status in MB (VmHWM: peak resident size).
double status_mb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == field + ":") {
      double kb;
      status >> kb;
      return kb / 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0;
}

struct Case {
  Plate plate;
  nbm_bench::Assembled a;
};

const Case& plate_case(const benchmark::State& state) {
  static std::map<std::pair<int, int>, std::unique_ptr<Case>> cache;
  const int order = static_cast<int>(state.range(0)), dofs = static_cast<int>(state.range(1));
  auto& c = cache[{order, dofs}];
  if (!c) {
    c = std::make_unique<Case>();
    c->plate = Plate::with_dofs(order, dofs);
    c->a = nbm_bench::assemble(c->plate);
  }
  return *c;
}

/// The plate's contact problem; with the massless boundary if `massless`.
nbm::ContactProblem make_problem(const Case& c, double gap, bool massless = false) {
  const nbm::ContactDescription d = nbm_bench::bottom_contact(c.plate, gap);
  nbm::ContactSet set(c.a.K.rows(), {d.dofs.begin(), d.dofs.end()}, d.normals,
                      Eigen::Map<const Vector>(d.gaps.data(), d.gaps.size()));
  const nbm::Matrix X = massless ? nbm_bench::dof_positions(c.plate) : nbm::Matrix();
  return nbm::ContactProblem(c.a.M, c.a.K, std::move(set), {}, massless ? &X : nullptr);
}

// Heap in use (glibc: small blocks and mmapped ones), in MB. Freed memory is
// reused without a change of the resident size, so the heap, not the RSS,
// measures what solver objects hold.
double heap_mb() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<double>(mi.uordblks + mi.hblkhd) / (1024.0 * 1024.0);
}

// Heap in use once the problem is assembled: what a benchmark's solver
// objects hold is the heap at report() time minus this.
double heap_after_assembly = 0;

const Case& plate_case_measured(const benchmark::State& state) {
  const Case& c = plate_case(state);
  heap_after_assembly = heap_mb();
  return c;
}

// Call while the solver objects are alive.
void report(benchmark::State& state, const Case& c, long contacts) {
  state.counters["dofs"] = c.a.K.rows();
  state.counters["contacts"] = static_cast<double>(contacts);
  state.counters["peak_rss_MB"] = status_mb("VmHWM");
  state.counters["held_MB"] = heap_mb() - heap_after_assembly;
}

// ------------------------------------------------------------ plain schemes

// Contact-free average-acceleration Newmark: one solve with M + dt^2/4 K.
void BM_PlainNewmarkStep(benchmark::State& state) {
  const Case& c = plate_case_measured(state);
  const double dt = kImplicitDt, bdt2 = 0.25 * dt * dt;
  const auto S = nbm::make_cholesky_inverse(c.a.M + bdt2 * c.a.K, "S");
  const Index n = c.a.K.rows();
  Vector u = Vector::Zero(n), v = Vector::Zero(n), a = Vector::Zero(n), r(n), u_pred(n), a_new(n);
  for (auto _ : state) {
    u_pred = u + dt * v + bdt2 * a;
    r.noalias() = c.a.M * u_pred;
    r += bdt2 * c.a.F;
    S->solve_in_place(r);
    a_new = (r - u_pred) / bdt2;
    v += (0.5 * dt) * (a + a_new);
    a.swap(a_new);
    u.swap(r);
    benchmark::DoNotOptimize(u.data());
  }
  report(state, c, 0);
}

// Contact-free central differences with the row-sum lumped mass.
void BM_PlainExplicitStep(benchmark::State& state) {
  const Case& c = plate_case_measured(state);
  const Vector m = c.a.M * Vector::Ones(c.a.M.rows());
  const double dt = 0.5 * 2 / std::sqrt(nbm::max_eigenvalue(c.a.K, m));
  const Index n = c.a.K.rows();
  Vector u = Vector::Zero(n), v = Vector::Zero(n), a = c.a.F.cwiseQuotient(m), a_new(n);
  for (auto _ : state) {
    u += dt * v + (0.5 * dt * dt) * a;
    a_new.noalias() = c.a.F - c.a.K * u;
    a_new.array() /= m.array();
    v += (0.5 * dt) * (a + a_new);
    a.swap(a_new);
    benchmark::DoNotOptimize(u.data());
  }
  report(state, c, 0);
}

void BM_PlainFactorization(benchmark::State& state) {
  const Case& c = plate_case_measured(state);
  const nbm::SparseMatrix S = c.a.M + (0.25 * kImplicitDt * kImplicitDt) * c.a.K;
  for (auto _ : state) benchmark::DoNotOptimize(nbm::make_cholesky_inverse(S, "S").get());
  report(state, c, 0);
}

// -------------------------------------------------------------- NBM schemes

// Runs `stepper` from rest `gap` above the ground, restarting (untimed) every
// `window` of simulated time, and counts the steps whose active set changed.
// The first step is taken before the timing and reported on its own
// (first_step_us): it factors the dense blocks of the initial active set
// once, a start-up cost, not the cost per step of a run.
void run_steps(benchmark::State& state, const nbm::ContactProblem& problem, nbm::Stepper& stepper,
               double window) {
  const Vector F = problem.to_internal(plate_case(state).a.F);
  const Vector zero = Vector::Zero(problem.size());
  stepper.initialize(zero, zero, F);
  const auto start = std::chrono::steady_clock::now();
  stepper.step(F);
  state.counters["first_step_us"] =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  long switches = 0, iterations = 0;
  for (auto _ : state) {
    if (stepper.time() > window) {
      state.PauseTiming();
      stepper.initialize(zero, zero, F);
      state.ResumeTiming();
    }
    const nbm::ActiveSet before = stepper.active();
    iterations += stepper.step(F).active_set_iterations;
    switches += stepper.active() != before;
  }
  state.counters["switch_steps"] = benchmark::Counter(switches, benchmark::Counter::kAvgIterations);
  state.counters["solves_per_step"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

// One NBM benchmark: the plate in free flight or bouncing, with the
// consistent or the redistributed mass, stepped by what `make` builds.
template <bool Bouncing, class Make>
void nbm_steps(benchmark::State& state, bool massless, Make make) {
  const Case& c = plate_case_measured(state);
  const nbm::ContactProblem problem = make_problem(c, Bouncing ? kBounceGap : kFreeGap, massless);
  const std::unique_ptr<nbm::Stepper> stepper = make(problem);
  run_steps(state, problem, *stepper, Bouncing ? kBounceWindow : 1e300);
  report(state, c, problem.n_contact());
}

template <bool Bouncing>
void BM_NbmNewmarkStep(benchmark::State& state) {
  nbm_steps<Bouncing>(state, false, [](const nbm::ContactProblem& p) {
    return std::make_unique<nbm::NewmarkStepper>(p, kImplicitDt);
  });
}

template <bool Bouncing>
void BM_NbmMasslessStep(benchmark::State& state) {
  nbm_steps<Bouncing>(state, true, [](const nbm::ContactProblem& p) {
    return std::make_unique<nbm::MasslessNewmarkStepper>(p, kImplicitDt);
  });
}

template <bool Bouncing>
void BM_NbmExplicitStep(benchmark::State& state) {
  nbm_steps<Bouncing>(state, false, [](const nbm::ContactProblem& p) {
    // Half the critical step of the lumped system.
    const double dt = 0.5 * 2 / std::sqrt(nbm::max_eigenvalue(p.K(), p.lumped_mass()));
    return std::make_unique<nbm::CentralDifferenceStepper>(p, dt);
  });
}

void BM_NbmSetup(benchmark::State& state) {
  const Case& c = plate_case_measured(state);
  long contacts = 0;
  for (auto _ : state) {
    const nbm::ContactProblem problem = make_problem(c, kBounceGap);
    nbm::NewmarkStepper stepper(problem, kImplicitDt);
    contacts = problem.n_contact();
    benchmark::DoNotOptimize(&stepper);
  }
  report(state, c, contacts);
}

// Sizes: P1 and P2 from 1e3 to 1e6 dofs (bench/run.sh picks which to run).
void sizes(benchmark::internal::Benchmark* b) {
  for (int order : {1, 2})
    for (int dofs : {1000, 10000, 100000, 1000000}) b->Args({order, dofs});
  b->ArgNames({"order", "dofs"})->Unit(benchmark::kMicrosecond);
}

}  // namespace

BENCHMARK(BM_PlainNewmarkStep)->Apply(sizes);
BENCHMARK(BM_PlainExplicitStep)->Apply(sizes);
BENCHMARK(BM_PlainFactorization)->Apply(sizes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NbmNewmarkStep<false>)->Name("BM_NbmNewmarkStepFreeFlight")->Apply(sizes);
BENCHMARK(BM_NbmNewmarkStep<true>)->Name("BM_NbmNewmarkStepBouncing")->Apply(sizes)->Iterations(kWindowSteps);
BENCHMARK(BM_NbmMasslessStep<false>)->Name("BM_NbmMasslessStepFreeFlight")->Apply(sizes);
BENCHMARK(BM_NbmMasslessStep<true>)->Name("BM_NbmMasslessStepBouncing")->Apply(sizes)->Iterations(kWindowSteps);
BENCHMARK(BM_NbmExplicitStep<false>)->Name("BM_NbmExplicitStepFreeFlight")->Apply(sizes);
BENCHMARK(BM_NbmExplicitStep<true>)->Name("BM_NbmExplicitStepBouncing")->Apply(sizes);
BENCHMARK(BM_NbmSetup)->Apply(sizes)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
