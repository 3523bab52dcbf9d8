#include "obstacle/rigid_obstacle.hpp"

#include <cmath>
#include <sstream>

#include "base/errors.hpp"

namespace nbm {
namespace {

void check_finite(const Vector& v, const std::string& who) {
  if (!v.allFinite()) throw InputError(who + ": non-finite coordinates");
}

// v / |v|; throws naming `who` if v is zero or not finite.
Vector unit(const Vector& v, const std::string& who) {
  check_finite(v, who);
  const double norm = v.norm();
  if (!(norm > 0)) throw InputError(who + ": zero vector, expected a direction");
  return v / norm;
}

std::string text(const Vector& v) {
  std::ostringstream s;
  s << "(";
  for (Index i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v(i);
  s << ")";
  return s.str();
}

// The translation of a moving obstacle: w(t) along a unit direction (none if
// w never changes).
struct Translation {
  Vector direction;
  TimeLaw law;

  Translation(int dim, const Vector& dir, const TimeLaw& w, const std::string& who) : law(w) {
    law.check(who + " translation");
    if (law.constant() && law.offset == 0) return;
    if (dir.size() != dim)
      throw InputError(who + " direction: " + std::to_string(dir.size()) +
                       " coordinates, expected " + std::to_string(dim) +
                       " (a moving obstacle needs the direction of its translation)");
    direction = unit(dir, who + " direction");
  }
  bool moves() const { return direction.size() != 0 && !law.constant(); }
  // Where `origin` is at time t, and its velocity.
  Vector at(const Vector& origin, double t) const {
    return direction.size() ? Vector(origin + law.value(t) * direction) : origin;
  }
  Vector velocity(double t) const {
    return direction.size() ? Vector(law.first(t) * direction) : Vector::Zero(0);
  }
};

class Plane final : public RigidObstacle {
 public:
  Plane(const Vector& point, const Vector& normal, const TimeLaw& shift)
      : RigidObstacle(static_cast<int>(point.size())),
        point_(point),
        normal_(unit(normal, "plane normal")),
        shift_(shift) {
    if (point.size() < 1 || point.size() > 3)
      throw InputError("plane point: " + std::to_string(point.size()) +
                       " coordinates, expected 1, 2 or 3");
    if (normal.size() != point.size())
      throw InputError("plane normal: " + std::to_string(normal.size()) +
                       " coordinates, expected " + std::to_string(point.size()) +
                       " (those of the point)");
    check_finite(point, "plane point");
    shift_.check("plane shift");
  }
  ObstaclePoint at(const double* x, double t) const override {
    ObstaclePoint p;
    p.phi = -shift_.value(t);
    for (int i = 0; i < dim(); ++i) {
      p.phi += normal_(i) * (x[i] - point_(i));
      p.grad(i) = normal_(i);
    }
    p.phi_t = -shift_.first(t);
    return p;
  }
  bool flat() const override { return true; }
  bool fixed() const override { return shift_.constant(); }
  bool is_distance() const override { return true; }
  std::string describe() const override {
    return "plane through " + text(point_) + " with normal " + text(normal_);
  }

 private:
  Vector point_, normal_;
  TimeLaw shift_;
};

// A ball (disc) or a cylinder: the distance to a centre point, or to an axis,
// compared with a radius that may change in time.
class RoundObstacle final : public RigidObstacle {
 public:
  RoundObstacle(const std::string& kind, const Vector& center, const Vector& axis, double R,
                Side side, const Vector& direction, const TimeLaw& translation,
                const TimeLaw& radius_change)
      : RigidObstacle(static_cast<int>(center.size())),
        kind_(kind),
        center_(center),
        R_(R),
        side_(side),
        translation_(static_cast<int>(center.size()), direction, translation, kind),
        radius_change_(radius_change) {
    check_finite(center, kind + " centre");
    if (!(std::isfinite(R) && R > 0))
      throw InputError(kind + " radius: " + std::to_string(R) + ", expected a finite R > 0");
    radius_change_.check(kind + " radius change");
    if (axis.size()) axis_ = unit(axis, kind + " axis");
  }
  ObstaclePoint at(const double* x, double t) const override {
    // Fixed-size arithmetic (no heap): called per node and frame iteration.
    const int d = dim();
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), r = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
    const bool moves = translation_.direction.size() != 0;
    const double w = moves ? translation_.law.value(t) : 0, w_rate = moves ? translation_.law.first(t) : 0;
    for (int i = 0; i < d; ++i) {
      const double e_i = moves ? translation_.direction(i) : 0;
      c(i) = center_(i) + w * e_i;
      v(i) = w_rate * e_i;
      r(i) = x[i] - c(i);
    }
    if (axis_.size()) {
      double along = 0;
      for (int i = 0; i < d; ++i) along += r(i) * axis_(i);
      for (int i = 0; i < d; ++i) r(i) -= along * axis_(i);
    }
    const double distance = r.norm();
    // The unit vector from the centre (axis) to x; any direction at the centre.
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    if (distance > 0)
      e = r / distance;
    else
      e(0) = 1;
    const double s = side_ == Side::kOutside ? 1.0 : -1.0;
    ObstaclePoint p;
    p.phi = s * (distance - (R_ + radius_change_.value(t)));
    p.grad = s * e;
    // d|r|/dt = -e . c'(t) at a fixed x.
    p.phi_t = s * (-e.dot(v) - radius_change_.first(t));
    return p;
  }
  bool fixed() const override { return !translation_.moves() && radius_change_.constant(); }
  bool is_distance() const override { return true; }
  std::string describe() const override {
    return kind_ + " of radius " + std::to_string(R_) + " around " + text(center_) +
           (side_ == Side::kOutside ? ", body outside" : ", body inside");
  }

 private:
  std::string kind_;
  Vector center_, axis_;
  double R_;
  Side side_;
  Translation translation_;
  TimeLaw radius_change_;
};

class DistanceObstacle final : public RigidObstacle {
 public:
  DistanceObstacle(int dim, DistanceFunction phi, bool moving, std::string description)
      : RigidObstacle(dim), phi_(std::move(phi)), moving_(moving), description_(std::move(description)) {
    if (!phi_) throw InputError("signed distance: no function given");
  }
  ObstaclePoint at(const double* x, double t) const override {
    ObstaclePoint p = phi_(x, t);
    for (int i = dim(); i < 3; ++i) p.grad(i) = 0;
    if (!moving_) p.phi_t = 0;
    return p;
  }
  bool fixed() const override { return !moving_; }
  std::string describe() const override { return description_; }

 private:
  DistanceFunction phi_;
  bool moving_;
  std::string description_;
};

// A shape in a frame turning by theta(t) about a pivot (make_rotating):
// with r = y - pivot the point in the shape's frame, y = Q^T (x - pivot) + pivot,
//   grad phi(x) = Q grad phi_s(y),
//   d phi / dt  = phi_s,t(y) + grad phi_s(y) . dy/dt,  dy/dt = -theta' a x r
// (d/dt Q^T = -theta' [a]x Q^T, and Q^T commutes with [a]x; method.md §10).
class RotatingObstacle final : public RigidObstacle {
 public:
  RotatingObstacle(std::unique_ptr<RigidObstacle> shape, const Vector& pivot, const Vector& axis,
                   const TimeLaw& angle)
      : RigidObstacle(shape->dim()), shape_(std::move(shape)), angle_(angle) {
    const int d = dim();
    if (d < 2) throw InputError("obstacle rotation: a 1D obstacle cannot turn");
    if (pivot.size() != d)
      throw InputError("obstacle pivot: " + std::to_string(pivot.size()) + " coordinates, expected " +
                       std::to_string(d) + " (the obstacle's dimension)");
    check_finite(pivot, "obstacle pivot");
    angle_.check("obstacle rotation");
    pivot_.setZero();
    pivot_.head(d) = pivot;
    if (d == 2) {
      if (axis.size() != 0)
        throw InputError("obstacle rotation axis: given in 2D, where the rotation is in the plane");
      axis_ = Eigen::Vector3d::UnitZ();
    } else {
      if (axis.size() != 3)
        throw InputError("obstacle rotation axis: " + std::to_string(axis.size()) +
                         " coordinates, expected 3 (the direction a 3D obstacle turns about)");
      axis_ = unit(axis, "obstacle rotation axis");
    }
  }
  ObstaclePoint at(const double* x, double t) const override {
    const int d = dim();
    const double theta = angle_.value(t), rate = angle_.first(t);
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int i = 0; i < d; ++i) r(i) = x[i] - pivot_(i);
    const Eigen::Vector3d r_s = turn(r, -theta);  // Q^T (x - pivot)
    const Eigen::Vector3d y = r_s + pivot_;
    ObstaclePoint p = shape_->at(y.data(), t);
    const Eigen::Vector3d grad_s = p.grad;
    p.phi_t += grad_s.dot(-rate * axis_.cross(r_s));
    p.grad = turn(grad_s, theta);
    for (int i = d; i < 3; ++i) p.grad(i) = 0;
    return p;
  }
  bool fixed() const override { return angle_.constant() && shape_->fixed(); }
  bool is_distance() const override { return shape_->is_distance(); }  // turned rigidly
  std::string describe() const override {
    Vector pivot = pivot_.head(dim());
    return shape_->describe() + ", turning about " + text(pivot);
  }

 private:
  // v turned by the angle theta about axis_ (Rodrigues' formula).
  Eigen::Vector3d turn(const Eigen::Vector3d& v, double theta) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return c * v + s * axis_.cross(v) + (1 - c) * axis_.dot(v) * axis_;
  }

  std::unique_ptr<RigidObstacle> shape_;
  Eigen::Vector3d pivot_, axis_;
  TimeLaw angle_;
};

}  // namespace

double TimeLaw::value(double t) const {
  double w = offset + rate * t + 0.5 * accel * t * t;
  for (const Harmonic& h : harmonics) w += h.cos * std::cos(h.omega * t) + h.sin * std::sin(h.omega * t);
  return w;
}

double TimeLaw::first(double t) const {
  double w = rate + accel * t;
  for (const Harmonic& h : harmonics)
    w += h.omega * (h.sin * std::cos(h.omega * t) - h.cos * std::sin(h.omega * t));
  return w;
}

double TimeLaw::second(double t) const {
  double w = accel;
  for (const Harmonic& h : harmonics)
    w -= h.omega * h.omega * (h.cos * std::cos(h.omega * t) + h.sin * std::sin(h.omega * t));
  return w;
}

bool TimeLaw::constant() const {
  if (rate != 0 || accel != 0) return false;
  for (const Harmonic& h : harmonics)
    if (h.omega != 0 && (h.cos != 0 || h.sin != 0)) return false;
  return true;
}

void TimeLaw::check(const std::string& who) const {
  bool finite = std::isfinite(offset) && std::isfinite(rate) && std::isfinite(accel);
  for (const Harmonic& h : harmonics)
    finite = finite && std::isfinite(h.omega) && std::isfinite(h.cos) && std::isfinite(h.sin);
  if (!finite) throw InputError(who + ": non-finite coefficient");
}

RigidObstacle::RigidObstacle(int dim) : dim_(dim) {
  if (dim < 1 || dim > 3)
    throw InputError("obstacle: dimension " + std::to_string(dim) + ", expected 1, 2 or 3");
}

std::unique_ptr<RigidObstacle> make_plane(const Vector& point, const Vector& normal,
                                          const TimeLaw& shift) {
  return std::make_unique<Plane>(point, normal, shift);
}

std::unique_ptr<RigidObstacle> make_ball(const Vector& center, double R, Side side,
                                         const Vector& direction, const TimeLaw& translation,
                                         const TimeLaw& radius_change) {
  if (center.size() != 2 && center.size() != 3)
    throw InputError("circle or sphere centre: " + std::to_string(center.size()) +
                     " coordinates, expected 2 (circle) or 3 (sphere)");
  return std::make_unique<RoundObstacle>(center.size() == 2 ? "circle" : "sphere", center,
                                         Vector(), R, side, direction, translation,
                                         radius_change);
}

std::unique_ptr<RigidObstacle> make_cylinder(const Vector& point, const Vector& axis, double R,
                                             Side side, const Vector& direction,
                                             const TimeLaw& translation,
                                             const TimeLaw& radius_change) {
  if (point.size() != 3 || axis.size() != 3)
    throw InputError("cylinder point and axis: " + std::to_string(point.size()) + " and " +
                     std::to_string(axis.size()) +
                     " coordinates, expected 3 each (in 2D, a cylinder is a circle)");
  return std::make_unique<RoundObstacle>("cylinder", point, axis, R, side, direction,
                                         translation, radius_change);
}

std::unique_ptr<RigidObstacle> make_rotating(std::unique_ptr<RigidObstacle> shape,
                                             const Vector& pivot, const Vector& axis,
                                             const TimeLaw& angle) {
  if (!shape) throw InputError("obstacle rotation: no shape given");
  return std::make_unique<RotatingObstacle>(std::move(shape), pivot, axis, angle);
}

std::unique_ptr<RigidObstacle> make_distance_obstacle(int dim, DistanceFunction phi, bool moving,
                                                      std::string description) {
  return std::make_unique<DistanceObstacle>(dim, std::move(phi), moving, std::move(description));
}

}  // namespace nbm
