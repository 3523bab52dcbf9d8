// FreeFEM functions of the periodic-orbit solvers (core: plugin/core/periodic).
// They take the model, an NBMModel Mo (no time step, no time-stepping
// factorization) or an NBM object S (its model); S below is either:
//
//   real T = nbmPeriodicOrbit(S, u, v, T0, F,            // guess (u, v, T0), load F
//              method = "shooting",                      // or "harmonic-balance"
//              probe = dof,                              // amplitude of this dof
//              phase = dof, condition = "displacement",  // or "energy", "period"
//              amplitude = a,                            // default: the guess's
//              half = true,                              // shooting from a state at rest
//              harmonics = 20, cosine = true,            // harmonic balance
//              integration = "exact", adaptive = false, truncation = 1e-6,
//              iterations = 50, modes = 0);           // modes > 0: reduced basis
//   // u, v now hold the orbit's state at t = 0.
//   real T = nbmContinueOrbit(S, u, v, step);  // the next orbit of the family
//   // through the two last orbits (pseudo-arclength, shooting); then, on the
//   // last orbit:
//   nbmOrbitState(S, t, u, v);        // the state at time t (exact flow)
//   nbmOrbitMultipliers(S, re, im);   // Floquet multipliers
//   nbmOrbitResiduals(S, r);          // periodicity, complementarity, trivial
//                                     // multiplier, Galerkin residual, truncation,
//                                     // reduction (full-model residual, modes > 0)
//   nbmOrbitEnergies(S, e);           // kinetic, elastic, load, total at t = 0
//   real tc = nbmOrbitContactTime(S); int s = nbmOrbitSwitches(S);
//   int st = nbmOrbitStable(S);
//   nbmOrbitHarmonics(S, C);          // real[int,int] ndof x (2H+1) (harmonic balance)
//   nbmOrbitSummary(S, "file.txt");   // the summary, printed and written
//
// Forced orbits (method.md §9; core: user_forced_orbit.hpp), under the load
// F(t) = F0 + sum_k Fc(:, k-1) cos(k omega t) + Fs(:, k-1) sin(k omega t)
// and moving obstacles, gaps g(t) = g0 + sum_k gapCos(:, k-1) cos(k omega t)
// + gapSin(:, k-1) sin(k omega t) (g0: the model's gaps, method.md §8):
//   real T = nbmForcedOrbit(S, F0, Fc, Fs, omega, u, v,  // guess (u, v) at t = 0
//              rayleighM = aM, rayleighK = bK, // damping C = aM M + bK K (+ the
//                                              // model's damping= matrix, if any);
//                                              // default: the model's coefficients
//              subharmonic = 1,                // period 2 pi m / omega
//              probe = dof,                    // amplitude of this dof (default:
//                                              // the dof of largest amplitude)
//              transient = 0,                  // periods run from the guess first
//              iterations = 50,
//              method = "shooting",            // or "harmonic-balance" (exact
//              harmonics = 20,                 // integration, H harmonics of omega / m)
//              gapCos = gc, gapSin = gs,       // harmonics of the gaps (default: none)
//              modes = 0);                     // > 0: on a reduced basis (as nbmPeriodicOrbit)
//   // Fc, Fs: real[int,int] ndof x H (column k-1: harmonic k; either may have
//   // fewer columns, even 0) or real[int] of size ndof (one harmonic, or size 0:
//   // none); on the contact dofs they move the nodal boundary relation like the
//   // gaps. gapCos, gapSin: of the same kind as Fc, Fs, one row (or entry) per
//   // contact node (the order of the gaps). u, v hold the orbit's state
//   // at t = 0 (and at every t = k T: no phase condition, time is the
//   // excitation's); the period T = 2 pi m / omega is returned. The nbmOrbit*
//   // functions above read the last forced orbit too (no trivial multiplier:
//   // stable iff all |mu| < 1); nbmContinueOrbit refuses it. With modes = m,
//   // on the reduced basis of nbmPeriodicOrbit (nbmOrbitResiduals: the full
//   // model's residual along the orbit, damping and excitation included).
//   // With mass = "redistributed", aM multiplies the
//   // redistributed mass, as in the time steppers. Harmonic balance starts
//   // from the Fourier series of the exact flow from (u, v) and reports like
//   // nbmPeriodicOrbit's (nbmOrbitHarmonics; nbmOrbitResiduals: Galerkin
//   // residual, truncation); u, v get the series' state at t = 0.
//   int n = nbmForcedResponse(S, F0, Fc, Fs, omega, u, v,  // the forced orbit as above,
//              (the named arguments of nbmForcedOrbit),   // then its response curve
//              parameter = "omega",            // or "amplitude": a factor on Fc, Fs,
//                                              // gapCos, gapSin (1 at start)
//              to = pEnd, from = pOther,       // heads towards `to`, stays in [from, to]
//                                              // (from: default the start)
//              step = 0.02, maxStep = 0.2,     // arclength steps (scaled unknowns)
//              points = 200, locate = true,    // events by bisection (else interpolated)
//              file = "curve.csv",             // a row per point (user_forced_orbit.hpp)
//              curve = C, events = E);         // real[int,int]: a row per point: omega,
//                                              // scale, arclength, amplitude, probe min, max,
//                                              // energy, largest energy, contact time,
//                                              // switches, min gap, max |mu|, stable,
//                                              // periodicity; a row per event: kind (0 fold,
//                                              // 1 period doubling, 2 Neimark-Sacker,
//                                              // 3 grazing), parameter, point past it, mu
//                                              // (re, im), arclength
//   // Pseudo-arclength continuation (core: forced_continuation.hpp): returns
//   // the number of points; u, v and the last orbit are the last point's.
//   // With doubling = true (method.md §9, branch switching): at the curve's
//   // first period doubling, the period-2m orbit (doublingAmplitude = 1e-3:
//   // its offset along the critical eigenvector, scaled unknowns) and its
//   // branch over the same range (doubled = D, doubledFile = "...": rows and
//   // CSV as curve, file); u, v and the last orbit are then that period-2m
//   // orbit (subharmonic 2m). No period doubling: an ExecError.
//   real a = nbmOrbitAmplitude(S);    // (max - min) / 2 of u[probe] over a period
//   nbmOrbitProbe(S, r);              // probe dof, min, max, largest total energy
//   // (every orbit: probe = the dof whose amplitude is reported, in every call).
//   real T = nbmSelectOrbit(S, k, u, v, doubled = false);
//   // orbit k (0: the first point) of the last backbone or response curve
//   // (doubled = true: of its period-doubled branch) becomes the last orbit,
//   // orbit k - 1 the previous one; u, v get its state at t = 0, as after
//   // nbmPeriodicOrbit: every nbmOrbit* accessor reads it, time integration
//   // can start from it, nbmContinueOrbit goes on along a backbone from it.
#include <cmath>
#include <fstream>
#include <iostream>

#include "binding.hpp"
#include "periodic/user_forced_orbit.hpp"
#include "periodic/user_orbit.hpp"

namespace nbm_binding {
namespace {

const nbm::OrbitReport& orbit_of(ModelHandle* h, const char* function) {
  model_of(h, function);
  if (!h->orbit)
    fail(std::string(function) + ": no periodic orbit computed yet (call nbmPeriodicOrbit first)");
  return *h->orbit;
}

// Copies the initial state of the last orbit of h to u, v; returns its period.
double keep_state(ModelHandle* h, KN<double>* u, KN<double>* v) {
  assign(u, h->orbit->u0);
  assign(v, h->orbit->v0);
  return h->orbit->period;
}

// Makes `report` the last orbit of h (the last one becomes the previous
// one) and copies its initial state to u, v; returns its period.
double keep(ModelHandle* h, nbm::OrbitReport&& report, KN<double>* u, KN<double>* v) {
  h->remember(std::move(report));
  return keep_state(h, u, v);
}

class PeriodicOrbit : public E_F0mps {
 public:
  static const int n_name_param = 13;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, u, v, T, F;

  PeriodicOrbit(const basicAC_F0& args, const Expression (&e)[5])
      : handle(e[0]), u(e[1]), v(e[2]), T(e[3]), F(e[4]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmPeriodicOrbit";
    ModelHandle* h = GetAny<ModelHandle*>((*handle)(s));
    const nbm::Model& model = periodic_model_of(h, fn);
    KN<double>* U = GetAny<KN<double>*>((*u)(s));
    KN<double>* V = GetAny<KN<double>*>((*v)(s));
    if (U == V) fail(std::string(fn) + ": u and v must be different arrays");
    nbm::OrbitOptions o;
    if (nargs[0]) o.method = *GetAny<string*>((*nargs[0])(s));
    if (nargs[1]) o.probe = GetAny<long>((*nargs[1])(s));
    if (nargs[2]) o.condition = *GetAny<string*>((*nargs[2])(s));
    if (nargs[3]) o.amplitude = GetAny<double>((*nargs[3])(s));
    if (nargs[4]) o.half_period = GetAny<bool>((*nargs[4])(s));
    if (nargs[5]) o.harmonics = static_cast<int>(GetAny<long>((*nargs[5])(s)));
    if (nargs[6]) o.cosine_only = GetAny<bool>((*nargs[6])(s));
    if (nargs[7]) o.integration = *GetAny<string*>((*nargs[7])(s));
    if (nargs[8]) o.adaptive = GetAny<bool>((*nargs[8])(s));
    if (nargs[9]) o.truncation_tolerance = GetAny<double>((*nargs[9])(s));
    if (nargs[10]) o.max_iterations = static_cast<int>(GetAny<long>((*nargs[10])(s)));
    if (nargs[11]) o.modes = static_cast<int>(GetAny<long>((*nargs[11])(s)));
    if (nargs[12]) o.phase = GetAny<long>((*nargs[12])(s));
    const std::vector<double> uu = vector_of<double>(U, fn, "u");
    const std::vector<double> vv = vector_of<double>(V, fn, "v");
    const std::vector<double> FF = vector_of<double>(GetAny<KN<double>*>((*F)(s)), fn, "F");
    const double T0 = GetAny<double>((*T)(s));
    auto report = guarded(fn, [&] {
      return nbm::periodic_orbit(model.problem(), FF, uu, vv, T0, o);
    });
    return SetAny<double>(keep(h, std::move(report), U, V));
  }
  operator aType() const override { return atype<double>(); }
};

basicAC_F0::name_and_type PeriodicOrbit::name_param[] = {
    {"method", &typeid(string*)},  {"probe", &typeid(long)},
    {"condition", &typeid(string*)}, {"amplitude", &typeid(double)},
    {"half", &typeid(bool)},        {"harmonics", &typeid(long)},
    {"cosine", &typeid(bool)},      {"integration", &typeid(string*)},
    {"adaptive", &typeid(bool)},    {"truncation", &typeid(double)},
    {"iterations", &typeid(long)},  {"modes", &typeid(long)},
    {"phase", &typeid(long)},
};

class PeriodicOrbitOp : public OneOperator {
 public:
  PeriodicOrbitOp()
      : OneOperator(atype<double>(), atype<ModelHandle*>(), atype<KN<double>*>(),
                    atype<KN<double>*>(), atype<double>(), atype<KN<double>*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[5];
    for (int k = 0; k < 5; ++k) e[k] = t[k]->CastTo(args[k]);
    return new PeriodicOrbit(args, e);
  }
};

// The harmonics of one load list (Fc or Fs): the columns of a
// real[int,int], or one real[int] (size 0: none).
std::vector<std::vector<double>> harmonics_of(KNM<double>* A, const char* fn, const char* name) {
  if (!A) fail(std::string(fn) + ": array " + name + " is missing");
  std::vector<std::vector<double>> list(A->M(), std::vector<double>(A->N()));
  for (long k = 0; k < A->M(); ++k)
    for (long i = 0; i < A->N(); ++i) list[k][i] = (*A)(i, k);
  return list;
}
std::vector<std::vector<double>> harmonics_of(KN<double>* x, const char* fn, const char* name) {
  std::vector<double> one = vector_of<double>(x, fn, name);
  if (one.empty()) return {};
  return {std::move(one)};
}

// The options of a forced orbit from the first six named arguments
// (rayleighM, rayleighK, subharmonic, probe, transient, iterations) of
// nbmForcedOrbit and nbmForcedResponse; the damping defaults to the
// model's Rayleigh coefficients, and its damping matrix (if any) is always
// part of the model.
nbm::ForcedOrbitOptions forced_options(const nbm::Model& model, const Expression* nargs,
                                       Stack s, double omega, const char* fn) {
  const nbm::ModelOptions& so = model.options();
  nbm::ForcedOrbitOptions o;
  o.omega = omega;
  o.rayleigh_mass = nargs[0] ? GetAny<double>((*nargs[0])(s)) : so.rayleigh_mass;
  o.rayleigh_stiffness = nargs[1] ? GetAny<double>((*nargs[1])(s)) : so.rayleigh_stiffness;
  o.damping = so.damping;
  if (nargs[2]) o.subharmonic = static_cast<int>(GetAny<long>((*nargs[2])(s)));
  if (nargs[3]) o.probe = GetAny<long>((*nargs[3])(s));
  if (nargs[4]) o.transient_periods = static_cast<int>(GetAny<long>((*nargs[4])(s)));
  if (nargs[5]) o.max_iterations = static_cast<int>(GetAny<long>((*nargs[5])(s)));
  return o;
}

// The positional arguments shared by nbmForcedOrbit and nbmForcedResponse,
// (S, F0, Fc, Fs, omega, u, v): H is KNM<double>* (one column per harmonic)
// or KN<double>* (one harmonic).
struct ForcedInputs {
  ModelHandle* h;
  const nbm::Model* model;
  KN<double>* U;
  KN<double>* V;
  nbm::ForcedOrbitOptions options;
  std::vector<double> u, v, F0;
  std::vector<std::vector<double>> cosines, sines;
};

template <class H>
class ForcedCall : public E_F0mps {
 public:
  Expression handle, F0, Fc, Fs, omega, u, v;

  explicit ForcedCall(const Expression (&e)[7])
      : handle(e[0]), F0(e[1]), Fc(e[2]), Fs(e[3]), omega(e[4]), u(e[5]), v(e[6]) {}

  /// The inputs, checked; `nargs` begins with the six named arguments of
  /// forced_options, and holds gapCos, gapSin, modes at `gaps`, `gaps` + 1,
  /// `gaps` + 2. A single orbit (`one_orbit`) on a model whose obstacle=
  /// moves takes the obstacle's gap harmonics at omega
  /// (Model::with_obstacle_harmonics); that model replaces the handle's
  /// linearised one, and the orbits computed on it go.
  ForcedInputs gather(Stack s, const Expression* nargs, int gaps, const char* fn,
                      bool one_orbit = false) const {
    ForcedInputs in;
    in.h = GetAny<ModelHandle*>((*handle)(s));
    const double w = GetAny<double>((*omega)(s));
    const nbm::Model& held = model_of(in.h, fn);
    nbm::ObstacleHarmonics moving;
    if (one_orbit && held.obstacle_moves()) {
      if (nargs[gaps] || nargs[gaps + 1])
        fail(std::string(fn) + ": gapCos, gapSin: given with an obstacle= that moves by its own "
             "law, whose motion gives the gap harmonics");
      moving = guarded(fn, [&] { return held.with_obstacle_harmonics(w); });
      in.h->forget_orbits();
      delete in.h->linearised;
      in.h->linearised = new std::shared_ptr<const nbm::Model>(moving.model);
      in.model = moving.model.get();
    } else {
      in.model = &periodic_model_of(in.h, fn);
    }
    in.U = GetAny<KN<double>*>((*u)(s));
    in.V = GetAny<KN<double>*>((*v)(s));
    if (in.U == in.V) fail(std::string(fn) + ": u and v must be different arrays");
    in.options = forced_options(*in.model, nargs, s, w, fn);
    in.options.gap_cos = std::move(moving.gap_cos);
    in.options.gap_sin = std::move(moving.gap_sin);
    in.u = vector_of<double>(in.U, fn, "u");
    in.v = vector_of<double>(in.V, fn, "v");
    in.F0 = vector_of<double>(GetAny<KN<double>*>((*F0)(s)), fn, "F0");
    in.cosines = harmonics_of(GetAny<H>((*Fc)(s)), fn, "Fc");
    in.sines = harmonics_of(GetAny<H>((*Fs)(s)), fn, "Fs");
    if (nargs[gaps]) in.options.gap_cos = harmonics_of(GetAny<H>((*nargs[gaps])(s)), fn, "gapCos");
    if (nargs[gaps + 1])
      in.options.gap_sin = harmonics_of(GetAny<H>((*nargs[gaps + 1])(s)), fn, "gapSin");
    if (nargs[gaps + 2])
      in.options.modes = static_cast<int>(GetAny<long>((*nargs[gaps + 2])(s)));
    return in;
  }
};

// The FreeFEM operator of a ForcedCall: (S, F0, Fc, Fs, omega, u, v) typed
// for H, returning R.
template <class Call, class H, class R>
class ForcedOp : public OneOperator {
 public:
  ForcedOp()
      : OneOperator(atype<R>(), atype<ModelHandle*>(), atype<KN<double>*>(), atype<H>(),
                    atype<H>(), atype<double>(), atype<KN<double>*>(), atype<KN<double>*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[7];
    for (int k = 0; k < 7; ++k) e[k] = t[k]->CastTo(args[k]);
    return new Call(args, e);
  }
};

// nbmForcedOrbit(S, F0, Fc, Fs, omega, u, v, ...).
template <class H>
class ForcedOrbit : public ForcedCall<H> {
 public:
  static const int n_name_param = 11;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];

  ForcedOrbit(const basicAC_F0& args, const Expression (&e)[7]) : ForcedCall<H>(e) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmForcedOrbit";
    ForcedInputs in = this->gather(s, nargs, 8, fn, true);
    if (nargs[6]) in.options.method = *GetAny<string*>((*nargs[6])(s));
    if (nargs[7]) in.options.harmonics = static_cast<int>(GetAny<long>((*nargs[7])(s)));
    auto report = guarded(fn, [&] {
      return nbm::forced_orbit(in.model->problem(), in.F0, in.cosines, in.sines, in.u, in.v,
                               in.options);
    });
    return SetAny<double>(keep(in.h, std::move(report), in.U, in.V));
  }
  operator aType() const override { return atype<double>(); }
};

template <class H>
basicAC_F0::name_and_type ForcedOrbit<H>::name_param[] = {
    {"rayleighM", &typeid(double)}, {"rayleighK", &typeid(double)},
    {"subharmonic", &typeid(long)}, {"probe", &typeid(long)},
    {"transient", &typeid(long)},   {"iterations", &typeid(long)},
    {"method", &typeid(string*)},   {"harmonics", &typeid(long)},
    {"gapCos", &typeid(H)},         {"gapSin", &typeid(H)},
    {"modes", &typeid(long)},
};

// nbmForcedResponse(S, F0, Fc, Fs, omega, u, v, ...): the named arguments
// of nbmForcedOrbit, then those of the continuation.
int event_code(const std::string& kind) {
  if (kind == "fold") return 0;
  if (kind == "period doubling") return 1;
  if (kind == "Neimark-Sacker") return 2;
  return 3;  // grazing
}

// The rows of `curve = C` (and `doubled = D`): a row per point.
void curve_rows(const std::vector<nbm::ForcedResponsePoint>& points, KNM<double>* C) {
  C->resize(points.size(), 14);
  for (long k = 0; k < static_cast<long>(points.size()); ++k) {
    const nbm::ForcedResponsePoint& p = points[k];
    const double row[14] = {p.omega, p.scale, p.arclength, p.amplitude, p.probe_min,
                            p.probe_max, p.energy, p.energy_max, p.contact_time,
                            static_cast<double>(p.switches), p.min_gap,
                            p.moduli.empty() ? 0.0 : p.moduli[0],
                            p.stable ? 1.0 : 0.0, p.periodicity_residual};
    for (long j = 0; j < 14; ++j) (*C)(k, j) = row[j];
  }
}

template <class H>
class ForcedResponse : public ForcedCall<H> {
 public:
  static const int n_name_param = 23;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];

  ForcedResponse(const basicAC_F0& args, const Expression (&e)[7]) : ForcedCall<H>(e) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmForcedResponse";
    const ForcedInputs in = this->gather(s, nargs, 20, fn);
    nbm::ForcedResponseOptions r;
    if (nargs[6]) r.parameter = *GetAny<string*>((*nargs[6])(s));
    if (nargs[7]) r.from = GetAny<double>((*nargs[7])(s));
    if (!nargs[8]) fail(std::string(fn) + ": to: the end of the parameter range is required");
    r.to = GetAny<double>((*nargs[8])(s));
    if (nargs[9]) r.step = GetAny<double>((*nargs[9])(s));
    r.max_step = nargs[10] ? GetAny<double>((*nargs[10])(s)) : std::max(r.max_step, r.step);
    if (nargs[11]) r.max_points = static_cast<int>(GetAny<long>((*nargs[11])(s)));
    if (nargs[12]) r.locate_events = GetAny<bool>((*nargs[12])(s));
    if (nargs[16]) r.doubling = GetAny<bool>((*nargs[16])(s));
    if (nargs[17]) r.doubling_amplitude = GetAny<double>((*nargs[17])(s));
    if (!r.doubling && (nargs[17] || nargs[18] || nargs[19]))
      fail(std::string(fn) +
           ": doublingAmplitude, doubled, doubledFile: only with doubling = true");
    const std::string file = nargs[13] ? *GetAny<string*>((*nargs[13])(s)) : std::string();
    nbm::ForcedResponse response = guarded(fn, [&] {
      return nbm::forced_response(in.model->problem(), in.F0, in.cosines, in.sines, in.u, in.v,
                                  in.options, r);
    });
    if (!file.empty()) guarded(fn, [&] { nbm::write_forced_response(response, file); });
    if (nargs[14]) curve_rows(response.points, GetAny<KNM<double>*>((*nargs[14])(s)));
    if (nargs[15]) {  // events = E: a row per event
      KNM<double>* E = GetAny<KNM<double>*>((*nargs[15])(s));
      E->resize(response.events.size(), 6);
      for (long k = 0; k < static_cast<long>(response.events.size()); ++k) {
        const nbm::ForcedResponseEvent& e = response.events[k];
        const double row[6] = {static_cast<double>(event_code(e.kind)), e.parameter,
                               static_cast<double>(e.point), e.multiplier_re, e.multiplier_im,
                               e.arclength};
        for (long j = 0; j < 6; ++j) (*E)(k, j) = row[j];
      }
    }
    std::cout << fn << ": " << response.points.size() << " points, " << response.events.size()
              << " events; " << response.stop_reason << std::endl;
    for (const auto& e : response.events) std::cout << "  " << e.description << std::endl;
    const long n = static_cast<long>(response.points.size());
    // The points become the object's curve (nbmSelectOrbit); the last point
    // (or, with doubling, the period-2m orbit) the last orbit.
    guarded(fn, [&] { in.h->select(*response.orbits, n - 1); });
    in.h->set_curve(response.orbits, response.doubling ? response.doubling->branch.orbits
                                                       : nullptr);
    if (!response.doubling) {
      keep_state(in.h, in.U, in.V);
      return SetAny<long>(n);
    }
    // Branch switching: the period-2m branch, and its first orbit as the last one.
    const nbm::ForcedDoubling& d = *response.doubling;
    if (nargs[18]) curve_rows(d.branch.points, GetAny<KNM<double>*>((*nargs[18])(s)));
    const std::string doubledFile = nargs[19] ? *GetAny<string*>((*nargs[19])(s)) : std::string();
    if (!doubledFile.empty())
      guarded(fn, [&] { nbm::write_forced_response(d.branch, doubledFile, "doubledFile"); });
    std::cout << fn << ": period doubling at " << r.parameter << " = " << d.event_parameter
              << ", period-" << 2 * in.options.subharmonic << " orbit at " << d.parameter
              << " (separation over one period before doubling " << d.separation
              << "); its branch: " << d.branch.points.size() << " points, "
              << d.branch.events.size() << " events; " << d.branch.stop_reason << std::endl;
    for (const auto& e : d.branch.events) std::cout << "  " << e.description << std::endl;
    nbm::OrbitReport switched = d.orbit;
    keep(in.h, std::move(switched), in.U, in.V);
    return SetAny<long>(n);
  }
  operator aType() const override { return atype<long>(); }
};

template <class H>
basicAC_F0::name_and_type ForcedResponse<H>::name_param[] = {
    {"rayleighM", &typeid(double)}, {"rayleighK", &typeid(double)},
    {"subharmonic", &typeid(long)}, {"probe", &typeid(long)},
    {"transient", &typeid(long)},   {"iterations", &typeid(long)},
    {"parameter", &typeid(string*)}, {"from", &typeid(double)},
    {"to", &typeid(double)},        {"step", &typeid(double)},
    {"maxStep", &typeid(double)},   {"points", &typeid(long)},
    {"locate", &typeid(bool)},      {"file", &typeid(string*)},
    {"curve", &typeid(KNM<double>*)}, {"events", &typeid(KNM<double>*)},
    {"doubling", &typeid(bool)},    {"doublingAmplitude", &typeid(double)},
    {"doubled", &typeid(KNM<double>*)}, {"doubledFile", &typeid(string*)},
    {"gapCos", &typeid(H)},         {"gapSin", &typeid(H)},
    {"modes", &typeid(long)},
};

double orbit_amplitude(ModelHandle* const& h) {
  return orbit_of(h, "nbmOrbitAmplitude").amplitude;
}
long orbit_probe(ModelHandle* const& h, KN<double>* const& r) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitProbe");
  assign(r, std::vector<double>{static_cast<double>(o.probe), o.probe_min, o.probe_max,
                                o.energy_max});
  return o.probe;
}

double continue_orbit(ModelHandle* const& h, KN<double>* const& u, KN<double>* const& v,
                      const double& step) {
  const char* fn = "nbmContinueOrbit";
  const nbm::OrbitReport& last = orbit_of(h, fn);
  if (!h->previous)
    fail(std::string(fn) + ": needs the two last orbits of a family (call nbmPeriodicOrbit "
                           "twice, for two nearby orbits)");
  if (u == v) fail(std::string(fn) + ": u and v must be different arrays");
  if (!(step > 0) || !std::isfinite(step))
    fail(std::string(fn) + ": step: expected a finite step > 0");
  auto report = guarded(fn, [&] { return nbm::continue_orbit(*h->previous, last, step); });
  return keep(h, std::move(report), u, v);
}

long orbit_state(ModelHandle* const& h, const double& t, KN<double>* const& u,
                 KN<double>* const& v) {
  const char* fn = "nbmOrbitState";
  const nbm::OrbitReport& o = orbit_of(h, fn);
  if (u == v) fail(std::string(fn) + ": u and v must be different arrays");
  if (!(t >= 0) || !std::isfinite(t)) fail(std::string(fn) + ": t: expected a time >= 0");
  std::vector<std::vector<double>> us, vs;
  guarded(fn, [&] { nbm::orbit_states(o, {t}, us, vs); });
  assign(u, us[0]);
  assign(v, vs[0]);
  return 0;
}

long orbit_multipliers(ModelHandle* const& h, KN<double>* const& re, KN<double>* const& im) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitMultipliers");
  assign(re, o.multipliers_re);
  assign(im, o.multipliers_im);
  return static_cast<long>(o.multipliers_re.size());
}

long orbit_residuals(ModelHandle* const& h, KN<double>* const& r) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitResiduals");
  assign(r, std::vector<double>{o.periodicity_residual, o.complementarity_residual,
                                o.trivial_residual, o.balance_residual, o.truncation,
                                o.reduction_residual});
  return 6;
}

long orbit_energies(ModelHandle* const& h, KN<double>* const& e) {
  assign(e, orbit_of(h, "nbmOrbitEnergies").energies);
  return 4;
}

double orbit_contact_time(ModelHandle* const& h) {
  return orbit_of(h, "nbmOrbitContactTime").contact_time;
}
long orbit_switches(ModelHandle* const& h) { return orbit_of(h, "nbmOrbitSwitches").switches; }
long orbit_stable(ModelHandle* const& h) { return orbit_of(h, "nbmOrbitStable").stable; }

long orbit_harmonics(ModelHandle* const& h, KNM<double>* const& C) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitHarmonics");
  if (o.harmonics == 0)
    fail("nbmOrbitHarmonics: the last orbit was not computed by harmonic balance");
  const long cols = 2 * o.harmonics + 1, rows = static_cast<long>(o.u0.size());
  C->resize(rows, cols);
  for (long i = 0; i < rows; ++i)
    for (long k = 0; k < cols; ++k) (*C)(i, k) = o.coefficients[i * cols + k];
  return o.harmonics;
}

long orbit_summary(ModelHandle* const& h, string* const& file) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitSummary");
  std::cout << o.summary;
  if (file && !file->empty()) {
    std::ofstream f(*file);
    if (!f) fail("nbmOrbitSummary: cannot write " + *file);
    f << o.summary;
  }
  return 0;
}

// nbmSelectOrbit(S, k, u, v, doubled = false): orbit k of the last curve.
class SelectOrbit : public E_F0mps {
 public:
  static const int n_name_param = 1;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, point, u, v;

  SelectOrbit(const basicAC_F0& args, const Expression (&e)[4])
      : handle(e[0]), point(e[1]), u(e[2]), v(e[3]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmSelectOrbit";
    ModelHandle* h = GetAny<ModelHandle*>((*handle)(s));
    model_of(h, fn);
    KN<double>* U = GetAny<KN<double>*>((*u)(s));
    KN<double>* V = GetAny<KN<double>*>((*v)(s));
    if (U == V) fail(std::string(fn) + ": u and v must be different arrays");
    const bool branch = nargs[0] && GetAny<bool>((*nargs[0])(s));
    const ModelHandle::Curve* curve = branch ? h->doubled : h->curve;
    if (!curve)
      fail(std::string(fn) + (branch ? ": doubled: the last response curve has no period-doubled "
                                       "branch (nbmForcedResponse with doubling = true)"
                                     : ": no backbone or response curve computed yet (call "
                                       "nbmBackbone or nbmForcedResponse first)"));
    const long k = GetAny<long>((*point)(s));
    const long n = static_cast<long>((*curve)->size());
    if (k < 0 || k >= n)
      fail(std::string(fn) + ": k: point " + std::to_string(k) + " out of range [0, " +
           std::to_string(n) + ") (the points of the last " +
           (branch ? "period-doubled branch" : "backbone or response curve") + ")");
    guarded(fn, [&] { h->select(**curve, static_cast<std::size_t>(k)); });
    return SetAny<double>(keep_state(h, U, V));
  }
  operator aType() const override { return atype<double>(); }
};

basicAC_F0::name_and_type SelectOrbit::name_param[] = {{"doubled", &typeid(bool)}};

class SelectOrbitOp : public OneOperator {
 public:
  SelectOrbitOp()
      : OneOperator(atype<double>(), atype<ModelHandle*>(), atype<long>(), atype<KN<double>*>(),
                    atype<KN<double>*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[4];
    for (int k = 0; k < 4; ++k) e[k] = t[k]->CastTo(args[k]);
    return new SelectOrbit(args, e);
  }
};

}  // namespace

void load_orbit_functions() {
  using H = ModelHandle*;
  using R = KN<double>*;
  Global.Add("nbmPeriodicOrbit", "(", new PeriodicOrbitOp);
  using A = KNM<double>*;  // harmonics as the columns of a real[int,int], or one real[int]
  Global.Add("nbmForcedOrbit", "(", new ForcedOp<ForcedOrbit<A>, A, double>);
  Global.Add("nbmForcedOrbit", "(", new ForcedOp<ForcedOrbit<R>, R, double>);
  Global.Add("nbmForcedResponse", "(", new ForcedOp<ForcedResponse<A>, A, long>);
  Global.Add("nbmForcedResponse", "(", new ForcedOp<ForcedResponse<R>, R, long>);
  Global.Add("nbmSelectOrbit", "(", new SelectOrbitOp);
  Global.Add("nbmOrbitAmplitude", "(", new OneOperator1_<double, H>(orbit_amplitude));
  Global.Add("nbmOrbitProbe", "(", new OneOperator2_<long, H, R>(orbit_probe));
  Global.Add("nbmContinueOrbit", "(", new OneOperator4_<double, H, R, R, double>(continue_orbit));
  Global.Add("nbmOrbitState", "(", new OneOperator4_<long, H, double, R, R>(orbit_state));
  Global.Add("nbmOrbitMultipliers", "(", new OneOperator3_<long, H, R, R>(orbit_multipliers));
  Global.Add("nbmOrbitResiduals", "(", new OneOperator2_<long, H, R>(orbit_residuals));
  Global.Add("nbmOrbitEnergies", "(", new OneOperator2_<long, H, R>(orbit_energies));
  Global.Add("nbmOrbitContactTime", "(", new OneOperator1_<double, H>(orbit_contact_time));
  Global.Add("nbmOrbitSwitches", "(", new OneOperator1_<long, H>(orbit_switches));
  Global.Add("nbmOrbitStable", "(", new OneOperator1_<long, H>(orbit_stable));
  Global.Add("nbmOrbitHarmonics", "(", new OneOperator2_<long, H, KNM<double>*>(orbit_harmonics));
  Global.Add("nbmOrbitSummary", "(", new OneOperator2_<long, H, string*>(orbit_summary));
}

}  // namespace nbm_binding
