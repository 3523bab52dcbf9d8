// FreeFEM binding of the rigid obstacle held exactly (method.md §10):
//
//   real[int] c = [0, 0];
//   NBMObstacle bowl("circle", c, radius = 1.25, side = "inside");
//   NBMObstacle ground("plane", p0, axis = [0, 1]);                // normal out of the obstacle
//   NBMObstacle drum("cylinder", p0, axis = a, radius = 1);         // 3D
//   NBMObstacle casing("circle", c, radius = R, side = "inside",
//                      radiusChange = [-d/2, 0, 0, k*Om, d/2, 0]); // ovalisation law
//   NBM S(M, K, cdofs, cnormals, cgaps, dt = ..., mass = "redistributed",
//         positions = xy, obstacle = bowl);
//
//   NBMObstacle cam("circle", c, radius = R, pivot = p0,
//                   rotation = [0, Om, 0]);                        // turns about p0
//   real[int] o = [0, 0];                                          // the script's phi:
//   NBMObstacle ramp("distance", o, distance = y - 0.2 * x^2);     // fixed
//   real tphi;
//   NBMObstacle wave("distance", o, distance = y - a * sin(x - tphi),
//                    time = tphi);                                  // moving
//
// A motion is a time law [offset, rate, accel, omega1, cos1, sin1, ...]:
// w(t) = offset + rate t + accel t^2/2 + sum (cos_j cos(omega_j t) + sin_j sin(omega_j t)),
// for translation = (along direction = ..., or a plane's normal),
// radiusChange = (round obstacles) and rotation = (the angle, radians, about
// pivot = ... and, in 3D, rotationAxis = ...).
// A "distance" expression is evaluated at the point (x, y, z) FreeFEM's
// x, y, z read, with the script variable given as time = set to the time;
// both are restored after each evaluation.
#include "binding.hpp"

namespace nbm_binding {
namespace {

nbm::TimeLawDescription time_law(KN<double>* law, const char* name) {
  const std::vector<double> c = vector_of<double>(law, "NBMObstacle", name);
  if (c.size() < 3 || (c.size() - 3) % 3 != 0)
    fail(std::string("NBMObstacle: ") + name + ": " + std::to_string(c.size()) +
         " coefficients, expected [offset, rate, accel] followed by triples [omega, cos, sin]");
  nbm::TimeLawDescription d;
  d.offset = c[0], d.rate = c[1], d.accel = c[2];
  d.harmonics.assign(c.begin() + 3, c.end());
  return d;
}

// phi of a "distance" obstacle: the script's expression at x (dim
// coordinates) and time t, evaluated on the stack of the declaration (the
// script's top level, where its variables live).
std::function<double(const double*, double)> script_distance(Expression phi, Stack s, int dim,
                                                              double* time) {
  return [phi, s, dim, time](const double* x, double t) {
    MeshPoint* mp = MeshPointStack(s);
    const MeshPoint saved = *mp;
    const double saved_time = time ? *time : 0;
    if (time) *time = t;
    mp->set(x[0], dim > 1 ? x[1] : 0.0, dim > 2 ? x[2] : 0.0);
    const double value = GetAny<double>((*phi)(s));
    *mp = saved;
    if (time) *time = saved_time;
    return value;
  };
}

class ObstacleConstruct : public E_F0mps {
 public:
  static const int n_name_param = 12;
  static basicAC_F0::name_and_type name_param[];
  Expression nargs[n_name_param];
  Expression handle, kind, point;

  ObstacleConstruct(const basicAC_F0& args, const Expression (&e)[3])
      : handle(e[0]), kind(e[1]), point(e[2]) {
    args.SetNameParam(n_name_param, name_param, nargs);
  }

  AnyType operator()(Stack s) const override {
    ObstacleHandle* h = GetAny<ObstacleHandle*>((*handle)(s));
    auto d = std::make_unique<nbm::ObstacleDescription>();
    d->kind = *GetAny<string*>((*kind)(s));
    d->point = vector_of<double>(GetAny<KN<double>*>((*point)(s)), "NBMObstacle", "point");
    if (nargs[0]) d->radius = GetAny<double>((*nargs[0])(s));
    if (nargs[1]) d->side = *GetAny<string*>((*nargs[1])(s));
    if (nargs[2]) d->axis = vector_of<double>(GetAny<KN<double>*>((*nargs[2])(s)), "NBMObstacle", "axis");
    if (nargs[3])
      d->direction = vector_of<double>(GetAny<KN<double>*>((*nargs[3])(s)), "NBMObstacle", "direction");
    if (nargs[4]) d->translation = time_law(GetAny<KN<double>*>((*nargs[4])(s)), "translation");
    if (nargs[5]) d->radius_change = time_law(GetAny<KN<double>*>((*nargs[5])(s)), "radiusChange");
    if (nargs[6]) d->rotation = time_law(GetAny<KN<double>*>((*nargs[6])(s)), "rotation");
    if (nargs[7]) d->pivot = vector_of<double>(GetAny<KN<double>*>((*nargs[7])(s)), "NBMObstacle", "pivot");
    if (nargs[8])
      d->rotation_axis =
          vector_of<double>(GetAny<KN<double>*>((*nargs[8])(s)), "NBMObstacle", "rotationAxis");
    if (nargs[11]) d->fd_step = GetAny<double>((*nargs[11])(s));
    double* time = nargs[10] ? GetAny<double*>((*nargs[10])(s)) : nullptr;
    if (nargs[9]) {
      d->distance = script_distance(nargs[9], s, static_cast<int>(d->point.size()), time);
      d->moving = time != nullptr;
    } else if (time) {
      fail("NBMObstacle: time: given without distance = (it is the variable a distance "
           "expression reads the time from)");
    } else if (nargs[11]) {
      fail("NBMObstacle: fdStep: given without distance = (the step of the differences of a "
           "distance expression)");
    }
    // Checked now, where the script declares it, not at the NBM call.
    guarded("NBMObstacle", [&] { nbm::check_obstacle(*d); });
    h->destroy();
    h->description = d.release();
    return h;
  }
  operator aType() const override { return atype<ObstacleHandle*>(); }
};

basicAC_F0::name_and_type ObstacleConstruct::name_param[] = {
    {"radius", &typeid(double)},          {"side", &typeid(string*)},
    {"axis", &typeid(KN<double>*)},       {"direction", &typeid(KN<double>*)},
    {"translation", &typeid(KN<double>*)}, {"radiusChange", &typeid(KN<double>*)},
    {"rotation", &typeid(KN<double>*)},   {"pivot", &typeid(KN<double>*)},
    {"rotationAxis", &typeid(KN<double>*)}, {"distance", &typeid(double)},
    {"time", &typeid(double*)},           {"fdStep", &typeid(double)},
};

class ObstacleConstructOp : public OneOperator {
 public:
  ObstacleConstructOp()
      : OneOperator(atype<ObstacleHandle*>(), atype<ObstacleHandle*>(), atype<string*>(),
                    atype<KN<double>*>()) {}
  E_F0* code(const basicAC_F0& args) const override {
    Expression e[3];
    for (int k = 0; k < 3; ++k) e[k] = t[k]->CastTo(args[k]);
    return new ObstacleConstruct(args, e);
  }
};

// nbmObstacleDistance(O, x, t): the signed distance of the point x at time t
// (what every contact node of a run with obstacle = O keeps >= 0).
double nbm_obstacle_distance(ObstacleHandle* const& h, KN<double>* const& x, const double& t) {
  if (!h || !h->description) fail("nbmObstacleDistance: the NBMObstacle was not constructed");
  const std::vector<double> xx = vector_of<double>(x, "nbmObstacleDistance", "x");
  return guarded("nbmObstacleDistance", [&] { return nbm::obstacle_distance(*h->description, xx, t); });
}

}  // namespace

void load_obstacle_functions() {
  Dcl_Type<ObstacleHandle*>(InitP<ObstacleHandle>, Destroy<ObstacleHandle>);
  zzzfff->Add("NBMObstacle", atype<ObstacleHandle*>());
  TheOperators->Add("<-", new ObstacleConstructOp);
  Global.Add("nbmObstacleDistance", "(",
             new OneOperator3_<double, ObstacleHandle*, KN<double>*, double>(nbm_obstacle_distance));
}

}  // namespace nbm_binding
