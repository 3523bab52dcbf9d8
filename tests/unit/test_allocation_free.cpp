// Once warm, a time step allocates nothing on the heap: the steppers keep
// their workspaces, CHOLMOD's solve reuses its own (cholmod_solve2), and the
// dense factorizations per active set are cached. The test replaces the C
// allocator of this executable by a counting front end to glibc's (every
// C++ allocation, Eigen's and CHOLMOD's go through malloc), runs a bouncing
// plate once to fill the caches, then replays the same run and counts.
// Its own executable: the replacement must not reach the other tests, and it
// is left out of sanitizer builds, whose runtime owns malloc.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstddef>
#include <functional>
#include <memory>

#include "contact/mass_redistribution.hpp"
#include "linalg/constrained_solver.hpp"
#include "linalg/principal_block.hpp"
#include "test_problems.hpp"
#include "time/central_difference_stepper.hpp"
#include "time/generalized_alpha.hpp"
#include "time/massless_newmark_stepper.hpp"
#include "time/newmark_stepper.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
bool counting = false;
long allocations = 0;
void* counted(void* p) {
  if (counting) ++allocations;
  return p;
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) { return counted(__libc_malloc(n)); }
void* calloc(std::size_t n, std::size_t size) { return counted(__libc_calloc(n, size)); }
void* realloc(void* p, std::size_t n) { return counted(__libc_realloc(p, n)); }
void* memalign(std::size_t alignment, std::size_t n) {
  return counted(__libc_memalign(alignment, n));
}
void* aligned_alloc(std::size_t alignment, std::size_t n) {
  return counted(__libc_memalign(alignment, n));
}
int posix_memalign(void** p, std::size_t alignment, std::size_t n) {
  *p = counted(__libc_memalign(alignment, n));
  return *p != nullptr ? 0 : ENOMEM;
}
void free(void* p) { __libc_free(p); }
}

namespace {

using nbm_test::Plate;
using Vec = Eigen::VectorXd;

// A tilted plate dropped from 2 mm: about 0.02 s of fall, then the impact
// and the rebound, with its active-set changes.
struct DroppedPlate {
  Plate p;
  nbm_test::Assembled a;
  std::unique_ptr<nbm::ContactProblem> problem;
  explicit DroppedPlate(bool massless = false, int nx = 8) {
    p.nx = nx;
    p.ny = 4;
    p.angle = 0.1;
    a = assemble(p);
    const nbm::ContactDescription c = nbm_test::bottom_contact(p, 2e-3);
    nbm::ContactSet set(p.n_dofs(), std::vector<nbm::Index>(c.dofs.begin(), c.dofs.end()),
                        c.normals, nbm_test::to_eigen(c.gaps), {});
    const Eigen::MatrixXd X = nbm_test::node_positions(p);
    problem = std::make_unique<nbm::ContactProblem>(a.M, a.K, std::move(set),
                                                    std::vector<nbm::Index>{},
                                                    massless ? &X : nullptr);
  }
};

// Allocations during `steps` steps from rest, the caches being warm from an
// identical run. Also checks that the run changes active sets and that the
// counter sees the first run's allocations (workspaces, cached factors).
long allocations_in_replay(const nbm::ContactProblem& problem, nbm::Stepper& stepper,
                           const Vec& F, int steps) {
  const Vec zero = Vec::Zero(problem.size());
  long per_run[2];
  int changes = 0;
  for (int run = 0; run < 2; ++run) {
    stepper.initialize(zero, zero, F);
    allocations = 0;
    counting = true;
    for (int n = 0; n < steps; ++n) {
      const bool was_closed = stepper.active()[0];
      stepper.step(F);
      changes += stepper.active()[0] != was_closed;
    }
    counting = false;
    per_run[run] = allocations;
  }
  EXPECT_GT(changes, 0) << "the run must go through contact";
  EXPECT_GT(per_run[0], 0) << "the warm-up run allocates its workspaces and caches";
  return per_run[1];
}

TEST(AllocationFree, ImplicitNewmarkStep) {
  const DroppedPlate d;
  nbm::NewmarkStepper stepper(*d.problem, 1e-3);
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

TEST(AllocationFree, ImplicitNewmarkStepWithSparseContactBlocks) {
  // 33 contact nodes along an edge: K_CC is a band, so the LCP's principal
  // blocks and the open blocks get sparse factors and products
  // (principal_block.hpp); the plate above has too few contact nodes for it.
  const DroppedPlate d(false, 32);
  ASSERT_TRUE(nbm::PrincipalBlocks(d.problem->K_CC()).sparse());
  nbm::NewmarkStepper stepper(*d.problem, 1e-3);
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

TEST(AllocationFree, ExplicitStepWithSparseContactBlocks) {
  const DroppedPlate d(false, 32);
  ASSERT_TRUE(nbm::PrincipalBlocks(d.problem->K_CC()).sparse());
  const double critical =
      2 / std::sqrt(nbm::max_eigenvalue(d.problem->K(), d.problem->lumped_mass()));
  nbm::CentralDifferenceStepper stepper(*d.problem, 0.5 * critical);
  const int steps = static_cast<int>(0.1 / (0.5 * critical));
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), steps), 0);
}

TEST(AllocationFree, BorderedSchurFactorSolve) {
  // 33 contact nodes, one closed: the set differs from its base (all open)
  // at one node and gets a Schur factor bordered on the base's
  // (ConstrainedSolver::schur, schur_factor.hpp). The replays above meet
  // only sets that are their own base; a solve with a bordered factor, once
  // made, allocates nothing either.
  const DroppedPlate d(false, 32);
  const nbm::Index n = d.problem->size(), n_c = d.problem->n_contact();
  const nbm::SparseMatrix S = d.problem->M() + 1e-6 * d.problem->K();  // Newmark, dt = 2e-3
  const nbm::ConstrainedSolver solver(nbm::make_cholesky_inverse(S, "S"),
                                      d.problem->constraint_basis());
  nbm::ActiveSet front(n_c, false);
  front[0] = true;
  const Vec r = Vec::Ones(n), h = Vec::Zero(n_c);
  Vec x;
  allocations = 0;
  counting = true;
  solver.solve(front, r, h, x);  // makes the base and the bordered factor
  counting = false;
  EXPECT_GT(allocations, 0) << "the first solve factors";
  allocations = 0;
  counting = true;
  solver.solve(front, r, h, x);
  counting = false;
  EXPECT_EQ(allocations, 0);
}

TEST(AllocationFree, MasslessNewmarkStep) {
  const DroppedPlate d(true);
  nbm::MasslessNewmarkStepper stepper(*d.problem, 1e-3);
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

// Generalized-alpha's predictors and algorithmic acceleration (method.md
// §5.4) reuse their vectors too, with either contact step.
TEST(AllocationFree, GeneralizedAlphaSteps) {
  const DroppedPlate paper, massless(true);
  nbm::NewmarkParameters parameters;
  parameters.scheme = nbm::generalized_alpha(0.8);
  nbm::NewmarkStepper active_set(*paper.problem, 1e-3, parameters);
  EXPECT_EQ(allocations_in_replay(*paper.problem, active_set,
                                  paper.problem->to_internal(paper.a.F), 100),
            0);
  nbm::MasslessNewmarkStepper lcp(*massless.problem, 1e-3, nbm::hht_alpha(0.7));
  EXPECT_EQ(allocations_in_replay(*massless.problem, lcp, massless.problem->to_internal(massless.a.F),
                                  100),
            0);
}

TEST(AllocationFree, MasslessNewmarkStepRecomputingContactColumns) {
  const DroppedPlate d(true);
  nbm::MasslessNewmarkStepper stepper(*d.problem, 1e-3, {}, {},
                                      nbm::ContactColumns::kRecomputed);
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

// With damping (method.md §9) the steps keep their workspaces too.
nbm::Damping rayleigh(double a_M, double b_K) {
  nbm::Damping d;
  d.a_M = a_M;
  d.b_K = b_K;
  return d;
}

TEST(AllocationFree, DampedNewmarkStep) {
  const DroppedPlate d;
  nbm::NewmarkStepper stepper(*d.problem, 1e-3, {}, rayleigh(2, 1e-4));
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

TEST(AllocationFree, DampedMasslessNewmarkStep) {
  const DroppedPlate d(true);
  nbm::MasslessNewmarkStepper stepper(*d.problem, 1e-3, {}, rayleigh(2, 1e-4));
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), 100), 0);
}

TEST(AllocationFree, DampedExplicitStep) {
  const DroppedPlate d;
  const double critical =
      2 / std::sqrt(nbm::max_eigenvalue(d.problem->K(), d.problem->lumped_mass()));
  nbm::CentralDifferenceStepper stepper(*d.problem, 0.5 * critical, rayleigh(2, 0));
  const int steps = static_cast<int>(0.1 / (0.5 * critical));
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), steps), 0);
}

TEST(AllocationFree, ExplicitStep) {
  const DroppedPlate d;
  const double critical =
      2 / std::sqrt(nbm::max_eigenvalue(d.problem->K(), d.problem->lumped_mass()));
  nbm::CentralDifferenceStepper stepper(*d.problem, 0.5 * critical);
  const int steps = static_cast<int>(0.1 / (0.5 * critical));
  EXPECT_EQ(allocations_in_replay(*d.problem, stepper, d.problem->to_internal(d.a.F), steps), 0);
}

}  // namespace
