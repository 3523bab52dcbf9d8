// The continuation driver (arclength_continuation.hpp) on the unit circle
// |y|^2 = 1, where every step is known in closed form: from the point at
// angle a with its tangent, the hyperplane at weighted distance h along the
// tangent meets the circle at angle a + asin(h) (weights ones), so the
// steps, the bound, the events and the failures the driver reports can be
// checked against exact values. The circle turns through both folds of
// each coordinate, which a natural parameter could not follow.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "base/errors.hpp"
#include "periodic/arclength_continuation.hpp"

namespace {

using nbm::ArclengthCorrection;
using nbm::ArclengthCurve;
using nbm::ArclengthNode;
using nbm::ArclengthOptions;
using nbm::ArclengthStop;
using nbm::Vector;

// A point of the curve: its unknowns (the driver's Point type).
struct CirclePoint {
  Vector y;
};

double angle(const Vector& y) { return std::atan2(y(1), y(0)); }

Vector on_circle(double a) { return Vector{{std::cos(a), std::sin(a)}}; }

// Newton on [|y|^2 - 1; border . y - target]; the tangent (-y1, y0) oriented
// along the secant from the node the step started from. `fault` may replace
// the corrected point (a failure or a jump to another branch).
class Circle : public nbm::ArclengthProblem<CirclePoint> {
 public:
  Vector w = Vector::Ones(2);
  std::function<void(Vector& y, const ArclengthNode& from)> fault;
  int corrections = 0;

  Vector weights(const Vector&) const override { return w; }
  ArclengthCorrection<CirclePoint> correct(const Vector& guess, const Vector& border,
                                           double target,
                                           const ArclengthNode& from) const override {
    ++const_cast<Circle*>(this)->corrections;
    Vector y = guess;
    int it = 0;
    for (; it < 20; ++it) {
      const Eigen::Vector2d R(y.squaredNorm() - 1, border.dot(y) - target);
      if (R.norm() < 1e-15) break;
      Eigen::Matrix2d J;
      J << 2 * y(0), 2 * y(1), border(0), border(1);
      y -= J.partialPivLu().solve(R);
    }
    if (fault) fault(y, from);
    ArclengthCorrection<CirclePoint> c;
    c.y = y;
    c.tangent = Vector{{-y(1), y(0)}};
    const Vector secant = y - from.y;
    if (c.tangent.dot(secant.norm() > 0 ? secant : from.tangent) < 0) c.tangent = -c.tangent;
    c.iterations = it;
    c.point = CirclePoint{y};
    return c;
  }
  // Event 0: the sign of y(1) (the circle crosses the x axis at (-1, 0)).
  int event_kinds() const override { return 1; }
  int indicator(int, const CirclePoint& p) const override { return p.y(1) > 0 ? 1 : -1; }
};

ArclengthCurve<CirclePoint> start_at(double a) {
  ArclengthCurve<CirclePoint> curve;
  ArclengthNode first;
  first.y = on_circle(a);
  first.tangent = Vector{{-std::sin(a), std::cos(a)}};  // counterclockwise
  curve.nodes.push_back(first);
  curve.points.push_back(CirclePoint{first.y});
  return curve;
}

TEST(ArclengthContinuation, StepsToTheHyperplaneAcrossTheTangentAndGrows) {
  Circle circle;
  ArclengthOptions o;
  o.step = 0.01, o.min_step = 1e-4, o.max_step = 0.08, o.growth = 2;
  o.max_points = 90;
  o.locate_events = false;
  auto curve = start_at(0.3);
  nbm::continue_curve(circle, o, curve);
  EXPECT_EQ(curve.stop, ArclengthStop::max_points);
  ASSERT_EQ(curve.points.size(), 90u);
  double expected_step = o.step, total = 0;
  for (std::size_t k = 1; k < curve.nodes.size(); ++k) {
    const ArclengthNode &a = curve.nodes[k - 1], &b = curve.nodes[k];
    EXPECT_NEAR(b.y.norm(), 1, 1e-14) << k;
    // Newton converges in <= 3 iterations here: every step grows by 2 up to max_step.
    EXPECT_DOUBLE_EQ(b.step, expected_step) << k;
    expected_step = std::min(2 * expected_step, o.max_step);
    // The corrected point is at angle asin(h) further on: exactly on the
    // hyperplane at distance h along the unit tangent.
    double turn = angle(b.y) - angle(a.y);
    if (turn < 0) turn += 2 * M_PI;
    EXPECT_NEAR(turn, std::asin(b.step), 1e-13) << k;
    // The arclength adds the chords.
    EXPECT_NEAR(b.arclength - a.arclength, 2 * std::sin(turn / 2), 1e-13) << k;
    EXPECT_GT(b.tangent.dot(a.tangent), 0) << k;  // oriented along the curve
    total += turn;
  }
  EXPECT_GT(total, 2 * M_PI);  // around both folds of each coordinate
}

TEST(ArclengthContinuation, MeasuresStepsInTheWeightedUnknowns) {
  Circle circle;
  circle.w = Vector{{1, 3}};
  ArclengthOptions o;
  o.step = o.max_step = 0.05, o.min_step = 0.05;
  o.max_points = 30;
  auto curve = start_at(-1.0);
  nbm::continue_curve(circle, o, curve);
  ASSERT_EQ(curve.points.size(), 30u);
  for (std::size_t k = 1; k < curve.nodes.size(); ++k) {
    const ArclengthNode &a = curve.nodes[k - 1], &b = curve.nodes[k];
    const Vector t = a.tangent / circle.w.cwiseProduct(a.tangent).norm();
    EXPECT_NEAR(circle.w.cwiseAbs2().cwiseProduct(t).dot(b.y - a.y), 0.05, 1e-14) << k;
    EXPECT_NEAR(b.arclength - a.arclength, circle.w.cwiseProduct(b.y - a.y).norm(), 1e-15) << k;
  }
}

TEST(ArclengthContinuation, LandsOnTheBoundAndEnds) {
  for (const double lower : {-0.5, 0.1, -0.97}) {
    Circle circle;
    ArclengthOptions o;
    o.step = 0.1, o.max_step = 0.3;
    o.bounded = 0, o.lower = lower;
    auto curve = start_at(0.3);
    nbm::continue_curve(circle, o, curve);
    EXPECT_EQ(curve.stop, ArclengthStop::bound) << lower;
    const Vector& y = curve.nodes.back().y;
    EXPECT_NEAR(y(0), lower, 1e-15) << lower;
    EXPECT_NEAR(y(1), std::sqrt(1 - lower * lower), 1e-14) << lower;
    for (std::size_t k = 0; k + 1 < curve.nodes.size(); ++k) EXPECT_GT(curve.nodes[k].y(0), lower);
  }
}

TEST(ArclengthContinuation, BisectsEventsToTheirTolerance) {
  for (const double tolerance : {1e-4, 1e-8, 1e-12}) {
    Circle circle;
    ArclengthOptions o;
    o.step = o.max_step = 0.25;
    o.max_points = 30;
    o.event_tolerance = tolerance;
    auto curve = start_at(0.3);
    nbm::continue_curve(circle, o, curve);
    // Crossings of the x axis at angles pi and 2 pi: the first two events.
    ASSERT_GE(curve.events.size(), 2u);
    for (int e = 0; e < 2; ++e) {
      const auto& event = curve.events[e];
      EXPECT_TRUE(event.bisected);
      EXPECT_LE(event.hi - event.lo, tolerance);
      const Vector& a = curve.nodes[event.point].y;
      const Vector& b = curve.nodes[event.point + 1].y;
      EXPECT_LT(a(1) * b(1), 0);  // the bracket's points are on both sides
      // The point past the event is within the tolerance of the axis (the
      // hyperplane distance along a tangent at angle < 0.25 rad of it).
      EXPECT_LE(std::abs(event.past.y(1)), 1.1 * tolerance) << tolerance;
      EXPECT_EQ(circle.indicator(0, event.past), circle.indicator(0, curve.points[event.point + 1]));
    }
    // Without location the bracket is the whole step and the past point the next one.
    o.locate_events = false;
    auto plain = start_at(0.3);
    nbm::continue_curve(circle, o, plain);
    ASSERT_GE(plain.events.size(), 2u);
    EXPECT_FALSE(plain.events[0].bisected);
    EXPECT_EQ(plain.events[0].hi, plain.events[0].span);
    EXPECT_EQ(plain.events[0].past.y, plain.points[plain.events[0].point + 1].y);
  }
}

TEST(ArclengthContinuation, ShrinksFailedStepsAndStopsBelowMinStep) {
  // A corrector that fails beyond a chord of 0.07: every accepted step is
  // shorter, reached by shrinking 0.2 by 3 (0.0667), then grown back.
  Circle circle;
  circle.fault = [](Vector& y, const ArclengthNode& from) {
    if ((y - from.y).norm() > 0.07) throw nbm::NumericalError("no convergence (test)");
  };
  ArclengthOptions o;
  o.step = o.max_step = 0.2, o.min_step = 0.01, o.shrink = 3, o.growth = 3;
  o.max_points = 10;
  auto curve = start_at(0.0);
  nbm::continue_curve(circle, o, curve);
  ASSERT_EQ(curve.points.size(), 10u);
  for (std::size_t k = 1; k < curve.nodes.size(); ++k)
    EXPECT_NEAR(curve.nodes[k].step, 0.2 / 3, 1e-15) << k;
  // A corrector that always fails: 0.2, 0.0667, 0.0222 tried, then the curve ends.
  circle.fault = [](Vector&, const ArclengthNode&) {
    throw nbm::NumericalError("no convergence (test)");
  };
  circle.corrections = 0;
  auto stuck = start_at(0.0);
  nbm::continue_curve(circle, o, stuck);
  EXPECT_EQ(stuck.stop, ArclengthStop::step_too_small);
  EXPECT_EQ(stuck.reason, "no convergence (test)");
  EXPECT_EQ(stuck.points.size(), 1u);
  EXPECT_EQ(circle.corrections, 3);
}

TEST(ArclengthContinuation, RejectsJumpsToAnotherBranchAndSharpTurns) {
  // Beyond a chord of 0.1 the corrector lands a quarter turn further on (as
  // on another branch): rejected with max_jump 2 (the step halves to 0.08,
  // and stays there with growth 1), followed without it.
  auto jumping = [](Vector& y, const ArclengthNode& from) {
    if ((y - from.y).norm() > 0.1) y = Vector{{-y(1), y(0)}};
  };
  Circle circle;
  circle.fault = jumping;
  ArclengthOptions o;
  o.step = o.max_step = 0.16, o.min_step = 0.01, o.growth = 1;
  o.max_points = 8;
  o.locate_events = false;
  o.max_jump = 2;
  auto guarded = start_at(0.0);
  nbm::continue_curve(circle, o, guarded);
  ASSERT_EQ(guarded.points.size(), 8u);
  for (std::size_t k = 1; k < guarded.nodes.size(); ++k)
    EXPECT_NEAR(angle(guarded.nodes[k].y) - angle(guarded.nodes[k - 1].y), std::asin(0.08), 1e-13);
  o.max_jump = std::numeric_limits<double>::infinity();
  auto unguarded = start_at(0.0);
  nbm::continue_curve(circle, o, unguarded);
  EXPECT_GT(angle(unguarded.nodes[1].y), 1.5);  // took the jump
  // A corrector that goes back along the curve turns the tangent by pi.
  circle.fault = [](Vector& y, const ArclengthNode& from) { y = on_circle(angle(from.y) - 0.1); };
  o.max_turn = 0.5;
  auto back = start_at(0.0);
  nbm::continue_curve(circle, o, back);
  EXPECT_EQ(back.stop, ArclengthStop::step_too_small);
  EXPECT_NE(back.reason.find("the tangent turned by"), std::string::npos) << back.reason;
}

TEST(ArclengthContinuation, EndsWhereTheProblemSays) {
  struct HalfCircle : Circle {
    std::string end(const std::vector<CirclePoint>& points) const override {
      return points.back().y(0) < 0 ? "crossed the y axis" : "";
    }
  } half;
  ArclengthOptions o;
  o.step = o.max_step = 0.1;
  auto curve = start_at(0.0);
  nbm::continue_curve(half, o, curve);
  EXPECT_EQ(curve.stop, ArclengthStop::ended);
  EXPECT_EQ(curve.reason, "crossed the y axis");
  EXPECT_LT(curve.points.back().y(0), 0);
  EXPECT_GT(curve.points[curve.points.size() - 2].y(0), 0);
}

TEST(ArclengthContinuation, RejectsBadOptionsAndAnEmptyCurve) {
  Circle circle;
  ArclengthCurve<CirclePoint> empty;
  EXPECT_THROW(nbm::continue_curve(circle, ArclengthOptions{}, empty), nbm::InputError);
  auto with = [&](auto change) {
    ArclengthOptions o;
    change(o);
    auto curve = start_at(0.0);
    EXPECT_THROW(nbm::continue_curve(circle, o, curve), nbm::InputError);
  };
  with([](ArclengthOptions& o) { o.min_step = 0; });
  with([](ArclengthOptions& o) { o.step = 0.5; });      // above max_step
  with([](ArclengthOptions& o) { o.min_step = 0.1; });  // above step
  with([](ArclengthOptions& o) { o.shrink = 1; });
  with([](ArclengthOptions& o) { o.growth = 0.5; });
  with([](ArclengthOptions& o) { o.max_step = INFINITY; });
  with([](ArclengthOptions& o) { o.max_jump = 0.5; });
  with([](ArclengthOptions& o) { o.max_turn = 0; });
  with([](ArclengthOptions& o) { o.max_turn = 4; });
  with([](ArclengthOptions& o) { o.max_points = 0; });
  with([](ArclengthOptions& o) { o.event_tolerance = 0; });
  with([](ArclengthOptions& o) { o.max_bisections = -1; });
  with([](ArclengthOptions& o) { o.bounded = 2; });  // the circle has 2 unknowns
  with([](ArclengthOptions& o) { o.bounded = 0, o.lower = 1, o.upper = 0; });
}

}  // namespace
