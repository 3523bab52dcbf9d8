// libFuzzer target: a few time steps through the nbm::Solver front end
// (solver.hpp) on small random problems: random SPD K and M (node-structured
// or not, full or lower-half coordinate storage, duplicated entries, an
// occasional tgv diagonal whose dof joins `fixed` as the FreeFEM binding
// passes it, plugin/freefem/dirichlet.hpp), random contact sets with random unit normals and
// gaps, random Dirichlet dofs, schemes newmark / explicit / moreau-jean, mass
// consistent or redistributed (random node positions), random Newmark
// parameters, restitution, dt, initial state and loads; sometimes one input
// broken (NaN, inf, wrong sizes, invalid options).
//
// Properties: no crash, no hang, exceptions only nbm::InputError and
// nbm::NumericalError; after the initialisation and after every successful
// step the state (u, v, gaps; unless an extreme value was injected also the
// reactions, energies and acceleration) is finite, and for the NBM schemes
// (newmark with both mass treatments, explicit) gap_k >= -1e-9 * scale, where
// `scale` is the displacement scale of the step: max(|g|, |u|, dt |v|,
// dt^2 |a| before and after the step, and the displacement the load alone
// produces in one step) -- see StateScale below for why |u| and |g| alone
// are not enough. Moreau-Jean penetrates by design (O(dt v)): only
// finiteness is checked for it.
//
// Corpus: newmark-beta-denormal (beta = 4.9e-324: beta dt^2 underflows to 0
// and the step returned v = -inf, NaN without an error; nbm::Solver now throws
// NumericalError, solver.cpp); penetration-at-rest and massless-large-load
// (round-off of the scale discussed in StateScale); gap-1e300 (the energies
// of a state of 1e284 overflow: not checked after extreme values).
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "api/solver.hpp"
#include "dirichlet.hpp"
#include "fuzz_common.hpp"

using nbm_fuzz::fail;
using Dense = Eigen::MatrixXd;

namespace {

Dense random_spd(FuzzedDataProvider& fdp, int n, bool positive_entries) {
  Dense B = Dense::Zero(n, n);
  const int fill = fdp.ConsumeIntegralInRange<int>(1, 4);  // sparsity of B
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i == j || fdp.ConsumeIntegralInRange<int>(0, fill) == 0) {
        const double x = nbm_fuzz::uniform(fdp, positive_entries ? 0 : -1, 1);
        B(i, j) = x;
      }
  const double shift = nbm_fuzz::pow10_in(fdp, -3, 0);
  Dense A = B.transpose() * B + shift * Dense::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < i; ++j) A(j, i) = A(i, j);
  return A;
}

// A node-level matrix with positive entries (a consistent mass of a mesh
// graph: w [2 1; 1 2] per edge plus a positive diagonal), so that row sums
// (lumped masses) are positive.
Dense random_mass(FuzzedDataProvider& fdp, int nodes) {
  Dense M = Dense::Zero(nodes, nodes);
  for (int i = 0; i < nodes; ++i) M(i, i) = nbm_fuzz::pow10_in(fdp, -2, 0);
  for (int i = 0; i < nodes; ++i)
    for (int j = i + 1; j < nodes; ++j)
      if (j == i + 1 || fdp.ConsumeIntegralInRange<int>(0, 3) == 0) {
        const double w = nbm_fuzz::uniform(fdp, 0, 1) / 6;
        M(i, i) += 2 * w, M(j, j) += 2 * w, M(i, j) += w, M(j, i) += w;
      }
  return M;
}

Dense kron_identity(const Dense& A, int d) {
  Dense K = Dense::Zero(A.rows() * d, A.cols() * d);
  for (int i = 0; i < A.rows(); ++i)
    for (int j = 0; j < A.cols(); ++j)
      for (int c = 0; c < d; ++c) K(i * d + c, j * d + c) = A(i, j);
  return K;
}

nbm::CooMatrix to_coo(FuzzedDataProvider& fdp, const Dense& A) {
  nbm::CooMatrix C;
  C.rows = A.rows();
  C.cols = A.cols();
  C.lower_half = fdp.ConsumeBool();
  for (long j = 0; j < A.cols(); ++j)
    for (long i = 0; i < A.rows(); ++i) {
      if (A(i, j) == 0 || (C.lower_half && i < j)) continue;
      if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0) {  // split into duplicates
        const double part = A(i, j) * nbm_fuzz::uniform(fdp, 0, 1);
        C.i.push_back(i), C.j.push_back(j), C.value.push_back(part);
        C.i.push_back(i), C.j.push_back(j), C.value.push_back(A(i, j) - part);
      } else {
        C.i.push_back(i), C.j.push_back(j), C.value.push_back(A(i, j));
      }
    }
  // Random order of the entries (a few swaps).
  const int swaps = fdp.ConsumeIntegralInRange<int>(0, 8);
  for (int s = 0; s < swaps && C.value.size() > 1; ++s) {
    const std::size_t a = fdp.ConsumeIntegralInRange<std::size_t>(0, C.value.size() - 1);
    const std::size_t b = fdp.ConsumeIntegralInRange<std::size_t>(0, C.value.size() - 1);
    std::swap(C.i[a], C.i[b]), std::swap(C.j[a], C.j[b]), std::swap(C.value[a], C.value[b]);
  }
  return C;
}

double max_abs(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

bool all_finite(const std::vector<double>& x) {
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

// Smallest eigenvalue of A over the dofs not listed in `fixed` (which holds
// the tgv dofs too); +inf if not positive.
double lambda_min_free(const Dense& A, const std::vector<long>& fixed) {
  std::vector<int> keep;
  for (int i = 0; i < A.rows(); ++i)
    if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) keep.push_back(i);
  if (keep.empty()) return std::numeric_limits<double>::infinity();
  Dense B(keep.size(), keep.size());
  for (std::size_t a = 0; a < keep.size(); ++a)
    for (std::size_t b = 0; b < keep.size(); ++b) B(a, b) = A(keep[a], keep[b]);
  if (!B.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::SelfAdjointEigenSolver<Dense> es(B, Eigen::EigenvaluesOnly);
  const double l = es.eigenvalues().minCoeff();
  return l > 0 ? l : std::numeric_limits<double>::infinity();
}

// The scale of the displacements a step handles: the gaps, the state before
// and after (u, dt v, dt^2 a) and the displacement the load alone produces in
// one step, bounded by |F| min(dt^2 / lambda_min(M), 1 / lambda_min(K)), or by
// |F| / lambda_min(K) with the massless boundary (its contact dofs respond
// statically). Round-off of a step is relative to this, not to |u| and |g|
// alone: a body at rest on the obstacle with g = 0 has u = 0 while the
// constrained solve handles dt^2 F / m (corpus: penetration-at-rest); with
// the massless boundary the gap of a closed contact is w = q + A lambda of the
// LCP in the contact forces, q = g - u_free_C ~ |F| / k_CC, so it carries the
// round-off eps |F| / k_CC (corpus: massless-large-load).
struct StateScale {
  double dt, load_factor;
  double operator()(const nbm::Solver& S, const std::vector<double>& u,
                    const std::vector<double>& v, const std::vector<double>& F) const {
    const double a = max_abs(S.acceleration());
    return std::max({max_abs(u), dt * max_abs(v), dt * dt * a, load_factor * max_abs(F)});
  }
};

void check_state(const nbm::Solver& S, const std::vector<double>& u, const std::vector<double>& v,
                 const std::vector<double>& g, bool nbm_scheme, bool extreme, double scale_before,
                 double scale_after, const char* when) {
  const std::vector<double> gaps = S.gaps();
  if (static_cast<long>(gaps.size()) != S.n_contact()) fail("%s: gaps size", when);
  if (!all_finite(u) || !all_finite(v) || !all_finite(gaps))
    fail("%s: non-finite state (scheme %s)", when, nbm::name(S.options().scheme));
  const std::vector<double> lambda = S.reactions(), a = S.acceleration(), e = S.energies();
  if (!extreme && (!all_finite(lambda) || !all_finite(a) || !all_finite(e)))
    fail("%s: non-finite reactions, acceleration or energies", when);
  if (static_cast<long>(S.active().size()) != S.n_contact()) fail("%s: active size", when);
  if (!nbm_scheme) return;
  const double scale = std::max({max_abs(g), scale_before, scale_after});
  for (std::size_t k = 0; k < gaps.size(); ++k)
    if (gaps[k] < -1e-9 * scale)
      fail("%s: penetration at contact node %zu: gap %.17g < -1e-9 * %.17g (scheme %s, mass %s)",
           when, k, gaps[k], scale, nbm::name(S.options().scheme), nbm::name(S.options().mass));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider fdp(data, size);
  const int d = fdp.ConsumeIntegralInRange<int>(1, 3);
  const int nodes = fdp.ConsumeIntegralInRange<int>(2, 8);
  const int n = nodes * d;
  // Consumed first: short inputs still take several steps.
  const int steps = fdp.ConsumeIntegralInRange<int>(1, 6);
  // The implicit NBM schemes (the richest logic: active-set fixed point,
  // fallback, massless boundary) get two thirds of the inputs.
  using nbm::TimeScheme;
  static const TimeScheme schemes[] = {TimeScheme::kNewmark,  TimeScheme::kNewmark,
                                       TimeScheme::kGeneralizedAlpha, TimeScheme::kHhtAlpha,
                                       TimeScheme::kExplicit, TimeScheme::kMoreauJean};
  nbm::SolverOptions opt;
  opt.scheme = schemes[fdp.ConsumeIntegralInRange<int>(0, 5)];
  const bool alpha = opt.scheme == TimeScheme::kGeneralizedAlpha || opt.scheme == TimeScheme::kHhtAlpha;
  const bool redistributed = fdp.ConsumeIntegralInRange<int>(0, 2) == 0;
  if (redistributed) opt.mass = nbm::MassTreatment::kRedistributed;

  // An extreme value (NaN, inf, 1e300, DBL_MAX, denormals) was injected: the
  // state must stay finite (or the core throw), but derived outputs such as
  // the energies may overflow (a state of 1e284 from gaps of 1e300).
  bool extreme = false;
  const auto special = [&] {
    extreme = true;
    return nbm_fuzz::special(fdp);
  };
  // One broken input at most (0: none).
  const int broken =
      fdp.ConsumeIntegralInRange<int>(0, 3) == 0 ? fdp.ConsumeIntegralInRange<int>(1, 14) : 0;

  const double sK = nbm_fuzz::pow10_in(fdp, -6, 6), sM = nbm_fuzz::pow10_in(fdp, -6, 6);
  const double sg = nbm_fuzz::pow10_in(fdp, -6, 6);
  const double T0 = std::sqrt(sM / sK);  // time scale of the problem

  Dense K = sK * random_spd(fdp, n, false);
  Dense M = fdp.ConsumeIntegralInRange<int>(0, 4) == 0
                ? sM * random_spd(fdp, n, true)
                : sM * kron_identity(random_mass(fdp, nodes), d);
  if (broken == 1)
    K(fdp.ConsumeIntegralInRange<int>(0, n - 1), fdp.ConsumeIntegralInRange<int>(0, n - 1)) =
        special();
  if (broken == 2)
    M(fdp.ConsumeIntegralInRange<int>(0, n - 1), 0) *= 1 + 1e-6;  // non-symmetric (maybe)

  // Contact nodes: distinct nodes, dofs node*d + c.
  std::vector<int> order(nodes);
  std::iota(order.begin(), order.end(), 0);
  for (int i = nodes - 1; i > 0; --i)
    std::swap(order[i], order[fdp.ConsumeIntegralInRange<int>(0, i)]);
  const int nc = fdp.ConsumeIntegralInRange<int>(1, nodes);
  nbm::ContactDescription contact;
  for (int k = 0; k < nc; ++k) {
    const int node = order[k];
    std::vector<double> normal(d);
    double nn = 0;
    const bool axis = fdp.ConsumeIntegralInRange<int>(0, 2) == 0;
    for (int c = 0; c < d; ++c) {
      normal[c] =
          axis ? (c == 0 ? (fdp.ConsumeBool() ? 1.0 : -1.0) : 0.0) : nbm_fuzz::uniform(fdp, -1, 1);
      nn += normal[c] * normal[c];
    }
    if (!(nn > 1e-6)) normal.assign(d, 0), normal[0] = 1, nn = 1;
    for (int c = 0; c < d; ++c) {
      contact.dofs.push_back(node * d + c);
      contact.normals.push_back(normal[c] / std::sqrt(nn));
    }
    const int gap_kind = fdp.ConsumeIntegralInRange<int>(0, 4);
    contact.gaps.push_back(gap_kind == 0 ? 0.0 : sg * nbm_fuzz::uniform(fdp, 0, 1));
  }
  if (broken == 3) contact.gaps[fdp.ConsumeIntegralInRange<int>(0, nc - 1)] = special();
  if (broken == 4)
    contact.normals[fdp.ConsumeIntegralInRange<std::size_t>(0, contact.normals.size() - 1)] *=
        1 + 1e-6;
  if (broken == 5)
    contact.dofs[fdp.ConsumeIntegralInRange<std::size_t>(0, contact.dofs.size() - 1)] =
        fdp.ConsumeIntegralInRange<long>(-1, n);

  // Dirichlet dofs: `fixed` and/or a tgv diagonal, away from the contact
  // nodes unless broken.
  std::vector<long> free_dofs;
  for (int k = nc; k < nodes; ++k)
    for (int c = 0; c < d; ++c) free_dofs.push_back(order[k] * d + c);
  const int n_fixed =
      fdp.ConsumeIntegralInRange<int>(0, 3) == 0 ? fdp.ConsumeIntegralInRange<int>(1, 3) : 0;
  for (int f = 0; f < n_fixed && !free_dofs.empty(); ++f)
    opt.fixed.push_back(
        free_dofs[fdp.ConsumeIntegralInRange<std::size_t>(0, free_dofs.size() - 1)]);
  if (broken == 6) opt.fixed.push_back(contact.dofs[0]);
  if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0 && !free_dofs.empty()) {
    const long t = free_dofs[fdp.ConsumeIntegralInRange<std::size_t>(0, free_dofs.size() - 1)];
    K(t, t) = 1e30;
  }

  // Options.
  if (opt.scheme == TimeScheme::kNewmark || broken == 7) {
    if (fdp.ConsumeBool()) opt.beta = nbm_fuzz::uniform(fdp, 1e-3, 0.5);
    if (fdp.ConsumeBool()) opt.gamma = nbm_fuzz::uniform(fdp, 0.5, 1);
    if (broken == 7) opt.beta = fdp.ConsumeBool() ? special() : 0.75;
  }
  if (alpha && fdp.ConsumeBool()) opt.rho_inf = nbm_fuzz::uniform(fdp, 0.5, 1);
  if (opt.scheme == TimeScheme::kMoreauJean && fdp.ConsumeBool())
    opt.restitution = nbm_fuzz::uniform(fdp, 0, 1);
  if (broken == 8) opt.restitution = fdp.ConsumeBool() ? special() : 1.5;
  if (broken == 9) opt.rho_inf = fdp.ConsumeBool() ? special() : 1.5;  // or with another scheme
  if (broken == 10) opt.energy = nbm::EnergyControl::kMonotone;   // refused unless Newmark's step
  if (redistributed || broken == 11) {
    const int pdim =
        fdp.ConsumeIntegralInRange<int>(0, 3) == 0 ? fdp.ConsumeIntegralInRange<int>(1, 3) : d;
    std::vector<double> node_pos(static_cast<std::size_t>(nodes) * pdim);
    const bool grid = fdp.ConsumeIntegralInRange<int>(0, 3) == 0;  // aligned nodes
    for (std::size_t i = 0; i < node_pos.size(); ++i)
      node_pos[i] = grid ? double(i / pdim) : nbm_fuzz::uniform(fdp, 0, 1);
    for (int dof = 0; dof < n; ++dof)
      for (int c = 0; c < pdim; ++c) opt.positions.push_back(node_pos[(dof / d) * pdim + c]);
    if (broken == 11) opt.positions.push_back(0);
    if (broken == 12) opt.positions[0] = special();
  }

  const nbm::CooMatrix Mc = to_coo(fdp, M), Kc = to_coo(fdp, K);
  // The core knows only `fixed`: the tgv dofs join it, as in the binding.
  if (!nbm_fuzz::accepted([&] { opt.fixed = nbm_binding::dirichlet_dofs(Mc, Kc, opt.fixed); }))
    return 0;
  const bool nbm_scheme = opt.scheme != TimeScheme::kMoreauJean;

  // Time step: from the problem's time scale; for the explicit scheme mostly
  // a fraction of its critical step (read from a first construction).
  opt.dt = T0 * nbm_fuzz::pow10_in(fdp, -3, 0.5);
  if (opt.scheme == TimeScheme::kExplicit && fdp.ConsumeIntegralInRange<int>(0, 3) != 0) {
    nbm::SolverOptions probe = opt;
    probe.dt = 1e-300;
    double critical = 0;
    nbm_fuzz::accepted([&] { critical = nbm::Solver(Mc, Kc, contact, probe).critical_dt(); });
    if (critical > 0) opt.dt = critical * nbm_fuzz::uniform(fdp, 0.01, 1);
  }
  if (broken == 13) opt.dt = fdp.ConsumeBool() ? special() : -opt.dt;

  // Initial state and loads.
  std::vector<double> u(n, 0.0), v(n, 0.0), F0(n);
  if (fdp.ConsumeBool())
    for (int i = 0; i < n; ++i) u[i] = sg * nbm_fuzz::uniform(fdp, -0.5, 0.5);
  if (fdp.ConsumeBool())
    for (int i = 0; i < n; ++i) v[i] = sg / T0 * nbm_fuzz::uniform(fdp, -1, 1);
  const double sF = sK * sg * nbm_fuzz::pow10_in(fdp, -2, 2);
  for (int i = 0; i < n; ++i) F0[i] = sF * nbm_fuzz::uniform(fdp, -1, 1);
  if (broken == 14) F0[fdp.ConsumeIntegralInRange<int>(0, n - 1)] = special();

  std::vector<double> F = F0;
  nbm_fuzz::on_fail() = [&] {
    const auto vec = [](const char* name, const auto& x) {
      std::fprintf(stderr, "%s =", name);
      for (const auto& e : x) std::fprintf(stderr, " %.17g", double(e));
      std::fputc('\n', stderr);
    };
    std::fprintf(stderr,
                 "n = %d (d = %d), scheme %s, mass %s, dt = %.17g, beta %.17g, gamma %.17g\n", n, d,
                 nbm::name(opt.scheme), nbm::name(opt.mass), opt.dt, opt.beta.value_or(-1),
                 opt.gamma.value_or(-1));
    for (const auto& [name, A] : {std::pair{"K", &K}, {"M", &M}}) {
      std::fprintf(stderr, "%s =\n", name);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) std::fprintf(stderr, " %.17g", (*A)(i, j));
        std::fputc('\n', stderr);
      }
    }
    vec("cdofs", contact.dofs), vec("normals", contact.normals), vec("gaps", contact.gaps);
    vec("fixed", opt.fixed), vec("positions", opt.positions);
    vec("u", u), vec("v", v), vec("F", F);
  };
  std::unique_ptr<nbm::Solver> S;
  if (!nbm_fuzz::accepted([&] { S = std::make_unique<nbm::Solver>(Mc, Kc, contact, opt); }))
    return 0;
  if (S->n_dofs() != n || S->n_contact() != nc) fail("sizes %ld, %ld", S->n_dofs(), S->n_contact());
  if (S->fixed_dofs() != opt.fixed) fail("fixed_dofs() differs from the fixed option");
  const double lM = lambda_min_free(M, opt.fixed), lK = lambda_min_free(K, opt.fixed);
  // With the massless boundary the contact rows carry no inertia: they
  // respond statically, up to |F| / lambda_min(K), within a step.
  const double load_factor =
      opt.mass == nbm::MassTreatment::kRedistributed ? 1 / lK : std::min(opt.dt * opt.dt / lM, 1 / lK);
  const StateScale state_scale{opt.dt, load_factor};
  const double scale0 = std::max(max_abs(u), state_scale.load_factor * max_abs(F0));
  if (!nbm_fuzz::accepted([&] { S->initialize(u, v, F0); })) return 0;
  double scale = state_scale(*S, u, v, F0);
  check_state(*S, u, v, contact.gaps, nbm_scheme, extreme, scale0, scale, "initialization");

  for (int s = 0; s < steps; ++s) {
    if (fdp.ConsumeBool())
      for (int i = 0; i < n; ++i) F[i] = F0[i] + sF * nbm_fuzz::uniform(fdp, -1, 1);
    const double before = std::max(scale, state_scale.load_factor * max_abs(F));
    if (!nbm_fuzz::accepted([&] { S->step(u, v, F); })) return 0;
    scale = state_scale(*S, u, v, F);
    check_state(*S, u, v, contact.gaps, nbm_scheme, extreme, before, scale, "step");
  }
  return 0;
}
