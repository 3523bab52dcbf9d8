// FreeFEM binding of the nbm core: the `NBMModel` and `NBM` types and their
// functions.
//
//   load "nbm"
//   NBMModel Mo(M, K, cdofs, normals, gaps, fixed = fixedDofs,
//               mass = "redistributed", positions = xy);  // the structure, once
//   NBM S(Mo, dt = 1e-3, scheme = "newmark", beta = 0.25, gamma = 0.5);
//   NBM A(Mo, dt = 1e-3, scheme = "generalized-alpha", rhoInf = 0.8);  // or "hht-alpha"
//   NBM R(Mo, dt = 1e-3, modes = 20);  // on the reduced model (method.md §6)
//   real r = nbmReductionResidual(R);  // the full model's residual at its state
//   nbmPeriodicOrbit(Mo, u, v, T, F, ...);  // periodic tools take the model
//   NBM S(M, K, cdofs, normals, gaps, dt = 1e-3, ...);  // shorthand: a model
//                                   // of its own (every named argument above)
//   NBM E(..., mass = "redistributed", positions = xy,
//         energy = "monotone");  // or "bounded" (default), method.md §5.1
//   NBM P(M, K, cdofs, normals, gaps, dt = 1e-3, scheme = "moreau-jean",
//         restitution = 0);                           // the impact-law peer
//   NBM D(M, K, cdofs, normals, gaps, dt = 1e-3, rayleighM = aM, rayleighK = bK,
//         damping = C);       // damping C = aM M + bK K + C (method.md §9)
//   nbmInit(S, u, v, F);              // state at t = 0 (u, v updated in place)
//   int it = nbmStep(S, u, v, F);     // one step under the load F at t + dt
//   nbmObstacle(S, g, gdot, gddot);   // a moving obstacle: gaps and rates at
//                                     // the time of the next nbmInit/nbmStep
//   nbmLoadRates(S, Fdot, Fddot);     // a load varying on the contact dofs
//   nbmReplaceContacts(S, cdofs, cnormals, cgaps, u, v, F); // re-linearisation
//   nbmRestart(S, u, v, F, t, a, act [, state]); // exact restart from a saved state
//   nbmReactions(S, lambda); nbmGaps(S, gap); nbmActive(S, act);
//   nbmEnergies(S, e);  real t = nbmTime(S); ...  // e: 7 entries, e[5] dissipated, e[6] load work
//   NBMObstacle bowl("circle", c, radius = R, side = "inside");   // obstacle_functions.cpp
//   NBMModel Mp(..., solver = "mumps");  // the iteration matrix on MUMPS, over the
//                       // ranks of ff-mpirun -np N (default "cholmod"; method.md §4)
//   NBM F(M, K, cdofs, normals, gaps, dt = 1e-3, mass = "redistributed",
//         positions = xy, obstacle = bowl,  // held exactly, frame following the body
//         crossings = "warn");               // or "error": other nodes inside the obstacle
//   long c = nbmCrossings(F);              // those nodes at the last nbmStep
//   int r = nbmMpiRank(), n = nbmMpiSize();  // 0 and 1 unless under ff-mpirun
//
// Only this file sees FreeFEM headers. Every error from the core reaches the
// script as an ExecError whose message names the argument.
#include "binding.hpp"
#include "dirichlet.hpp"
#include "linalg/mpi_ranks.hpp"

using namespace nbm_binding;

namespace {

// The named arguments of a model (NBMModel, and the shorthand NBM), in this
// order.
constexpr int kModelParams = 8;
#define NBM_MODEL_PARAMS                                                        \
  {"fixed", &typeid(KN<long>*)}, {"mass", &typeid(string*)},                    \
      {"positions", &typeid(KN<double>*)}, {"rayleighM", &typeid(double)},      \
      {"rayleighK", &typeid(double)}, {"damping", &typeid(Matrice_Creuse<double>*)}, \
      {"obstacle", &typeid(ObstacleHandle*)}, {"solver", &typeid(string*)}
// The named arguments of a time integrator (NBM), in this order.
constexpr int kSchemeParams = 9;
#define NBM_SCHEME_PARAMS                                                       \
  {"dt", &typeid(double)}, {"scheme", &typeid(string*)}, {"beta", &typeid(double)}, \
      {"gamma", &typeid(double)}, {"restitution", &typeid(double)},             \
      {"energy", &typeid(string*)}, {"crossings", &typeid(string*)},            \
      {"rhoInf", &typeid(double)}, {"modes", &typeid(long)}

// The model of (M, K, cdofs, normals, gaps) and the named arguments `a`
// (NBM_MODEL_PARAMS), built by `function`.
std::shared_ptr<const nbm::Model> build_model(Stack s, const Expression (&e)[5],
                                              const Expression* a, const char* function) {
  nbm::ModelOptions opt;
  if (a[0]) opt.fixed = vector_of<long>(GetAny<KN<long>*>((*a[0])(s)), function, "fixed");
  if (a[1])
    opt.mass = choice_of(*GetAny<string*>((*a[1])(s)), function, "mass",
                         {nbm::MassTreatment::kConsistent, nbm::MassTreatment::kRedistributed});
  if (a[2])
    opt.positions = vector_of<double>(GetAny<KN<double>*>((*a[2])(s)), function, "positions");
  if (a[3]) opt.rayleigh_mass = GetAny<double>((*a[3])(s));
  if (a[4]) opt.rayleigh_stiffness = GetAny<double>((*a[4])(s));
  if (a[5]) opt.damping = coo_of(GetAny<Matrice_Creuse<double>*>((*a[5])(s)), function, "damping");
  if (a[6]) {
    const ObstacleHandle* o = GetAny<ObstacleHandle*>((*a[6])(s));
    if (!o || !o->description)
      fail(std::string(function) + ": obstacle: the NBMObstacle was not constructed");
    opt.obstacle = *o->description;
  }
  if (a[7])
    opt.solver = choice_of(*GetAny<string*>((*a[7])(s)), function, "solver",
                           {nbm::SparseSolver::kCholmod, nbm::SparseSolver::kMumps});
  nbm::ContactDescription contact;
  contact.dofs = vector_of<long>(GetAny<KN<long>*>((*e[2])(s)), function, "contact dofs");
  contact.normals = vector_of<double>(GetAny<KN<double>*>((*e[3])(s)), function, "normals");
  contact.gaps = vector_of<double>(GetAny<KN<double>*>((*e[4])(s)), function, "gaps");
  const nbm::CooMatrix Mc = coo_of(GetAny<Matrice_Creuse<double>*>((*e[0])(s)), function, "M");
  const nbm::CooMatrix Kc = coo_of(GetAny<Matrice_Creuse<double>*>((*e[1])(s)), function, "K");
  // on()'s conventions: the dofs with a tgv penalty join fixed=.
  opt.fixed = guarded(function, [&] { return dirichlet_dofs(Mc, Kc, std::move(opt.fixed)); });
  return guarded(function,
                 [&] { return std::make_shared<const nbm::Model>(Mc, Kc, contact, opt); });
}

// Builds the time integrator of `model` with the named arguments `a`
// (NBM_SCHEME_PARAMS) into h.
void build_solver(Stack s, NbmHandle* h, std::shared_ptr<const nbm::Model> model,
                  const Expression* a) {
  nbm::SchemeOptions opt;
  if (!a[0]) fail("NBM: the time step dt=... is required");
  opt.dt = GetAny<double>((*a[0])(s));
  if (a[1])
    opt.scheme = choice_of(*GetAny<string*>((*a[1])(s)), "NBM", "scheme",
                           {nbm::TimeScheme::kNewmark, nbm::TimeScheme::kGeneralizedAlpha,
                            nbm::TimeScheme::kHhtAlpha, nbm::TimeScheme::kExplicit,
                            nbm::TimeScheme::kMoreauJean});
  if (a[2]) opt.beta = GetAny<double>((*a[2])(s));
  if (a[3]) opt.gamma = GetAny<double>((*a[3])(s));
  if (a[4]) opt.restitution = GetAny<double>((*a[4])(s));
  if (a[5])
    opt.energy = choice_of(*GetAny<string*>((*a[5])(s)), "NBM", "energy",
                           {nbm::EnergyControl::kBounded, nbm::EnergyControl::kMonotone,
                            nbm::EnergyControl::kNone});
  if (a[7]) opt.rho_inf = GetAny<double>((*a[7])(s));
  if (a[8]) {
    const long modes = GetAny<long>((*a[8])(s));
    if (modes < 1 || modes > std::numeric_limits<int>::max())
      fail("NBM: modes: " + std::to_string(modes) +
           ", expected a number of fixed-interface modes >= 1 (method.md §6)");
    opt.modes = static_cast<int>(modes);
  }
  bool fatal = false;
  if (a[6]) {
    const string mode = *GetAny<string*>((*a[6])(s));
    if (mode != "warn" && mode != "error")
      fail("NBM: crossings: \"" + mode + "\", expected \"warn\" or \"error\"");
    if (!model->options().obstacle) fail("NBM: crossings: given without obstacle=, which it watches");
    fatal = mode == "error";
  }
  nbm::Solver* solver = guarded("NBM", [&] { return new nbm::Solver(model, opt); });
  h->destroy();  // the old solver and any orbit computed on it
  h->solver = solver;
  h->set_model(std::move(model));
  h->crossings_fatal = fatal;
}

// A constructor from (M, K, cdofs, normals, gaps) after the handle, with
// the N named arguments of Derived::name_param.
template <class Derived, int N>
class ConstructFromMatrices : public E_F0mps {
 public:
  static const int n_name_param = N;
  Expression nargs[N];
  Expression handle;
  Expression e[5];  // M, K, cdofs, normals, gaps

  ConstructFromMatrices(const basicAC_F0& args, const Expression (&x)[6]) : handle(x[0]) {
    for (int k = 0; k < 5; ++k) e[k] = x[k + 1];
    args.SetNameParam(N, Derived::name_param, nargs);
  }
};

// NBMModel Mo(M, K, cdofs, normals, gaps, fixed=..., mass=..., ...)
class ModelConstruct : public ConstructFromMatrices<ModelConstruct, kModelParams> {
 public:
  static basicAC_F0::name_and_type name_param[];
  using ConstructFromMatrices::ConstructFromMatrices;

  AnyType operator()(Stack s) const override {
    ModelHandle* h = GetAny<ModelHandle*>((*handle)(s));
    h->set_model(build_model(s, e, nargs, "NBMModel"));
    return h;
  }
  operator aType() const override { return atype<ModelHandle*>(); }
};
basicAC_F0::name_and_type ModelConstruct::name_param[] = {NBM_MODEL_PARAMS};

// NBM S(M, K, cdofs, normals, gaps, dt=..., ...): the shorthand, a model of
// its own and its integrator.
class NbmConstruct
    : public ConstructFromMatrices<NbmConstruct, kSchemeParams + kModelParams> {
 public:
  static basicAC_F0::name_and_type name_param[];
  using ConstructFromMatrices::ConstructFromMatrices;

  AnyType operator()(Stack s) const override {
    NbmHandle* h = GetAny<NbmHandle*>((*handle)(s));
    if (!nargs[0]) fail("NBM: the time step dt=... is required");  // before the model's work
    build_solver(s, h, build_model(s, e, nargs + kSchemeParams, "NBM"), nargs);
    return h;
  }
  operator aType() const override { return atype<NbmHandle*>(); }
};
basicAC_F0::name_and_type NbmConstruct::name_param[] = {NBM_SCHEME_PARAMS, NBM_MODEL_PARAMS};

// NBM S(Mo, dt=..., ...): the time integrator of the model Mo.
class NbmOfModel : public E_F0mps {
 public:
  static const int n_name_param = kSchemeParams;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, model;

  NbmOfModel(const basicAC_F0& args, const Expression (&x)[2]) : handle(x[0]), model(x[1]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    NbmHandle* h = GetAny<NbmHandle*>((*handle)(s));
    ModelHandle* m = GetAny<ModelHandle*>((*model)(s));
    if (!m || !m->model)
      fail("NBM: the model was not constructed (declare it as NBMModel Mo(M, K, cdofs, "
           "normals, gaps, ...))");
    build_solver(s, h, *m->model, nargs);
    return h;
  }
  operator aType() const override { return atype<NbmHandle*>(); }
};
basicAC_F0::name_and_type NbmOfModel::name_param[] = {NBM_SCHEME_PARAMS};

// The operator `<-` of a constructor C whose positional arguments have the
// types Args (after the handle of type Handle*).
template <class C, class Handle, class... Args>
class ConstructOp : public OneOperator {
 public:
  ConstructOp() : OneOperator(atype<Handle*>(), atype<Handle*>(), atype<Args>()...) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[1 + sizeof...(Args)];
    for (int k = 0; k < 1 + static_cast<int>(sizeof...(Args)); ++k) e[k] = t[k]->CastTo(args[k]);
    return new C(args, e);
  }
};
using Matrix = Matrice_Creuse<double>*;
using ModelConstructOp =
    ConstructOp<ModelConstruct, ModelHandle, Matrix, Matrix, KN<long>*, KN<double>*, KN<double>*>;
using NbmConstructOp =
    ConstructOp<NbmConstruct, NbmHandle, Matrix, Matrix, KN<long>*, KN<double>*, KN<double>*>;
using NbmOfModelOp = ConstructOp<NbmOfModel, NbmHandle, ModelHandle*>;

// The state vectors cross the boundary as std::vector copies: O(n) per step,
// negligible next to a sparse solve.
// u and v are written in place: one array passed as both would be silently
// overwritten by the velocity.
void check_distinct(KN<double>* u, KN<double>* v, const char* function) {
  if (u == v)
    fail(std::string(function) + ": u and v are the same array; pass the displacement and the "
         "velocity as two distinct arrays");
}

long nbm_init(NbmHandle* const& h, KN<double>* const& u, KN<double>* const& v,
              KN<double>* const& F) {
  nbm::Solver& S = solver_of(h, "nbmInit");
  check_distinct(u, v, "nbmInit");
  std::vector<double> uu = vector_of<double>(u, "nbmInit", "u");
  std::vector<double> vv = vector_of<double>(v, "nbmInit", "v");
  const std::vector<double> FF = vector_of<double>(F, "nbmInit", "F");
  guarded("nbmInit", [&] { S.initialize(uu, vv, FF); });
  assign(u, uu);
  assign(v, vv);
  return 0;
}

long nbm_step(NbmHandle* const& h, KN<double>* const& u, KN<double>* const& v,
              KN<double>* const& F) {
  nbm::Solver& S = solver_of(h, "nbmStep");
  if (!S.initialized()) fail("nbmStep: no initial state; call nbmInit first");
  check_distinct(u, v, "nbmStep");
  std::vector<double> uu = vector_of<double>(u, "nbmStep", "u");
  std::vector<double> vv = vector_of<double>(v, "nbmStep", "v");
  const std::vector<double> FF = vector_of<double>(F, "nbmStep", "F");
  const nbm::StepInfo info = guarded("nbmStep", [&] { return S.step(uu, vv, FF); });
  assign(u, uu);
  assign(v, vv);
  h->crossings = info.crossings;
  if (info.crossings > 0 && (h->crossings_fatal || !h->crossings_reported)) {
    const std::string what =
        "nbmStep: " + std::to_string(info.crossings) + " node(s) outside the contact set inside "
        "the obstacle at t = " + std::to_string(S.time()) + "; add them to the contact nodes "
        "(a contact description that includes them, nbmReplaceContacts)";
    if (h->crossings_fatal) fail(what + " [crossings = \"error\"]");
    cout << "nbm: " << what << " (reported once; nbmCrossings(S) counts them at every step)" << endl;
    h->crossings_reported = true;
  }
  return info.active_set_iterations;
}

// nbmObstacle(S, g, gdot, gddot): the obstacle (gaps along the contact
// normals and their time derivatives, one per contact node) from the next
// nbmInit, nbmStep or nbmRestart on.
long nbm_obstacle(NbmHandle* const& h, KN<double>* const& g, KN<double>* const& g_rate,
                  KN<double>* const& g_accel) {
  nbm::Solver& S = solver_of(h, "nbmObstacle");
  const std::vector<double> gg = vector_of<double>(g, "nbmObstacle", "g");
  const std::vector<double> gr = vector_of<double>(g_rate, "nbmObstacle", "gdot");
  const std::vector<double> ga = vector_of<double>(g_accel, "nbmObstacle", "gddot");
  guarded("nbmObstacle", [&] { S.set_obstacle(gg, gr, ga); });
  return 0;
}

// nbmReplaceContacts(S, cdofs, cnormals, cgaps, u, v, F): a new contact
// description at the current state (re-linearisation), one setup.
long nbm_replace_contacts(NbmHandle* const& h, KN<long>* const& dofs, KN<double>* const& normals,
                          KN<double>* const& gaps, KN<double>* const& u, KN<double>* const& v,
                          KN<double>* const& F) {
  const char* f = "nbmReplaceContacts";
  nbm::Solver& S = solver_of(h, f);
  if (!S.initialized()) fail("nbmReplaceContacts: no state yet; call nbmInit first");
  check_distinct(u, v, f);
  nbm::ContactDescription contact;
  contact.dofs = vector_of<long>(dofs, f, "contact dofs");
  contact.normals = vector_of<double>(normals, f, "normals");
  contact.gaps = vector_of<double>(gaps, f, "gaps");
  std::vector<double> uu = vector_of<double>(u, f, "u");
  std::vector<double> vv = vector_of<double>(v, f, "v");
  const std::vector<double> FF = vector_of<double>(F, f, "F");
  guarded(f, [&] { S.replace_contacts(contact, uu, vv, FF); });
  h->set_model(S.model());  // the orbits computed on the old contact set go
  assign(u, uu);
  assign(v, vv);
  return S.n_contact();
}

// nbmLoadRates(S, Fdot, Fddot): time derivatives of the load at the time of
// the next call (arrays of size 0: zero).
long nbm_load_rates(NbmHandle* const& h, KN<double>* const& F_rate, KN<double>* const& F_accel) {
  nbm::Solver& S = solver_of(h, "nbmLoadRates");
  const std::vector<double> r = vector_of<double>(F_rate, "nbmLoadRates", "Fdot");
  const std::vector<double> a = vector_of<double>(F_accel, "nbmLoadRates", "Fddot");
  guarded("nbmLoadRates", [&] { S.set_load_rates(r, a); });
  return 0;
}

// nbmRestart(S, u, v, F, t, a, act [, state]): the state saved after nbmInit
// or nbmStep (u, v, nbmTime, nbmAcceleration, nbmActive, nbmSchemeState),
// restored as it is.
long nbm_restart_with_state(NbmHandle* const& h, KN<double>* const& u, KN<double>* const& v,
                            KN<double>* const& F, const double& t, KN<double>* const& a,
                            KN<long>* const& act, KN<double>* const& state) {
  nbm::Solver& S = solver_of(h, "nbmRestart");
  check_distinct(u, v, "nbmRestart");
  std::vector<double> uu = vector_of<double>(u, "nbmRestart", "u");
  std::vector<double> vv = vector_of<double>(v, "nbmRestart", "v");
  const std::vector<double> FF = vector_of<double>(F, "nbmRestart", "F");
  const std::vector<double> aa = vector_of<double>(a, "nbmRestart", "a");
  const std::vector<long> active = vector_of<long>(act, "nbmRestart", "active");
  const std::vector<double> scheme =
      state ? vector_of<double>(state, "nbmRestart", "state") : std::vector<double>();
  guarded("nbmRestart", [&] { S.restart(uu, vv, FF, t, aa, active, scheme); });
  assign(u, uu);
  assign(v, vv);
  return 0;
}
long nbm_restart(NbmHandle* const& h, KN<double>* const& u, KN<double>* const& v,
                 KN<double>* const& F, const double& t, KN<double>* const& a,
                 KN<long>* const& act) {
  return nbm_restart_with_state(h, u, v, F, t, a, act, nullptr);
}

long nbm_reactions(NbmHandle* const& h, KN<double>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmReactions");
  if (!S.initialized()) fail("nbmReactions: call nbmInit first");
  assign(out, S.reactions());
  return out->N();
}
long nbm_gaps(NbmHandle* const& h, KN<double>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmGaps");
  if (!S.initialized()) fail("nbmGaps: call nbmInit first");
  assign(out, S.gaps());
  return out->N();
}
long nbm_active(NbmHandle* const& h, KN<long>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmActive");
  if (!S.initialized()) fail("nbmActive: call nbmInit first");
  assign(out, S.active());
  return out->N();
}
long nbm_energies(NbmHandle* const& h, KN<double>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmEnergies");
  if (!S.initialized()) fail("nbmEnergies: call nbmInit first");
  assign(out, S.energies());
  return out->N();
}
long nbm_acceleration(NbmHandle* const& h, KN<double>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmAcceleration");
  if (!S.initialized()) fail("nbmAcceleration: call nbmInit first");
  assign(out, S.acceleration());
  return out->N();
}
long nbm_scheme_state(NbmHandle* const& h, KN<double>* const& out) {
  nbm::Solver& S = solver_of(h, "nbmSchemeState");
  if (!S.initialized()) fail("nbmSchemeState: call nbmInit first");
  assign(out, S.scheme_state());
  return out->N();
}
// Of the model (an NBM object passes its own).
long nbm_fixed(ModelHandle* const& h, KN<long>* const& out) {
  assign(out, model_of(h, "nbmFixedDofs").fixed_dofs());
  return out->N();
}
long nbm_n_contact(ModelHandle* const& h) { return model_of(h, "nbmContactNodes").n_contact(); }
double nbm_time(NbmHandle* const& h) { return solver_of(h, "nbmTime").time(); }
double nbm_critical_dt(NbmHandle* const& h) { return solver_of(h, "nbmCriticalDt").critical_dt(); }
long nbm_fallbacks(NbmHandle* const& h) { return solver_of(h, "nbmFallbacks").fallbacks(); }
double nbm_reduction_residual(NbmHandle* const& h) {
  nbm::Solver& S = solver_of(h, "nbmReductionResidual");
  return guarded("nbmReductionResidual", [&] { return S.reduction_residual(); });
}
long nbm_crossings(NbmHandle* const& h) {
  solver_of(h, "nbmCrossings");
  return h->crossings;
}

// The MPI rank of this process and the number of ranks (0 and 1 in a plain
// FreeFem++ run, where the script has no mpirank): which rank writes what.
long nbm_mpi_rank() { return nbm::world_rank(); }
long nbm_mpi_size() { return nbm::world_size(); }

void Load_Init() {
  load_obstacle_functions();  // NBMObstacle, which NBM's obstacle= takes
  Dcl_Type<ModelHandle*>(InitP<ModelHandle>, Destroy<ModelHandle>);
  zzzfff->Add("NBMModel", atype<ModelHandle*>());
  TheOperators->Add("<-", new ModelConstructOp);
  Dcl_Type<NbmHandle*>(InitP<NbmHandle>, Destroy<NbmHandle>);
  zzzfff->Add("NBM", atype<NbmHandle*>());
  TheOperators->Add("<-", new NbmOfModelOp);
  TheOperators->Add("<-", new NbmConstructOp);
  // An NBM object is also its model: every call taking an NBMModel (the
  // periodic tools, NBM S(Mo, ...)) takes it.
  map_type[typeid(ModelHandle*).name()]->AddCast(
      new E_F1_funcT<ModelHandle*, NbmHandle*>(Cast<ModelHandle*, NbmHandle*>));

  using H = NbmHandle*;
  using R = KN<double>*;
  Global.Add("nbmInit", "(", new OneOperator4_<long, H, R, R, R>(nbm_init));
  Global.Add("nbmStep", "(", new OneOperator4_<long, H, R, R, R>(nbm_step));
  Global.Add("nbmRestart", "(",
             new OneOperator7_<long, H, R, R, R, double, R, KN<long>*>(nbm_restart));
  Global.Add("nbmRestart", "(",
             new OneOperator8_<long, H, R, R, R, double, R, KN<long>*, R>(nbm_restart_with_state));
  Global.Add("nbmReplaceContacts", "(",
             new OneOperator7_<long, H, KN<long>*, R, R, R, R, R>(nbm_replace_contacts));
  Global.Add("nbmObstacle", "(", new OneOperator4_<long, H, R, R, R>(nbm_obstacle));
  Global.Add("nbmLoadRates", "(", new OneOperator3_<long, H, R, R>(nbm_load_rates));
  Global.Add("nbmSchemeState", "(", new OneOperator2_<long, H, R>(nbm_scheme_state));
  Global.Add("nbmReactions", "(", new OneOperator2_<long, H, R>(nbm_reactions));
  Global.Add("nbmGaps", "(", new OneOperator2_<long, H, R>(nbm_gaps));
  Global.Add("nbmActive", "(", new OneOperator2_<long, H, KN<long>*>(nbm_active));
  Global.Add("nbmEnergies", "(", new OneOperator2_<long, H, R>(nbm_energies));
  Global.Add("nbmAcceleration", "(", new OneOperator2_<long, H, R>(nbm_acceleration));
  Global.Add("nbmFixedDofs", "(", new OneOperator2_<long, ModelHandle*, KN<long>*>(nbm_fixed));
  Global.Add("nbmTime", "(", new OneOperator1_<double, H>(nbm_time));
  Global.Add("nbmMpiRank", "(", new OneOperator0<long>(nbm_mpi_rank));
  Global.Add("nbmMpiSize", "(", new OneOperator0<long>(nbm_mpi_size));
  Global.Add("nbmCriticalDt", "(", new OneOperator1_<double, H>(nbm_critical_dt));
  Global.Add("nbmFallbacks", "(", new OneOperator1_<long, H>(nbm_fallbacks));
  Global.Add("nbmReductionResidual", "(", new OneOperator1_<double, H>(nbm_reduction_residual));
  Global.Add("nbmContactNodes", "(", new OneOperator1_<long, ModelHandle*>(nbm_n_contact));
  Global.Add("nbmCrossings", "(", new OneOperator1_<long, H>(nbm_crossings));
  load_orbit_functions();
  load_backbone_functions();
}

}  // namespace

LOADFUNC(Load_Init)
