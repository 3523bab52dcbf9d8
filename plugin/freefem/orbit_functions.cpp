// FreeFEM functions of the periodic-orbit solvers (core: plugin/core/periodic):
//
//   real T = nbmPeriodicOrbit(S, u, v, T0, F,            // guess (u, v, T0), load F
//              method = "shooting",                      // or "harmonic-balance"
//              probe = dof, condition = "displacement",  // or "energy", "period"
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
#include <cmath>
#include <fstream>
#include <iostream>

#include "binding.hpp"
#include "user_orbit.hpp"

namespace nbm_binding {
namespace {

const nbm::OrbitReport& orbit_of(NbmHandle* h, const char* function) {
  solver_of(h, function);
  if (!h->orbit)
    fail(std::string(function) + ": no periodic orbit computed yet (call nbmPeriodicOrbit first)");
  return *h->orbit;
}

// Makes `report` the last orbit of h (the last one becomes the previous
// one) and copies its initial state to u, v; returns its period.
double keep(NbmHandle* h, nbm::OrbitReport&& report, KN<double>* u, KN<double>* v) {
  delete h->previous;
  h->previous = h->orbit;
  h->orbit = new nbm::OrbitReport(std::move(report));
  assign(u, h->orbit->u0);
  assign(v, h->orbit->v0);
  return h->orbit->period;
}

class PeriodicOrbit : public E_F0mps {
 public:
  static const int n_name_param = 12;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, u, v, T, F;

  PeriodicOrbit(const basicAC_F0& args, const Expression (&e)[5])
      : handle(e[0]), u(e[1]), v(e[2]), T(e[3]), F(e[4]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmPeriodicOrbit";
    NbmHandle* h = GetAny<NbmHandle*>((*handle)(s));
    nbm::Solver& solver = solver_of(h, fn);
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
    const std::vector<double> uu = vector_of<double>(U, fn, "u");
    const std::vector<double> vv = vector_of<double>(V, fn, "v");
    const std::vector<double> FF = vector_of<double>(GetAny<KN<double>*>((*F)(s)), fn, "F");
    const double T0 = GetAny<double>((*T)(s));
    auto report = guarded(fn, [&] {
      return nbm::periodic_orbit(solver.problem(), FF, uu, vv, T0, o);
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
};

class PeriodicOrbitOp : public OneOperator {
 public:
  PeriodicOrbitOp()
      : OneOperator(atype<double>(), atype<NbmHandle*>(), atype<KN<double>*>(),
                    atype<KN<double>*>(), atype<double>(), atype<KN<double>*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[5];
    for (int k = 0; k < 5; ++k) e[k] = t[k]->CastTo(args[k]);
    return new PeriodicOrbit(args, e);
  }
};

double continue_orbit(NbmHandle* const& h, KN<double>* const& u, KN<double>* const& v,
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

long orbit_state(NbmHandle* const& h, const double& t, KN<double>* const& u,
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

long orbit_multipliers(NbmHandle* const& h, KN<double>* const& re, KN<double>* const& im) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitMultipliers");
  assign(re, o.multipliers_re);
  assign(im, o.multipliers_im);
  return static_cast<long>(o.multipliers_re.size());
}

long orbit_residuals(NbmHandle* const& h, KN<double>* const& r) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitResiduals");
  assign(r, std::vector<double>{o.periodicity_residual, o.complementarity_residual,
                                o.trivial_residual, o.balance_residual, o.truncation,
                                o.reduction_residual});
  return 6;
}

long orbit_energies(NbmHandle* const& h, KN<double>* const& e) {
  assign(e, orbit_of(h, "nbmOrbitEnergies").energies);
  return 4;
}

double orbit_contact_time(NbmHandle* const& h) {
  return orbit_of(h, "nbmOrbitContactTime").contact_time;
}
long orbit_switches(NbmHandle* const& h) { return orbit_of(h, "nbmOrbitSwitches").switches; }
long orbit_stable(NbmHandle* const& h) { return orbit_of(h, "nbmOrbitStable").stable; }

long orbit_harmonics(NbmHandle* const& h, KNM<double>* const& C) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitHarmonics");
  if (o.harmonics == 0)
    fail("nbmOrbitHarmonics: the last orbit was not computed by harmonic balance");
  const long cols = 2 * o.harmonics + 1, rows = static_cast<long>(o.u0.size());
  C->resize(rows, cols);
  for (long i = 0; i < rows; ++i)
    for (long k = 0; k < cols; ++k) (*C)(i, k) = o.coefficients[i * cols + k];
  return o.harmonics;
}

long orbit_summary(NbmHandle* const& h, string* const& file) {
  const nbm::OrbitReport& o = orbit_of(h, "nbmOrbitSummary");
  std::cout << o.summary;
  if (file && !file->empty()) {
    std::ofstream f(*file);
    if (!f) fail("nbmOrbitSummary: cannot write " + *file);
    f << o.summary;
  }
  return 0;
}

}  // namespace

void load_orbit_functions() {
  using H = NbmHandle*;
  using R = KN<double>*;
  Global.Add("nbmPeriodicOrbit", "(", new PeriodicOrbitOp);
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
