// A rigid obstacle described once: its shape, its motion, and what the
// contact step asks of it at any point and time -- the signed distance
// phi(x, t) (> 0 outside the obstacle, 0 on its surface), its gradient and its
// rate of change at a fixed point (method.md §8, §10). The contact frame of a
// node is taken where the node is, not where it started: normal
// n = -grad phi / |grad phi| and gap phi / |grad phi| at its current position.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/types.hpp"

namespace nbm {

/// A scalar function of time with its first two derivatives:
///   w(t) = offset + rate t + accel t^2 / 2 + sum_j (c_j cos(omega_j t) + s_j sin(omega_j t)).
/// Rigid motions of obstacles are made of these (translation along a
/// direction, change of radius); the blade-casing ovalisation
/// g0 - delta (1 - cos(k Omega t)) / 2 is offset -delta/2 and one harmonic
/// (k Omega, delta/2, 0).
struct TimeLaw {
  struct Harmonic {
    double omega = 0, cos = 0, sin = 0;
  };
  double offset = 0, rate = 0, accel = 0;
  std::vector<Harmonic> harmonics;

  double value(double t) const;
  double first(double t) const;   ///< dw/dt
  double second(double t) const;  ///< d2w/dt2
  bool constant() const;          ///< true if w never changes
  /// Throws InputError naming `who` on a non-finite coefficient.
  void check(const std::string& who) const;
};

/// What an obstacle says about one point x at time t.
struct ObstaclePoint {
  double phi = 0;              ///< signed distance (or a function with the same zero set)
  Eigen::Vector3d grad{0, 0, 0};  ///< grad phi (the first dim entries; the others 0)
  double phi_t = 0;            ///< d phi / dt at fixed x: the obstacle's motion
};

class RigidObstacle {
 public:
  explicit RigidObstacle(int dim);
  virtual ~RigidObstacle() = default;
  /// Space dimension of the points (1, 2 or 3).
  int dim() const { return dim_; }
  /// phi, grad phi and d phi / dt at x (dim() coordinates), time t.
  virtual ObstaclePoint at(const double* x, double t) const = 0;
  /// True if the normal is the same at every point and time (a plane, fixed
  /// or moving): the contact frame never changes and is exact once taken.
  virtual bool flat() const { return false; }
  /// True if the obstacle does not move (d phi / dt = 0 everywhere).
  virtual bool fixed() const = 0;
  /// True if phi is a signed distance, |phi(x) - phi(y)| <= |x - y|: a point
  /// at phi > 0 cannot reach the obstacle by moving less than phi.
  virtual bool is_distance() const { return false; }
  /// A one-line description for messages ("circle of radius 1.25 ...").
  virtual std::string describe() const = 0;

 private:
  int dim_;
};

/// Which side of a closed surface the body stays on.
enum class Side { kOutside, kInside };

/// A plane through `point` whose unit normal `normal` points out of the
/// obstacle (into the body's side), shifted by shift(t) along that normal:
/// phi(x, t) = normal . (x - point) - shift(t).
std::unique_ptr<RigidObstacle> make_plane(const Vector& point, const Vector& normal,
                                          const TimeLaw& shift = {});

/// A disc (2D) or ball (3D) of radius R + radius_change(t) whose centre moves
/// to center + translation(t) direction; the body stays outside it
/// (phi = |x - c| - R) or inside it (phi = R - |x - c|, a casing).
std::unique_ptr<RigidObstacle> make_ball(const Vector& center, double R, Side side,
                                         const Vector& direction = Vector(),
                                         const TimeLaw& translation = {},
                                         const TimeLaw& radius_change = {});

/// An infinite circular cylinder (3D) of axis point + s axis and radius
/// R + radius_change(t), moving like make_ball's centre.
std::unique_ptr<RigidObstacle> make_cylinder(const Vector& point, const Vector& axis, double R,
                                             Side side, const Vector& direction = Vector(),
                                             const TimeLaw& translation = {},
                                             const TimeLaw& radius_change = {});

/// `shape` turned by the angle theta(t) (radians, counter-clockwise about
/// `axis`) around the point `pivot`: phi(x, t) = phi_s(y, t) with
/// y = Q(t)^T (x - pivot) + pivot, Q(t) the rotation by theta(t). The shape's
/// own motion (translation, radius change) is that of the turning frame: a
/// cam, a tilting table, an eccentric rotor. In 2D the rotation is in the
/// plane (`axis` empty); in 3D `axis` is its direction (any length).
std::unique_ptr<RigidObstacle> make_rotating(std::unique_ptr<RigidObstacle> shape,
                                             const Vector& pivot, const Vector& axis,
                                             const TimeLaw& angle);

/// A signed distance given by a function (a script's): it fills phi, grad and
/// phi_t. `moving` says whether phi_t may be nonzero.
using DistanceFunction = std::function<ObstaclePoint(const double* x, double t)>;
std::unique_ptr<RigidObstacle> make_distance_obstacle(int dim, DistanceFunction phi, bool moving,
                                                      std::string description);

}  // namespace nbm
