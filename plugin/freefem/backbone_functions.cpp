// FreeFEM function of the backbones from grazing (core:
// plugin/core/periodic/backbone.hpp, user_backbone.hpp; method.md §6):
//
//   int n = nbmBackbone(S, F, mode, points, step, "backbone.csv",
//                       half = true,       // half-period shooting (false: full)
//                       energy = Emax,     // stop past this vibration energy
//                       iterations = 50,   // Newton iterations per orbit
//                       probe = i,         // the dof of probe_amplitude (default: the
//                                          // dof of largest amplitude at grazing)
//                       table = P,         // real[int,int] n x 12, the CSV's numbers
//                       branch = "arclength" | "frequency", with the latter
//                       frequencyStep = 0.002, energyJump = 0.4, skips = 3,
//                       to = omegaMax       // (user_backbone.hpp, BackboneOptions)
//                       modes = 0);        // > 0: on a reduced basis (as nbmPeriodicOrbit)
//
// The backbone of linear mode `mode` (0: the lowest of the system with every
// contact open) under the constant load F: its grazing orbit, then up to
// `points` - 1 pseudo-arclength steps of `step`. Prints a summary (linear
// frequency, grazing amplitude, why it stopped); writes one CSV row per orbit
// ("" for no file):
//   omega,period,energy,amplitude,contact_time,switches,max_multiplier,stable,periodicity,
//   probe_amplitude,probe_min,probe_max,events
// (energy and amplitude about the static state; probe_amplitude: (max - min) / 2
// of u[probe] over the period, the amplitude nbmForcedResponse reports; events:
// grazing, fold-frequency, fold-energy, stability; user_backbone.hpp). Returns
// the number of orbits. The last two orbits become the object's last orbits:
// the nbmOrbit* functions read the last one (nbmOrbitState, ...), and
// nbmContinueOrbit goes on along the backbone from them; nbmSelectOrbit
// picks any other by index (orbit_functions.cpp).
#include <fstream>
#include <iostream>

// user_backbone.hpp first: binding.hpp's choice_of finds nbm::name(Branch)
// where it is defined.
#include "periodic/user_backbone.hpp"
#include "binding.hpp"

namespace nbm_binding {
namespace {

class Backbone : public E_F0mps {
 public:
  static const int n_name_param = 11;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, F, mode, points, step, file;

  Backbone(const basicAC_F0& args, const Expression (&e)[6])
      : handle(e[0]), F(e[1]), mode(e[2]), points(e[3]), step(e[4]), file(e[5]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    const char* fn = "nbmBackbone";
    ModelHandle* h = GetAny<ModelHandle*>((*handle)(s));
    const nbm::Model& model = periodic_model_of(h, fn);
    nbm::BackboneOptions o;
    o.points = GetAny<long>((*points)(s));
    o.step = GetAny<double>((*step)(s));
    if (nargs[0]) o.half_period = GetAny<bool>((*nargs[0])(s));
    if (nargs[1]) o.max_energy = GetAny<double>((*nargs[1])(s));
    if (nargs[2]) o.max_iterations = static_cast<int>(GetAny<long>((*nargs[2])(s)));
    KNM<double>* table = nargs[3] ? GetAny<KNM<double>*>((*nargs[3])(s)) : nullptr;
    if (nargs[4]) o.probe = GetAny<long>((*nargs[4])(s));
    if (nargs[5]) o.modes = static_cast<int>(GetAny<long>((*nargs[5])(s)));
    using Branch = nbm::BackboneOptions::Branch;
    if (nargs[6])
      o.branch = choice_of(*GetAny<string*>((*nargs[6])(s)), fn, "branch",
                           {Branch::arclength, Branch::frequency});
    const char* frequency_only[] = {"frequencyStep", "energyJump", "skips", "to"};
    for (int k = 7; k < 11; ++k)
      if (nargs[k] && o.branch != Branch::frequency)
        fail(std::string(fn) + ": " + frequency_only[k - 7] +
             ": only with branch = \"frequency\" (the arclength branch has no use for it)");
    if (nargs[7]) o.frequency_step = GetAny<double>((*nargs[7])(s));
    if (nargs[8]) o.energy_jump = GetAny<double>((*nargs[8])(s));
    if (nargs[9]) o.max_skips = static_cast<int>(GetAny<long>((*nargs[9])(s)));
    if (nargs[10]) o.max_omega = GetAny<double>((*nargs[10])(s));
    const std::vector<double> FF = vector_of<double>(GetAny<KN<double>*>((*F)(s)), fn, "F");
    const long j = GetAny<long>((*mode)(s));
    const string* name = GetAny<string*>((*file)(s));
    std::ofstream csv;  // opened first: a bad file name fails before the computation
    if (name && !name->empty()) {
      csv.open(*name);
      if (!csv) fail(std::string(fn) + ": cannot write " + *name);
      csv.precision(12);
      csv << "omega,period,energy,amplitude,contact_time,switches,max_multiplier,stable,"
             "periodicity,probe_amplitude,probe_min,probe_max,events\n";
    }
    nbm::BackboneReport r = guarded(fn, [&] { return nbm::backbone(model.problem(), FF, j, o); });
    // Its orbits become the object's curve (nbmSelectOrbit), its last two
    // the last orbits: nbmOrbit* read the last one, nbmContinueOrbit goes on
    // along the backbone.
    guarded(fn, [&] { h->select(*r.orbits, r.orbits->size() - 1); });
    h->set_curve(r.orbits, nullptr);
    std::cout << r.summary;
    const long n = static_cast<long>(r.points.size());
    constexpr int columns = 12;
    if (table) table->resize(n, columns);
    for (int k = 0; k < static_cast<int>(n); ++k) {
      const nbm::BackbonePointReport& p = r.points[k];
      const double row[columns] = {p.omega, p.period, p.energy, p.amplitude, p.contact_time,
                                   static_cast<double>(p.switches), p.max_multiplier,
                                   p.stable ? 1.0 : 0.0, p.periodicity_residual,
                                   p.probe_amplitude, p.probe_min, p.probe_max};
      for (int c = 0; c < columns; ++c) {
        if (table) (*table)(k, c) = row[c];
        if (csv.is_open()) csv << row[c] << ",";
      }
      if (csv.is_open()) csv << p.events << "\n";
    }
    return SetAny<long>(n);
  }
  operator aType() const override { return atype<long>(); }
};

basicAC_F0::name_and_type Backbone::name_param[] = {
    {"half", &typeid(bool)},
    {"energy", &typeid(double)},
    {"iterations", &typeid(long)},
    {"table", &typeid(KNM<double>*)},
    {"probe", &typeid(long)},
    {"modes", &typeid(long)},
    {"branch", &typeid(string*)},
    {"frequencyStep", &typeid(double)},
    {"energyJump", &typeid(double)},
    {"skips", &typeid(long)},
    {"to", &typeid(double)},
};

class BackboneOp : public OneOperator {
 public:
  BackboneOp()
      : OneOperator(atype<long>(), atype<ModelHandle*>(), atype<KN<double>*>(), atype<long>(),
                    atype<long>(), atype<double>(), atype<string*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[6];
    for (int k = 0; k < 6; ++k) e[k] = t[k]->CastTo(args[k]);
    return new Backbone(args, e);
  }
};

}  // namespace

void load_backbone_functions() { Global.Add("nbmBackbone", "(", new BackboneOp); }

}  // namespace nbm_binding
