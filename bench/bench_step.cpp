// Cost of NBM against the plain contact-free schemes, on the same matrices
// assembled here (the plane-strain plate of bench/plate.hpp, the 3D block of
// bench/block.hpp), the same factorization library (CHOLMOD through
// nbm::make_cholesky_inverse) and in the same run:
//   Plain*            contact-free Newmark / central differences: the floor
//   Nbm*              the NBM steppers, in free flight (the body far above
//                     the ground) and through bounces (active-set changes)
//   *Setup/*Factor    construction against one plain factorization
// Two families of arguments:
//   BM_<name>/order:o/dofs:n         the plate with its bottom edge in contact
//                                    (bench/RESULTS.md's first tables)
//   BM_Scale<name>/body:b/order:o/dofs:n/contact_pct:p
//                                    issue 14's large contact sets: body 0 the
//                                    plate (W/H = 2), 1 the strip (W/H = 80),
//                                    2 the block; contact on p % of the bottom
//                                    face (along x), 200: bottom and top faces.
//                                    The impacts are a contact front sweeping
//                                    the contact set (Sweep: an inclined
//                                    obstacle and a falling body, a new column
//                                    of nodes touching at every step), and
//                                    PenaltyStep is the competitor that
//                                    refactorises at every active-set change.
// Every benchmark reports the problem size, the contact nodes, the memory its
// solver objects hold (heap growth since the body was assembled) and the peak
// resident memory of its process (VmHWM: meaningful when each benchmark runs
// in its own process, as bench/run.sh does). `nbm_bench --blas` prints which
// BLAS the process loaded (bench/measure.hpp).
#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "contact/contact_problem.hpp"
#include "contact/mass_redistribution.hpp"
#include "contact_region.hpp"
#include "measure.hpp"
#include "plain_step.hpp"
#include "scale_case.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/newmark_stepper.hpp"

namespace {

using nbm::Index;
using nbm::Vector;
using nbm_bench::ContactRegion;

// Bouncing runs: the plate starts kBounceGap above the ground (fall 0.014)
// and is restarted after kBounceWindow (the impact lasts about 2 H / c_p =
// 0.027): every timed run covers whole windows of fall, impact and rebound.
constexpr double kBounceGap = 1e-3, kBounceWindow = 0.05, kImplicitDt = 2e-4;
constexpr int kWindowSteps = 250;
constexpr double kFreeGap = 1e6;  // never reached: free flight
// Sweeping runs (scale_case.hpp): memory is read after their kSweepSteps steps.
using nbm_bench::Case;
using nbm_bench::kBlock;
using nbm_bench::kPlate;
using nbm_bench::kStrip;
using nbm_bench::kSweepSteps;

const Case& body_case(int body, int order, int dofs) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<Case>> cache;
  auto& c = cache[{body, order, dofs}];
  if (!c) c = std::make_unique<Case>(nbm_bench::assemble_body(body, order, dofs));
  return *c;
}

// Heap in use once the problem is assembled: what a benchmark's solver
// objects hold is the heap at report() time minus this.
double heap_after_assembly = 0;

// The case of a BM_<name> (plate) or a BM_Scale<name> benchmark, once
// assembled; the heap from here on is the benchmark's.
const Case& plate_case(const benchmark::State& state) {
  const Case& c = body_case(kPlate, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  heap_after_assembly = nbm_bench::heap_mb();
  return c;
}
const Case& scale_case(const benchmark::State& state) {
  const Case& c = body_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                            static_cast<int>(state.range(2)));
  heap_after_assembly = nbm_bench::heap_mb();
  return c;
}

// The contact set of a scale benchmark (scale_case.hpp).
ContactRegion scale_region(const benchmark::State& state) {
  return nbm_bench::scale_region(static_cast<int>(state.range(3)));
}

/// The contact problem of `region`; with the massless boundary if `massless`.
nbm::ContactProblem make_problem(const Case& c, const ContactRegion& region, bool massless = false) {
  const nbm::ContactDescription d = nbm_bench::contact_on(c.X, region);
  nbm::ContactSet set(c.a.K.rows(), {d.dofs.begin(), d.dofs.end()}, d.normals,
                      Eigen::Map<const Vector>(d.gaps.data(), d.gaps.size()));
  return nbm::ContactProblem(c.a.M, c.a.K, std::move(set), {}, massless ? &c.X : nullptr);
}

// Call while the solver objects are alive.
void report(benchmark::State& state, const Case& c, long contacts) {
  state.counters["dofs"] = c.a.K.rows();
  state.counters["contacts"] = static_cast<double>(contacts);
  state.counters["peak_rss_MB"] = nbm_bench::status_mb("VmHWM");
  state.counters["held_MB"] = nbm_bench::heap_mb() - heap_after_assembly;
}


// Whether the row-sum lumped mass is positive (not for P2 tetrahedra: the
// rows of their vertices sum to negative masses), which the explicit schemes
// need; skips the benchmark if not.
bool has_explicit_scheme(benchmark::State& state, const Case& c) {
  if ((c.a.M * Vector::Ones(c.a.M.rows())).minCoeff() > 0) return true;
  state.SkipWithError("row-sum lumped mass not positive: no explicit scheme");
  return false;
}

using nbm_bench::explicit_dt;

// ------------------------------------------------------------ plain schemes

// The plain steps (plain_step.hpp), what every ratio divides by.
void plain_newmark_step(benchmark::State& state, const Case& c) {
  const auto S = nbm::make_cholesky_inverse(c.a.M + (0.25 * kImplicitDt * kImplicitDt) * c.a.K, "S");
  nbm_bench::PlainNewmark plain(*S, c.a, kImplicitDt);
  for (auto _ : state) {
    plain.step();
    benchmark::DoNotOptimize(plain.u().data());
  }
  report(state, c, 0);
}

void plain_explicit_step(benchmark::State& state, const Case& c) {
  if (!has_explicit_scheme(state, c)) return;
  const Vector m = c.a.M * Vector::Ones(c.a.M.rows());
  nbm_bench::PlainCentralDifference plain(c.a, m, explicit_dt(c.a.K, m));
  for (auto _ : state) {
    plain.step();
    benchmark::DoNotOptimize(plain.u().data());
  }
  report(state, c, 0);
}

void plain_factorization(benchmark::State& state, const Case& c) {
  const nbm::SparseMatrix S = c.a.M + (0.25 * kImplicitDt * kImplicitDt) * c.a.K;
  for (auto _ : state) benchmark::DoNotOptimize(nbm::make_cholesky_inverse(S, "S").get());
  report(state, c, 0);
}

// The competitor of a changing NBM step: average-acceleration Newmark with a
// penalty kappa (n.u - g)^2 / 2 on the penetrating contact nodes, whose matrix
// M + dt^2/4 (K + kappa sum_active n n') changes with the active set and is
// refactorised then -- numerically, CHOLMOD's symbolic analysis done once
// (cholmod_factorize with the existing factor, through Eigen's
// CholmodSupernodalLLT::factorize). The normals of the benchmark bodies are
// coordinate axes, so the penalty only changes diagonal entries of the pattern.
// A sweep: the penetrating set grows at every step. kappa: 1e3 max K_ii.
void penalty_sweep_step(benchmark::State& state, const Case& c, const ContactRegion& region) {
  const double dt = kImplicitDt, bdt2 = 0.25 * dt * dt;
  const nbm::ContactDescription d = nbm_bench::contact_on(c.X, nbm_bench::sweeping(region, c.X, dt));
  const Index n = c.a.K.rows(), dim = c.X.cols(), nc = static_cast<Index>(d.gaps.size());
  const double kappa = 1e3 * c.a.K.diagonal().maxCoeff();
  nbm::SparseMatrix S = c.a.M + bdt2 * c.a.K;
  std::vector<Index> normal_dof(nc);
  std::vector<double> normal(nc);
  std::vector<double*> diagonal(nc);
  for (Index k = 0; k < nc; ++k) {
    normal_dof[k] = d.dofs[k * dim + dim - 1];
    normal[k] = d.normals[k * dim + dim - 1];
    diagonal[k] = &S.coeffRef(normal_dof[k], normal_dof[k]);
  }
  const Vector S_diagonal = S.diagonal();
  Eigen::CholmodSupernodalLLT<nbm::SparseMatrix, Eigen::Lower> llt;
  const auto start = std::chrono::steady_clock::now();
  llt.compute(S);
  state.counters["penalty_factor_us"] =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  Vector u = Vector::Zero(n), v = nbm_bench::falling(c.X), a = Vector::Zero(n);
  Vector u_pred(n), r(n), a_new(n);
  std::vector<char> active(nc, 0), next(nc);
  long refactorizations = 0;
  for (auto _ : state) {
    u_pred = u + dt * v + bdt2 * a;
    r.noalias() = c.a.M * u_pred;
    r += bdt2 * c.a.F;
    for (Index k = 0; k < nc; ++k) next[k] = normal[k] * u_pred(normal_dof[k]) > d.gaps[k];
    if (next != active) {
      active = next;
      for (Index k = 0; k < nc; ++k)
        *diagonal[k] = S_diagonal(normal_dof[k]) + (active[k] ? bdt2 * kappa : 0.0);
      llt.factorize(S);
      ++refactorizations;
    }
    for (Index k = 0; k < nc; ++k)
      if (active[k]) r(normal_dof[k]) += bdt2 * kappa * d.gaps[k] * normal[k];
    u_pred = llt.solve(r);
    a_new = (u_pred - (u + dt * v + bdt2 * a)) / bdt2;
    u.swap(u_pred);
    v += (0.5 * dt) * (a + a_new);
    a.swap(a_new);
  }
  state.counters["switch_steps"] =
      benchmark::Counter(static_cast<double>(refactorizations), benchmark::Counter::kAvgIterations);
  report(state, c, nc);
}

// -------------------------------------------------------------- NBM schemes

// Runs `stepper` from the state (u = 0, v0), restarting (untimed) every
// `window` of simulated time, and counts the steps whose active set changed.
// The first step is taken before the timing and reported on its own
// (first_step_us): it factors the dense blocks of the initial active set
// once, a start-up cost, not the cost per step of a run. In a sweep
// (`sweep`), no first step: every timed step brings new contacts.
void run_steps(benchmark::State& state, const Case& c, const nbm::ContactProblem& problem,
               nbm::Stepper& stepper, double window, const Vector& v0_user, bool sweep) {
  const Vector F = problem.to_internal(c.a.F);
  const Vector zero = Vector::Zero(problem.size()), v0 = problem.to_internal(v0_user);
  stepper.initialize(zero, v0, F);
  if (!sweep) {
    const auto start = std::chrono::steady_clock::now();
    stepper.step(F);
    state.counters["first_step_us"] =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  }
  long switches = 0, iterations = 0, fallbacks = 0;
  for (auto _ : state) {
    if (stepper.time() > window) {
      state.PauseTiming();
      stepper.initialize(zero, v0, F);
      state.ResumeTiming();
    }
    const nbm::ActiveSet before = stepper.active();
    const nbm::StepReport r = stepper.step(F);
    iterations += r.active_set_iterations;
    fallbacks += r.fallback;
    switches += stepper.active() != before;
  }
  state.counters["switch_steps"] = benchmark::Counter(switches, benchmark::Counter::kAvgIterations);
  state.counters["solves_per_step"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  state.counters["fallbacks"] = static_cast<double>(fallbacks);
}

enum class Motion { kFreeFlight, kBouncing, kSweep };

// One NBM benchmark: the body in free flight, bouncing or sweeping, with the
// consistent or the redistributed mass, stepped by what `make` builds with
// its time step.
template <class Make>
void nbm_steps(benchmark::State& state, const Case& c, ContactRegion region, Motion motion,
               bool massless, double dt, Make make) {
  Vector v0 = Vector::Zero(c.X.rows());
  double window = 1e300;
  if (motion == Motion::kFreeFlight) region.gap = kFreeGap;
  if (motion == Motion::kBouncing) {
    region.gap = kBounceGap;
    window = kBounceWindow;
  }
  if (motion == Motion::kSweep) {
    region = nbm_bench::sweeping(region, c.X, dt);
    v0 = nbm_bench::falling(c.X);
  }
  // The setup (what BM_NbmSetup times) is reported too: where one process per
  // benchmark is all a size allows (the 3D block of 1e6 dofs), the sweep gives it.
  const auto start = std::chrono::steady_clock::now();
  const nbm::ContactProblem problem = make_problem(c, region, massless);
  const std::unique_ptr<nbm::Stepper> stepper = make(problem, dt);
  state.counters["setup_us"] =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  run_steps(state, c, problem, *stepper, window, v0, motion == Motion::kSweep);
  report(state, c, problem.n_contact());
}

std::unique_ptr<nbm::Stepper> newmark(const nbm::ContactProblem& p, double dt) {
  return std::make_unique<nbm::NewmarkStepper>(p, dt);
}
std::unique_ptr<nbm::Stepper> massless_newmark(const nbm::ContactProblem& p, double dt) {
  return std::make_unique<nbm::MasslessNewmarkStepper>(p, dt);
}
std::unique_ptr<nbm::Stepper> central_difference(const nbm::ContactProblem& p, double dt) {
  return std::make_unique<nbm::CentralDifferenceStepper>(p, dt);
}

// The plate benchmarks' explicit step: half the critical step of the lumped
// system of the problem (bench/RESULTS.md); the scale benchmarks use the
// plain explicit step's, explicit_dt of the row-sum mass, for both sides.
std::unique_ptr<nbm::Stepper> central_difference_own_dt(const nbm::ContactProblem& p, double) {
  return central_difference(p, explicit_dt(p.K(), p.lumped_mass()));
}

double row_sum_explicit_dt(const Case& c) {
  return explicit_dt(c.a.K, c.a.M * Vector::Ones(c.a.M.rows()));
}

void nbm_setup(benchmark::State& state, const Case& c, const ContactRegion& region) {
  long contacts = 0;
  for (auto _ : state) {
    const nbm::ContactProblem problem = make_problem(c, region);
    nbm::NewmarkStepper stepper(problem, kImplicitDt);
    contacts = problem.n_contact();
    benchmark::DoNotOptimize(&stepper);
  }
  report(state, c, contacts);
}

// ------------------------------------------------------------- registration

// Plate sizes: P1 and P2 from 1e3 to 1e6 dofs (bench/run.sh picks which to run).
void plate_sizes(benchmark::internal::Benchmark* b) {
  for (int order : {1, 2})
    for (int dofs : {1000, 10000, 100000, 1000000}) b->Args({order, dofs});
  b->ArgNames({"order", "dofs"})->Unit(benchmark::kMicrosecond);
}

// Scale cases: every body, order and size bench/scale.sh may ask for, the
// contact set from 1/16 of the bottom face to both faces.
void scale_sizes(benchmark::internal::Benchmark* b) {
  for (int body : {kPlate, kStrip, kBlock})
    for (int order : {1, 2})
      for (int dofs : {3000, 30000, 100000, 300000, 1000000})
        for (int pct : {6, 12, 25, 50, 100, 200}) b->Args({body, order, dofs, pct});
  b->ArgNames({"body", "order", "dofs", "contact_pct"})->Unit(benchmark::kMicrosecond);
}

using Benchmark = void (*)(benchmark::State&);
void add(const char* name, Benchmark plate, Benchmark scale, bool slow = false) {
  auto* p = benchmark::RegisterBenchmark(name, plate)->Apply(plate_sizes);
  auto* s = benchmark::RegisterBenchmark((std::string("BM_Scale") + (name + 3)).c_str(), scale)
                ->Apply(scale_sizes);
  if (slow) {
    p->Unit(benchmark::kMillisecond);
    s->Unit(benchmark::kMillisecond);
  }
}

void register_all() {
  add("BM_PlainNewmarkStep", [](benchmark::State& s) { plain_newmark_step(s, plate_case(s)); },
      [](benchmark::State& s) { plain_newmark_step(s, scale_case(s)); });
  add("BM_PlainExplicitStep", [](benchmark::State& s) { plain_explicit_step(s, plate_case(s)); },
      [](benchmark::State& s) { plain_explicit_step(s, scale_case(s)); });
  add("BM_PlainFactorization", [](benchmark::State& s) { plain_factorization(s, plate_case(s)); },
      [](benchmark::State& s) { plain_factorization(s, scale_case(s)); }, true);
  add("BM_NbmSetup", [](benchmark::State& s) { nbm_setup(s, plate_case(s), ContactRegion{}); },
      [](benchmark::State& s) { nbm_setup(s, scale_case(s), scale_region(s)); }, true);
  // The plate's NBM steps: free flight and bouncing.
  const struct {
    const char* name;
    bool massless, explicit_scheme;
  } schemes[] = {{"Newmark", false, false}, {"Massless", true, false}, {"Explicit", false, true}};
  for (const auto& k : schemes) {
    for (const Motion motion : {Motion::kFreeFlight, Motion::kBouncing}) {
      const std::string name = std::string("BM_Nbm") + k.name + "Step" +
                               (motion == Motion::kBouncing ? "Bouncing" : "FreeFlight");
      auto* b = benchmark::RegisterBenchmark(name.c_str(), [k, motion](benchmark::State& s) {
        const Case& c = plate_case(s);
        if (k.explicit_scheme)
          nbm_steps(s, c, ContactRegion{}, motion, false, 0, central_difference_own_dt);
        else
          nbm_steps(s, c, ContactRegion{}, motion, k.massless, kImplicitDt,
                    k.massless ? massless_newmark : newmark);
      })->Apply(plate_sizes);
      if (motion == Motion::kBouncing && !k.explicit_scheme) b->Iterations(kWindowSteps);
    }
    // The scale cases: free flight and a sweep of kSweepSteps steps.
    for (const Motion motion : {Motion::kFreeFlight, Motion::kSweep}) {
      const std::string name = std::string("BM_ScaleNbm") + k.name + "Step" +
                               (motion == Motion::kSweep ? "Sweep" : "FreeFlight");
      auto* b = benchmark::RegisterBenchmark(name.c_str(), [k, motion](benchmark::State& s) {
        const Case& c = scale_case(s);
        if (k.explicit_scheme && !has_explicit_scheme(s, c)) return;
        const double dt = k.explicit_scheme ? row_sum_explicit_dt(c) : kImplicitDt;
        nbm_steps(s, c, scale_region(s), motion, k.massless, dt,
                  k.explicit_scheme ? central_difference : k.massless ? massless_newmark : newmark);
      })->Apply(scale_sizes);
      if (motion == Motion::kSweep) b->Iterations(kSweepSteps);
    }
  }
  benchmark::RegisterBenchmark("BM_ScalePenaltyStepSweep", [](benchmark::State& s) {
    penalty_sweep_step(s, scale_case(s), scale_region(s));
  })->Apply(scale_sizes)->Iterations(kSweepSteps);
}

}  // namespace

int main(int argc, char** argv) {
  if (nbm_bench::blas_flag(argc, argv)) return 0;
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
