// What the energy-stable steps cost (method.md §5.1, §5.3): a P1 plate
// (bench/plate.hpp, cells of 0.02 x 0.02, Poisson ratio NU) dropped 1e-3 onto
// flat ground along its bottom edge and left on it, steps of DT, so that its
// contacts open and close in most steps. Prints, in one process:
//   - the plain contact-free Newmark step (plain_step.hpp) and its factorization;
//   - for the massless boundary and for the paper's NBM (contact nodes with
//     mass), with energy = "bounded", "monotone" and "none": setup, mean
//     step, the share of steps in which a contact switched, of those taken
//     between two candidates (balanced) and of the paper's fallbacks, and
//     each step / plain step;
//   - the massless stepper in free flight (the ground far below): the
//     massless step without contact forces.
// CPU times of this thread, mean over STEPS steps after SETTLE steps of
// settling; run with OPENBLAS_NUM_THREADS=1.
//   nbm_energy_cost NX NY NU DT SETTLE STEPS
//   OPENBLAS_NUM_THREADS=1 build/bench/nbm_energy_cost 100 50 0.49 1e-3 200 200
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contact/contact_problem.hpp"
#include "plain_step.hpp"
#include "plate.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/newmark_stepper.hpp"

namespace {

using nbm::Index;
using nbm::Vector;

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Measured {
  double setup = 0, step = 0;
  double switching = 0, balanced = 0, fallbacks = 0;  // shares of the timed steps
};

// The two mass treatments (method.md §4).
enum class Mass { kMassless, kConsistent };

// The plate's bottom edge against a ground `gap` below it, mass treatment
// `mass`, energy control `energy`: setup, then SETTLE steps, then STEPS
// timed ones.
Measured at_rest(const nbm_bench::Plate& p, const nbm_bench::Assembled& a,
                 const Eigen::MatrixXd& X, double gap, double dt, Mass mass,
                 nbm::EnergyControl energy, int settle, int steps) {
  const Index n = a.K.rows();
  std::vector<Index> dofs;
  std::vector<double> normals, gaps;
  for (int i = 0; i < p.nodes_x(); ++i) {
    dofs.push_back(2 * p.node(i, 0) + 1);
    normals.push_back(-1);
    gaps.push_back(gap);
  }
  Measured m;
  const double start = cpu_seconds();
  const nbm::ContactProblem problem(
      a.M, a.K, nbm::ContactSet(n, dofs, normals, Eigen::Map<const Vector>(gaps.data(), gaps.size())),
      {}, mass == Mass::kMassless ? &X : nullptr);
  std::unique_ptr<nbm::NbmStepper> s;
  if (mass == Mass::kMassless) {
    s = std::make_unique<nbm::MasslessNewmarkStepper>(problem, dt, nbm::SchemeParameters{}, nbm::Damping{},
                                                      nbm::ContactColumns::kAuto, energy);
  } else {
    nbm::NewmarkParameters parameters;
    parameters.energy = energy;
    s = std::make_unique<nbm::NewmarkStepper>(problem, dt, parameters);
  }
  m.setup = cpu_seconds() - start;
  const Vector F = problem.to_internal(a.F), zero = Vector::Zero(n);
  s->initialize(zero, zero, F);
  for (int k = 0; k < settle; ++k) s->step(F);
  const long balanced_before = s->balanced_steps();
  int switching = 0, fallbacks = 0;
  const double t0 = cpu_seconds();
  for (int k = 0; k < steps; ++k) {
    const nbm::ActiveSet before = s->active();
    fallbacks += s->step(F).fallback;
    switching += s->active() != before;
  }
  m.step = (cpu_seconds() - t0) / steps;
  m.switching = static_cast<double>(switching) / steps;
  m.balanced = static_cast<double>(s->balanced_steps() - balanced_before) / steps;
  m.fallbacks = static_cast<double>(fallbacks) / steps;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s NX NY NU DT SETTLE STEPS\n", argv[0]);
    return 2;
  }
  nbm_bench::Plate p = nbm_bench::Plate::of_cells(std::atoi(argv[1]), std::atoi(argv[2]));
  p.nu = std::atof(argv[3]);
  const double dt = std::atof(argv[4]);
  const int settle = std::atoi(argv[5]), steps = std::atoi(argv[6]);
  if (!(p.nu > -1 && p.nu < 0.5) || !(dt > 0) || settle < 0 || steps < 1) {
    std::fprintf(stderr, "%s: expected -1 < NU < 0.5, DT > 0, SETTLE >= 0, STEPS >= 1\n", argv[0]);
    return 2;
  }
  const nbm_bench::Assembled a = nbm_bench::assemble(p);
  const Eigen::MatrixXd X = nbm_bench::dof_positions(p);

  double start = cpu_seconds();
  auto S = nbm::make_cholesky_inverse(a.M + (0.25 * dt * dt) * a.K, "S");
  const double factorization = cpu_seconds() - start;
  nbm_bench::PlainNewmark plain(*S, a, dt);
  plain.step();
  plain.step();
  start = cpu_seconds();
  for (int k = 0; k < steps; ++k) plain.step();
  const double plain_step = (cpu_seconds() - start) / steps;
  S.reset();

  std::printf("dofs %ld, contact nodes %d, nu %g, dt %g: factorization %.4f s, plain step "
              "%.6f s\n",
              static_cast<long>(a.K.rows()), p.nodes_x(), p.nu, dt, factorization, plain_step);
  const Measured free_flight = at_rest(p, a, X, 1e6, dt, Mass::kMassless,
                                       nbm::EnergyControl::kBounded, settle, steps);
  std::printf("massless, free flight:       setup %.4f s (%.2f factorizations), step %.6f s "
              "(%.2f plain)\n",
              free_flight.setup, free_flight.setup / factorization, free_flight.step,
              free_flight.step / plain_step);
  for (const auto& [mass, mass_name] :
       {std::pair{Mass::kMassless, "massless"}, {Mass::kConsistent, "paper NBM"}})
    for (const auto& [energy, name] : {std::pair{nbm::EnergyControl::kBounded, "bounded"},
                                       {nbm::EnergyControl::kMonotone, "monotone"},
                                       {nbm::EnergyControl::kNone, "none"}}) {
      const Measured m = at_rest(p, a, X, 1e-3, dt, mass, energy, settle, steps);
      std::printf("%s, at rest, %-9s setup %.4f s (%.2f factorizations), step %.6f s "
                  "(%.2f plain); switching %.0f%%, balanced %.0f%%, fallbacks %.0f%% of the "
                  "steps\n",
                  mass_name, (std::string(name) + ":").c_str(), m.setup, m.setup / factorization,
                  m.step, m.step / plain_step, 100 * m.switching, 100 * m.balanced,
                  100 * m.fallbacks);
    }
  return 0;
}
