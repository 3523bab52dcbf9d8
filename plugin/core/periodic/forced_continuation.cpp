#include "periodic/forced_continuation.hpp"

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "base/errors.hpp"
#include "linalg/dense_eigen.hpp"
#include "periodic/arclength_continuation.hpp"
#include "periodic/gauss_newton.hpp"

namespace nbm {
namespace {

constexpr int kSamples = 256;  // samples of a period for min_gap and peak

std::string number(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

const char* parameter_name(ForcedParameter p) {
  return p == ForcedParameter::frequency ? "omega" : "amplitude scale";
}

// The forced response as a curve for the arclength driver, in the scaled
// unknowns y = (u0 / L, v0 / V, p / P) (method.md §9, "Continuation of
// forced orbits"); its weights are ones.
class ScaledProblem : public ArclengthProblem<ForcedPoint> {
 public:
  ScaledProblem(const ReducedField& field, const Damping& damping, const HarmonicLoad& load,
                const ForcedContinuationOptions& o, double L, double V, double P)
      : field_(field), load_(load), base_(field, damping, load), o_(o),
        n_(field.size()), L_(L), V_(V), P_(P) {}

  Index size() const { return 2 * n_ + 1; }
  Index p_index() const { return 2 * n_; }
  Vector scaled(const Vector& u, const Vector& v, double p) const {
    Vector y(size());
    y << u / L_, v / V_, p / P_;
    return y;
  }
  Vector u(const Vector& y) const { return y.head(n_) * L_; }
  Vector v(const Vector& y) const { return y.segment(n_, n_) * V_; }
  double p(const Vector& y) const { return y(p_index()) * P_; }
  double scaled_parameter(double p) const { return p / P_; }
  double parameter_scale() const { return P_; }
  /// A state perturbation dx = (du, dv) in the scaled unknowns.
  Vector scaled_state(const Vector& dx) const {
    Vector y = Vector::Zero(size());
    y << dx.head(n_) / L_, dx.tail(n_) / V_, 0;
    return y;
  }

  /// The flow at parameter p; with_load shares the state-space
  /// decompositions of a damping matrix between the parameters.
  ExactFlow flow(double p) const { return base_.with_load(forced_load(load_, o_.parameter, p)); }
  bool admissible(double p) const {
    return std::isfinite(p) && (o_.parameter != ForcedParameter::frequency || p > 0);
  }

  /// The bordered system at y for the period map of subharmonic m: rows
  /// W (Phi - x) and border . y - target; Jacobian with dPhi/dp by central
  /// differences (step difference_step * P). A failed flow (a parameter out
  /// of range, a resonance, Zeno behaviour) is an infinite merit, which the
  /// Gauss-Newton line search backs away from.
  GaussNewtonEvaluation evaluate(const Vector& y, bool jacobian, const Vector& border,
                                 double target, int m) const {
    GaussNewtonEvaluation e;
    const double p = this->p(y);
    if (!y.allFinite() || !admissible(p)) return e;
    try {
      const Vector u = this->u(y), v = this->v(y);
      const ExactFlow f = flow(p);
      const double T = forced_period(f, m);
      const FlowResult r = f.integrate(u, v, T, jacobian);
      e.R.resize(size());
      e.R << (r.u - u) / L_, (r.v - v) / V_, border.dot(y) - target;
      // Periodicity relative to the orbit's size as in shoot (forced problem), floored
      // at 1e-6 L so that an orbit at rest (zero load) stays measurable.
      const double ls = std::max({u.norm(), r.u.norm(), 1e-6 * L_, periodic_tiny});
      e.merit = std::max(periodicity_residual(u, v, r.u, r.v, T, ls), std::abs(e.R(p_index())));
      e.size = e.R.norm();
      if (!jacobian) return e;
      const Index N = 2 * n_;
      Vector unit(N);  // the scale of each state unknown
      unit << Vector::Constant(n_, L_), Vector::Constant(n_, V_);
      e.J.resize(size(), size());
      e.J.topLeftCorner(N, N) = unit.cwiseInverse().asDiagonal() *
                                (r.monodromy - Matrix::Identity(N, N)) * unit.asDiagonal();
      const double dp = o_.difference_step * P_;
      if (!admissible(p - dp)) return GaussNewtonEvaluation{};
      auto end_state = [&](double q) {
        const ExactFlow fq = flow(q);
        const FlowResult rq = fq.integrate(u, v, forced_period(fq, m), false);
        Vector x(N);
        x << rq.u, rq.v;
        return x;
      };
      e.J.topRightCorner(N, 1) =
          (end_state(p + dp) - end_state(p - dp)).cwiseQuotient(unit) * (P_ / (2 * dp));
      e.J.bottomRows(1) = border.transpose();
    } catch (const NumericalError&) {
      return GaussNewtonEvaluation{};
    }
    return e;
  }

  /// Newton on the bordered system from `guess`. Throws NumericalError.
  GaussNewtonResult newton(const Vector& guess, const Vector& border, double target, int m,
                           int max_iterations) const {
    GaussNewtonOptions gn;
    gn.period_index = -1;
    gn.tolerance = o_.shooting.tolerance;
    gn.max_iterations = max_iterations;
    gn.solver = GaussNewtonOptions::Solver::householder;  // square: LU
    gn.name = "forced continuation";
    gn.context = "near " + std::string(parameter_name(o_.parameter)) + " = " +
                 number(p(guess)) + " ";
    return gauss_newton(
        [&](const Vector& y, bool jac) { return evaluate(y, jac, border, target, m); }, guess,
        gn);
  }

  /// The driver's corrector: Newton for subharmonic m, the tangent oriented
  /// along the secant from `from` (at a corner of a nonsmooth curve the
  /// tangent may turn by more than 90 degrees, and orienting it along
  /// from's would send the curve back), the analysed point.
  ArclengthCorrection<ForcedPoint> correct(const Vector& guess, const Vector& border,
                                           double target,
                                           const ArclengthNode& from) const override {
    const int m = o_.subharmonic;
    const GaussNewtonResult r = newton(guess, border, target, m, o_.corrector_iterations);
    const Vector secant = r.y - from.y;
    ArclengthCorrection<ForcedPoint> c;
    c.y = r.y;
    c.tangent = tangent(r.last.J, secant.norm() > 0 ? secant : from.tangent);
    c.iterations = r.iterations;
    c.point = point(c.y, c.tangent, r.iterations, m);
    return c;
  }
  int event_kinds() const override { return 4; }
  int indicator(int kind, const ForcedPoint& pt) const override;
  bool happened(int kind, const ForcedPoint& a, const ForcedPoint& b) const override;

  /// The unit tangent at a corrected point: J's top rows (the period map)
  /// annihilate it; with J's last row replaced by `orientation`, the
  /// solution of J t = e_last has orientation . t = 1, i.e. t points the
  /// same way. Falls back to the null vector by SVD if that J is singular.
  Vector tangent(Matrix J, const Vector& orientation) const {
    J.bottomRows(1) = orientation.transpose();
    Vector rhs = Vector::Zero(size());
    rhs(p_index()) = 1;
    Vector t = J.partialPivLu().solve(rhs);
    if (!t.allFinite() || !((J * t - rhs).norm() < 1e-6)) {
      Eigen::JacobiSVD<Matrix> svd(J.topRows(2 * n_), Eigen::ComputeFullV);
      t = svd.matrixV().col(size() - 1);
      if (t.dot(orientation) < 0) t = -t;
    }
    return t.normalized();
  }

  /// The analysed point at y (corrected): orbit, samples for min_gap and peak.
  /// Its arclength is the driver's (set when the curve is done).
  ForcedPoint point(const Vector& y, const Vector& tangent, int iterations, int m) const {
    ForcedPoint pt;
    pt.parameter = p(y);
    const ExactFlow f = flow(pt.parameter);
    pt.omega = f.forcing().Omega.front();
    pt.scale = o_.parameter == ForcedParameter::amplitude ? pt.parameter : 1.0;
    pt.tangent_parameter = tangent(p_index());
    pt.corrector_iterations = iterations;
    pt.orbit.u0 = u(y);
    pt.orbit.v0 = v(y);
    pt.orbit.period = forced_period(f, m);
    pt.orbit.iterations = iterations;
    analyse_orbit(f, pt.orbit, false);
    pt.switches = static_cast<int>(pt.orbit.switches.size());
    std::vector<double> times(kSamples);
    for (int k = 0; k < kSamples; ++k) times[k] = pt.orbit.period * k / kSamples;
    const FlowResult r = f.integrate(pt.orbit.u0, pt.orbit.v0, pt.orbit.period, false, times);
    pt.peak = Vector::Zero(n_);
    pt.min_gap = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kSamples; ++k) {
      const Vector uk = r.samples.col(k).head(n_);
      pt.peak = pt.peak.cwiseMax(uk.cwiseAbs());
      const ContactShift shift = f.forcing().shift(times[k]);
      const Vector full = field_.expand(uk, shift);
      for (Index c = 0; c < field_.n_contact(); ++c)
        pt.min_gap = std::min(pt.min_gap, field_.gaps()(c) + (shift.empty() ? 0 : shift.gap(c)) -
                                              full(field_.contact()[c]));
    }
    pt.min_gap = std::max(pt.min_gap, 0.0);  // round-off of a closed contact
    return pt;
  }

 private:
  const ReducedField& field_;
  const HarmonicLoad& load_;
  const ExactFlow base_;  ///< at the starting load
  const ForcedContinuationOptions& o_;
  Index n_;
  double L_, V_, P_;
};

// Discrete indicators of the events (method.md §9): an event lies between
// two points where its indicator differs.
bool is_real(std::complex<double> mu) { return mu.imag() == 0; }
int real_below_minus_one(const PeriodicOrbit& o) {
  return static_cast<int>(std::count_if(o.multipliers.begin(), o.multipliers.end(),
                                        [](auto mu) { return is_real(mu) && mu.real() < -1; }));
}
int outside(const PeriodicOrbit& o, bool complex_only) {
  return static_cast<int>(std::count_if(o.multipliers.begin(), o.multipliers.end(), [&](auto mu) {
    return std::abs(mu) > 1 && (!complex_only || !is_real(mu));
  }));
}
int ScaledProblem::indicator(int kind, const ForcedPoint& pt) const {
  switch (static_cast<ForcedEventKind>(kind)) {
    case ForcedEventKind::fold: return pt.tangent_parameter > 0 ? 1 : -1;
    case ForcedEventKind::period_doubling: return real_below_minus_one(pt.orbit) % 2;
    case ForcedEventKind::neimark_sacker: return outside(pt.orbit, true);
    case ForcedEventKind::grazing: return pt.switches;
  }
  return 0;
}
bool ScaledProblem::happened(int kind, const ForcedPoint& a, const ForcedPoint& b) const {
  if (indicator(kind, a) == indicator(kind, b)) return false;
  // A complex pair through the unit circle changes the number of multipliers
  // outside it; two real ones colliding into a pair outside it does not.
  if (static_cast<ForcedEventKind>(kind) == ForcedEventKind::neimark_sacker)
    return outside(a.orbit, false) != outside(b.orbit, false);
  return true;
}

std::complex<double> critical_multiplier(ForcedEventKind kind, const PeriodicOrbit& o) {
  std::complex<double> best = 0;
  double distance = std::numeric_limits<double>::infinity();
  for (const auto mu : o.multipliers) {
    double d = distance;
    if (kind == ForcedEventKind::fold) d = std::abs(mu - 1.0);
    if (kind == ForcedEventKind::period_doubling && is_real(mu)) d = std::abs(mu + 1.0);
    if (kind == ForcedEventKind::neimark_sacker && !is_real(mu)) d = std::abs(std::abs(mu) - 1);
    if (d < distance) distance = d, best = mu;
  }
  return best;
}

}  // namespace

HarmonicLoad forced_load(const HarmonicLoad& load, ForcedParameter parameter, double p) {
  HarmonicLoad out = load;
  if (parameter == ForcedParameter::frequency) {
    out.omega = p;
  } else {
    for (auto* list : {&out.cos, &out.sin, &out.gap_cos, &out.gap_sin})
      for (auto& x : *list) x *= p;
  }
  return out;
}

std::string to_string(ForcedEventKind kind) {
  switch (kind) {
    case ForcedEventKind::fold: return "fold";
    case ForcedEventKind::period_doubling: return "period doubling";
    case ForcedEventKind::neimark_sacker: return "Neimark-Sacker";
    case ForcedEventKind::grazing: return "grazing";
  }
  return "?";
}

namespace {

void check_options(const ReducedField& field, const HarmonicLoad& load, const Vector& u0,
                   const Vector& v0, const ForcedContinuationOptions& o) {
  const std::string c = "forced continuation: ";
  if (load.harmonics() == 0)
    throw InputError(c + "the load has no harmonics (nothing forces the orbit)");
  if (!(load.omega > 0) || !std::isfinite(load.omega))
    throw InputError(c + "the load's omega must be finite and > 0");
  if (u0.size() != field.size() || v0.size() != field.size())
    throw InputError(c + "initial guess of size " + std::to_string(u0.size()) + " and " +
                     std::to_string(v0.size()) + ", expected " + std::to_string(field.size()) +
                     " interior dofs");
  if (!(std::isfinite(o.parameter_min) && std::isfinite(o.parameter_max)))
    throw InputError(c + "parameter_min and parameter_max must be given (finite)");
  if (!(o.parameter_min < o.parameter_max))
    throw InputError(c + "parameter_min must be < parameter_max, got " +
                     number(o.parameter_min) + " and " + number(o.parameter_max));
  if (o.parameter == ForcedParameter::frequency && !(o.parameter_min > 0))
    throw InputError(c + "parameter_min must be > 0 for the frequency, got " +
                     number(o.parameter_min));
  const double p0 = o.parameter == ForcedParameter::frequency ? load.omega : 1.0;
  if (p0 < o.parameter_min || p0 > o.parameter_max)
    throw InputError(c + "the start " + parameter_name(o.parameter) + " = " + number(p0) +
                     " is outside [parameter_min, parameter_max] = [" + number(o.parameter_min) +
                     ", " + number(o.parameter_max) + "]");
  if (o.direction != 1 && o.direction != -1)
    throw InputError(c + "direction must be +1 or -1, got " + std::to_string(o.direction));
  if (p0 == (o.direction > 0 ? o.parameter_max : o.parameter_min))
    throw InputError(c + "the start " + parameter_name(o.parameter) + " = " + number(p0) +
                     " is on the bound the direction " + std::to_string(o.direction) +
                     " leaves through");
  if (!(o.min_step > 0) || !(o.step >= o.min_step) || !(o.max_step >= o.step) ||
      !std::isfinite(o.max_step))
    throw InputError(c + "steps must satisfy 0 < min_step <= step <= max_step < inf, got " +
                     number(o.min_step) + ", " + number(o.step) + ", " + number(o.max_step));
  if (!(o.growth >= 1) || !std::isfinite(o.growth))
    throw InputError(c + "growth must be finite and >= 1, got " + number(o.growth));
  if (o.easy_iterations < 0)
    throw InputError(c + "easy_iterations must be >= 0, got " + std::to_string(o.easy_iterations));
  if (!(o.max_jump >= 1) || !std::isfinite(o.max_jump))
    throw InputError(c + "max_jump must be finite and >= 1, got " + number(o.max_jump));
  if (!(o.max_turn > 0) || !(o.max_turn <= M_PI))
    throw InputError(c + "max_turn must be in (0, pi], got " + number(o.max_turn));
  if (o.max_points < 1)
    throw InputError(c + "max_points must be >= 1, got " + std::to_string(o.max_points));
  if (!(o.length >= 0) || !std::isfinite(o.length))
    throw InputError(c + "length must be finite and >= 0 (0: automatic), got " + number(o.length));
  if (!(o.parameter_scale >= 0) || !std::isfinite(o.parameter_scale))
    throw InputError(c + "parameter_scale must be finite and >= 0 (0: automatic), got " +
                     number(o.parameter_scale));
  if (!(o.difference_step > 0) || !(o.difference_step < 0.1))
    throw InputError(c + "difference_step must be in (0, 0.1), got " + number(o.difference_step));
  if (o.corrector_iterations < 1)
    throw InputError(c + "corrector_iterations must be >= 1, got " +
                     std::to_string(o.corrector_iterations));
  if (!(o.shooting.tolerance > 0))
    throw InputError(c + "shooting.tolerance must be > 0");
  if (o.subharmonic < 1)
    throw InputError(c + "subharmonic must be >= 1, got " +
                     std::to_string(o.subharmonic));
  if (!(o.event_tolerance > 0))
    throw InputError(c + "event_tolerance must be > 0, got " + number(o.event_tolerance));
  if (o.max_bisections < 0)
    throw InputError(c + "max_bisections must be >= 0, got " + std::to_string(o.max_bisections));
}

// The driver's event as the curve reports it: where (the bisected bracket's
// end, or interpolated), the critical multiplier, a description.
ForcedEvent forced_event(const ScaledProblem& problem, const ForcedContinuationOptions& o,
                         const ArclengthCurve<ForcedPoint>& curve,
                         const ArclengthEvent<ForcedPoint>& bracket) {
  const auto kind = static_cast<ForcedEventKind>(bracket.kind);
  const Index k = bracket.point;
  const ForcedPoint &pa = curve.points[k], &pb = curve.points[k + 1];
  const ArclengthNode &a = curve.nodes[k], &b = curve.nodes[k + 1];
  ForcedEvent e;
  e.kind = kind;
  e.point = k;
  e.bisected = bracket.bisected;
  if (bracket.bisected) {
    e.parameter = bracket.past.parameter;
    e.arclength = pa.arclength + bracket.hi;
  } else if (kind == ForcedEventKind::fold && bracket.lo == 0 && bracket.hi == bracket.span) {
    // The vertex of the parabola p(sigma) whose slope is linear between the
    // two points' dp/dsigma (scaled): the chord would cut the turning
    // parameter short.
    const double slope_a = a.tangent(problem.p_index()),
                 slope_b = b.tangent(problem.p_index()) / b.tangent.dot(a.tangent);
    const double s = bracket.span * slope_a / (slope_a - slope_b);
    e.parameter = pa.parameter + problem.parameter_scale() * slope_a * s / 2;
    e.arclength = pa.arclength + s;
  } else {
    // The middle of the bracket, on the chord between the two points.
    const double s = 0.5 * (bracket.lo + bracket.hi);
    e.parameter = pa.parameter + (s / bracket.span) * (pb.parameter - pa.parameter);
    e.arclength = pa.arclength + s;
  }
  e.orbit = bracket.past.orbit;
  if (kind != ForcedEventKind::grazing) e.multiplier = critical_multiplier(kind, e.orbit);
  std::ostringstream d;
  d << to_string(kind) << " at " << parameter_name(o.parameter) << " = " << number(e.parameter)
    << " between points " << k << " and " << k + 1 << " ("
    << (e.bisected ? "bisection" : "interpolation") << ")";
  if (kind != ForcedEventKind::grazing) d << ", multiplier " << e.multiplier;
  if (kind == ForcedEventKind::grazing)
    d << ", switches per period " << pa.switches << " -> " << pb.switches;
  e.description = d.str();
  return e;
}

// The driver's options for the forced curve: step control as given, the
// parameter bounded (in the scaled unknowns).
ArclengthOptions driver_options(const ScaledProblem& problem, const ForcedContinuationOptions& o) {
  ArclengthOptions a;
  a.step = o.step, a.min_step = o.min_step, a.max_step = o.max_step;
  a.shrink = 2;
  a.growth = o.growth, a.easy_iterations = o.easy_iterations;
  a.max_jump = o.max_jump, a.max_turn = o.max_turn;
  a.max_points = o.max_points;
  a.bounded = problem.p_index();
  a.lower = problem.scaled_parameter(o.parameter_min);
  a.upper = problem.scaled_parameter(o.parameter_max);
  a.locate_events = o.locate_events;
  a.event_tolerance = o.event_tolerance;
  a.max_bisections = o.max_bisections;
  return a;
}

}  // namespace

ForcedCurve continue_forced(const ReducedField& field, const Damping& damping,
                            const HarmonicLoad& load, const Vector& u0, const Vector& v0,
                            const ForcedContinuationOptions& o) {
  check_options(field, load, u0, v0, o);
  const double p0 = o.parameter == ForcedParameter::frequency ? load.omega : 1.0;
  const ExactFlow flow0(field, damping, load);
  const PeriodicProblem start(flow0, o.subharmonic);
  const PeriodicOrbit first = shoot(start, u0, v0, start.period(), o.shooting);

  ForcedCurve curve;
  const double omega0 = load.omega;
  curve.length = o.length > 0
                     ? o.length
                     : std::max({first.u0.norm(), first.v0.norm() / omega0, periodic_tiny});
  curve.parameter_scale = o.parameter_scale > 0 ? o.parameter_scale : std::abs(p0);
  const ScaledProblem problem(field, damping, load, o, curve.length, curve.length * omega0,
                              curve.parameter_scale);

  // The first tangent: the null vector of the period map's rows, pointing
  // towards the parameter's `direction`.
  ArclengthCurve<ForcedPoint> arc;
  ArclengthNode node;
  node.y = problem.scaled(first.u0, first.v0, p0);
  node.iterations = first.iterations;
  Vector row = Vector::Zero(problem.size());
  row(problem.p_index()) = o.direction;
  const GaussNewtonEvaluation e =
      problem.evaluate(node.y, true, row, row.dot(node.y), o.subharmonic);
  if (!std::isfinite(e.merit))
    throw NumericalError("forced continuation: the period map failed at the first orbit");
  node.tangent = problem.tangent(e.J, row);
  arc.points.push_back(problem.point(node.y, node.tangent, first.iterations,
                                     o.subharmonic));
  arc.nodes.push_back(std::move(node));
  continue_curve(problem, driver_options(problem, o), arc);

  for (std::size_t k = 0; k < arc.points.size(); ++k)
    arc.points[k].arclength = arc.nodes[k].arclength;
  for (const auto& bracket : arc.events)
    curve.events.push_back(forced_event(problem, o, arc, bracket));
  // Events in the order met along the curve (several between two points
  // are ordered by their arclength).
  std::stable_sort(curve.events.begin(), curve.events.end(),
                   [](const ForcedEvent& x, const ForcedEvent& y) {
                     return x.point != y.point ? x.point < y.point : x.arclength < y.arclength;
                   });
  curve.points = std::move(arc.points);
  const std::string name = parameter_name(o.parameter);
  const double last = curve.points.back().parameter;
  switch (arc.stop) {
    case ArclengthStop::bound:
      curve.stop = ForcedStop::parameter_bound;
      curve.stop_reason = "reached the bound " + name + " = " + number(last);
      break;
    case ArclengthStop::step_too_small:
      curve.stop = ForcedStop::step_too_small;
      curve.stop_reason = "stopped at " + name + " = " + number(last) + " (point " +
                          std::to_string(curve.points.size() - 1) +
                          "): the corrector failed with the step halved below min_step = " +
                          number(o.min_step) + "; last failure: " + arc.reason;
      break;
    case ArclengthStop::max_points:
    case ArclengthStop::ended:  // the forced curve has no end of its own
      curve.stop = ForcedStop::max_points;
      curve.stop_reason = "reached max_points = " + std::to_string(o.max_points) + " at " + name +
                          " = " + number(last);
      break;
  }
  return curve;
}

PeriodDoubledOrbit switch_at_period_doubling(const ReducedField& field, const Damping& damping,
                                             const HarmonicLoad& load,
                                             const ForcedContinuationOptions& o,
                                             const ForcedCurve& curve, const ForcedEvent& event,
                                             double amplitude) {
  const std::string c = "period-doubling branch switching: ";
  if (event.kind != ForcedEventKind::period_doubling)
    throw InputError(c + "the event is a " + to_string(event.kind) + ", not a period doubling");
  if (!(amplitude > 0) || !std::isfinite(amplitude))
    throw InputError(c + "amplitude must be finite and > 0, got " + number(amplitude));
  if (curve.points.empty() || !(curve.length > 0) || !(curve.parameter_scale > 0))
    throw InputError(c + "the curve has no points (not made by continue_forced)");
  const Index n = field.size();
  if (event.orbit.u0.size() != n || event.orbit.monodromy.rows() != 2 * n)
    throw InputError(c + "the event's orbit does not belong to this field");
  const double L = curve.length;
  const ScaledProblem problem(field, damping, load, o, L, L * curve.points.front().omega,
                              curve.parameter_scale);

  // The eigenvector of the real multiplier nearest -1, at t = 0 where the
  // event's orbit starts: the period-2 orbit leaves x* along it.
  const GeneralEigen eig = general_eigen(event.orbit.monodromy, true);
  if (!eig.ok) throw NumericalError(c + "the eigenvalue solver of the event's monodromy failed");
  Index j = -1;
  double best = std::numeric_limits<double>::infinity();
  for (Index i = 0; i < eig.values.size(); ++i) {
    const auto mu = eig.values(i);
    if (is_real(mu) && std::abs(mu + 1.0) < best) best = std::abs(mu + 1.0), j = i;
  }
  if (j < 0) throw NumericalError(c + "the event's orbit has no real multiplier");
  Vector row = problem.scaled_state(eig.vectors.col(j).real());
  row.normalize();

  // Bordered corrector on the period-2m map with the condition
  // e . (y - y*) = amplitude: the period-1 orbit (e . (y - y*) = O(amplitude^2)
  // near the event) is excluded by construction.
  const int m = o.subharmonic;
  const Vector star = problem.scaled(event.orbit.u0, event.orbit.v0, event.parameter);
  const GaussNewtonResult r =
      problem.newton(star + amplitude * row, row, row.dot(star) + amplitude, 2 * m,
                      std::max(o.corrector_iterations, o.shooting.max_iterations));

  PeriodDoubledOrbit out;
  out.parameter = problem.p(r.y);
  const ExactFlow flow = problem.flow(out.parameter);
  ShootingOptions shooting = o.shooting;
  shooting.transient_periods = 0;
  const PeriodicProblem doubled(flow, 2 * m);
  out.orbit = shoot(doubled, problem.u(r.y), problem.v(r.y), doubled.period(), shooting);
  const FlowResult once =
      flow.integrate(out.orbit.u0, out.orbit.v0, forced_period(flow, m), false);
  Vector x0(2 * n), x1(2 * n);
  x0 << out.orbit.u0, out.orbit.v0;
  x1 << once.u, once.v;
  out.separation = problem.scaled_state(x1 - x0).norm();
  if (!(out.separation > 0.01 * amplitude))
    throw NumericalError(c + "the orbit found at " + parameter_name(o.parameter) + " = " +
                         number(out.parameter) + " is the period-1 orbit (separation " +
                         number(out.separation) + ")");
  return out;
}

}  // namespace nbm
