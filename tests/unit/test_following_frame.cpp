// The contact frame that follows the body (method.md §10): round bodies on
// round obstacles held exactly, against the rigid-body motion of the same
// frictionless problem (curved_problems.hpp), with the energy conserved to
// the scheme's accuracy and exact restarts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "contact/contact_problem.hpp"
#include "curved_problems.hpp"
#include "obstacle/rigid_obstacle.hpp"
#include "test_util.hpp"
#include "time/following_frame_stepper.hpp"

namespace {

using nbm_test::CurvedBody;
const double pi = std::acos(-1.0);

// phi, grad phi and phi_t of an obstacle against central differences.
void expect_consistent(const nbm::RigidObstacle& o, const Eigen::VectorXd& x, double t) {
  const int d = o.dim();
  const nbm::ObstaclePoint p = o.at(x.data(), t);
  const double h = 1e-6;
  for (int i = 0; i < d; ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h, xm(i) -= h;
    EXPECT_NEAR(p.grad(i), (o.at(xp.data(), t).phi - o.at(xm.data(), t).phi) / (2 * h), 1e-8)
        << o.describe() << ", component " << i;
  }
  EXPECT_NEAR(p.phi_t, (o.at(x.data(), t + h).phi - o.at(x.data(), t - h).phi) / (2 * h), 1e-7)
      << o.describe();
  double norm2 = 0;
  for (int i = 0; i < d; ++i) norm2 += p.grad(i) * p.grad(i);
  EXPECT_NEAR(std::sqrt(norm2), 1.0, 1e-14) << "a signed distance: " << o.describe();
}

TEST(RigidObstacle, SignedDistancesOfEveryKind) {
  nbm::TimeLaw law;
  law.offset = 0.1, law.rate = 0.3, law.harmonics = {{2.0, 0.05, -0.02}};
  const auto plane = nbm::make_plane(Eigen::Vector2d(0, -1), Eigen::Vector2d(1, 1), law);
  // phi = n . (x - p) - w(t), n = (1, 1)/sqrt 2.
  const Eigen::Vector2d x(0.3, 0.2);
  EXPECT_NEAR(plane->at(x.data(), 0.7).phi, (0.3 + 1.2) / std::sqrt(2.0) - law.value(0.7), 1e-15);
  EXPECT_TRUE(plane->flat());
  EXPECT_FALSE(plane->fixed());
  expect_consistent(*plane, x, 0.7);

  const auto bowl = nbm::make_ball(Eigen::Vector2d(0.1, 0), 1.25, nbm::Side::kInside,
                                   Eigen::Vector2d(1, 0), law, law);
  EXPECT_NEAR(bowl->at(x.data(), 0.0).phi,
              1.25 + law.value(0) - (x - Eigen::Vector2d(0.1 + law.value(0), 0)).norm(), 1e-15);
  expect_consistent(*bowl, x, 0.4);
  const auto ball = nbm::make_ball(Eigen::Vector3d(0, 0, -1), 0.7, nbm::Side::kOutside);
  const Eigen::Vector3d y(0.2, -0.3, 0.4);
  EXPECT_NEAR(ball->at(y.data(), 3.0).phi, (y - Eigen::Vector3d(0, 0, -1)).norm() - 0.7, 1e-15);
  EXPECT_TRUE(ball->fixed());
  expect_consistent(*ball, y, 3.0);
  const auto cylinder = nbm::make_cylinder(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 0, 0), 0.5,
                                           nbm::Side::kOutside, Eigen::Vector3d(0, 1, 1), law);
  // Distance to the axis: the x coordinate does not count.
  const Eigen::Vector3d c0(0, law.value(0) / std::sqrt(2.0), -1 + law.value(0) / std::sqrt(2.0));
  EXPECT_NEAR(cylinder->at(y.data(), 0.0).phi,
              Eigen::Vector2d(y(1) - c0(1), y(2) - c0(2)).norm() - 0.5, 1e-15);
  expect_consistent(*cylinder, y, 1.1);
}

TEST(RigidObstacle, BadInputNamed) {
  const auto expect_throw_with = nbm_test::expect_throw_with<nbm::InputError>;
  expect_throw_with([] { nbm::make_plane(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)); },
                    {"plane normal", "zero vector"});
  expect_throw_with([] { nbm::make_plane(Eigen::Vector2d(0, 0), Eigen::Vector3d(0, 0, 1)); },
                    {"plane normal", "expected 2"});
  expect_throw_with(
      [] { nbm::make_ball(Eigen::Vector2d(0, 0), -1, nbm::Side::kInside); },
      {"circle radius", "R > 0"});
  expect_throw_with(
      [] { nbm::make_ball(Eigen::Vector3d(0, 0, NAN), 1, nbm::Side::kInside); },
      {"sphere centre", "non-finite"});
  nbm::TimeLaw moving;
  moving.rate = 1;
  expect_throw_with(
      [&] { nbm::make_ball(Eigen::Vector2d(0, 0), 1, nbm::Side::kInside, Eigen::VectorXd(), moving); },
      {"circle direction", "needs the direction"});
  nbm::TimeLaw bad;
  bad.harmonics = {{INFINITY, 1, 0}};
  expect_throw_with([&] { nbm::make_plane(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1), bad); },
                    {"plane shift", "non-finite"});
  expect_throw_with(
      [] { nbm::make_cylinder(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1), 1, nbm::Side::kInside); },
      {"cylinder", "expected 3"});
}

// The obstacle's shape at y = Q^T (x - pivot) + pivot, Q from Eigen's
// angle-axis rotation (not the code under test's Rodrigues formula).
double turned_phi(const nbm::RigidObstacle& shape, const Eigen::Vector3d& pivot,
                  const Eigen::Vector3d& axis, double theta, const Eigen::VectorXd& x, double t) {
  const int d = shape.dim();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  r.head(d) = x - pivot.head(d);
  const Eigen::Vector3d y =
      Eigen::AngleAxisd(-theta, axis.normalized()).toRotationMatrix() * r + pivot;
  return shape.at(y.data(), t).phi;
}

TEST(RigidObstacle, TurningObstaclesAreTheirShapeTurned) {
  nbm::TimeLaw angle;
  angle.offset = 0.2, angle.rate = 1.5, angle.harmonics = {{3.0, 0.0, 0.1}};
  // A bowl of radius 1 centred at (0.3, 0.1), turning about the origin: a cam
  // whose centre runs on a circle, Q(theta) c.
  const Eigen::Vector2d c(0.3, 0.1);
  const auto cam = nbm::make_rotating(nbm::make_ball(c, 1.0, nbm::Side::kInside),
                                      Eigen::Vector2d(0, 0), Eigen::VectorXd(), angle);
  for (double t : {0.0, 0.4, 1.3}) {
    const double th = angle.value(t);
    const Eigen::Vector2d ct(std::cos(th) * c(0) - std::sin(th) * c(1),
                             std::sin(th) * c(0) + std::cos(th) * c(1));
    for (const Eigen::Vector2d& x : {Eigen::Vector2d(0.2, -0.5), Eigen::Vector2d(-0.4, 0.3)}) {
      EXPECT_NEAR(cam->at(x.data(), t).phi, 1.0 - (x - ct).norm(), 1e-15);
      expect_consistent(*cam, x, t);
    }
  }
  EXPECT_FALSE(cam->fixed());
  // A plane tilting about a point of its own, and one about another point.
  const auto shape = [] { return nbm::make_plane(Eigen::Vector2d(0, -1), Eigen::Vector2d(0, 1)); };
  for (const Eigen::Vector2d& pivot : {Eigen::Vector2d(0, -1), Eigen::Vector2d(0.5, 0.2)}) {
    const auto table = nbm::make_rotating(shape(), pivot, Eigen::VectorXd(), angle);
    const Eigen::Vector2d x(0.3, 0.2);
    const Eigen::Vector3d p3(pivot(0), pivot(1), 0);
    EXPECT_NEAR(table->at(x.data(), 0.7).phi,
                turned_phi(*shape(), p3, Eigen::Vector3d::UnitZ(), angle.value(0.7), x, 0.7), 1e-15);
    expect_consistent(*table, x, 0.7);
    EXPECT_FALSE(table->flat()) << "its normal turns";
  }
  // A translating cylinder (its motion is the turning frame's) turned about a
  // skew axis through a point off its own axis.
  nbm::TimeLaw shift;
  shift.harmonics = {{2.0, 0.05, -0.02}};
  const auto cylinder = [&] {
    return nbm::make_cylinder(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 0, 0), 0.5,
                              nbm::Side::kOutside, Eigen::Vector3d(0, 1, 1), shift);
  };
  const Eigen::Vector3d pivot(0.1, -0.2, 0.3), axis(1, 2, -0.5);
  const auto drum = nbm::make_rotating(cylinder(), pivot, axis, angle);
  const Eigen::Vector3d y(0.2, -0.3, 0.4);
  for (double t : {0.0, 0.9}) {
    EXPECT_NEAR(drum->at(y.data(), t).phi,
                turned_phi(*cylinder(), pivot, axis, angle.value(t), y, t), 1e-14);
    expect_consistent(*drum, y, t);
  }
  // A ball turning about its own centre does not move: d phi / dt = 0.
  const auto spinning = nbm::make_rotating(
      nbm::make_ball(Eigen::Vector3d(0, 0, -1), 0.7, nbm::Side::kOutside), Eigen::Vector3d(0, 0, -1),
      Eigen::Vector3d(0, 1, 1), angle);
  EXPECT_NEAR(spinning->at(y.data(), 0.5).phi_t, 0.0, 1e-15);
  // A constant angle is a fixed obstacle, turned once.
  nbm::TimeLaw tilt;
  tilt.offset = 0.3;
  EXPECT_TRUE(nbm::make_rotating(shape(), Eigen::Vector2d(0, -1), Eigen::VectorXd(), tilt)->fixed());
}

TEST(RigidObstacle, TurningBadInputNamed) {
  const auto expect_throw_with = nbm_test::expect_throw_with<nbm::InputError>;
  const auto plane2 = [] { return nbm::make_plane(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1)); };
  const auto ball3 = [] { return nbm::make_ball(Eigen::Vector3d(0, 0, 0), 1, nbm::Side::kInside); };
  nbm::TimeLaw angle;
  angle.rate = 1;
  expect_throw_with([&] { nbm::make_rotating(plane2(), Eigen::Vector3d(0, 0, 0), Eigen::VectorXd(), angle); },
                    {"obstacle pivot", "expected 2"});
  expect_throw_with([&] { nbm::make_rotating(plane2(), Eigen::Vector2d(0, NAN), Eigen::VectorXd(), angle); },
                    {"obstacle pivot", "non-finite"});
  expect_throw_with(
      [&] { nbm::make_rotating(plane2(), Eigen::Vector2d(0, 0), Eigen::Vector3d(0, 0, 1), angle); },
      {"rotation axis", "given in 2D"});
  expect_throw_with([&] { nbm::make_rotating(ball3(), Eigen::Vector3d(0, 0, 0), Eigen::VectorXd(), angle); },
                    {"rotation axis", "expected 3"});
  expect_throw_with(
      [&] { nbm::make_rotating(ball3(), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0), angle); },
      {"rotation axis", "zero vector"});
  nbm::TimeLaw bad;
  bad.rate = NAN;
  expect_throw_with([&] { nbm::make_rotating(plane2(), Eigen::Vector2d(0, 0), Eigen::VectorXd(), bad); },
                    {"obstacle rotation", "non-finite"});
  expect_throw_with([&] { nbm::make_rotating(nullptr, Eigen::Vector2d(0, 0), Eigen::VectorXd(), angle); },
                    {"obstacle rotation", "no shape"});
}

// A body, its problem in the user's axes and the stepper, started at rest.
struct FrameRun {
  CurvedBody body;
  std::unique_ptr<nbm::ContactProblem> problem;
  std::unique_ptr<nbm::FollowingFrameStepper> stepper;
  int max_frame_iterations = 0;

  FrameRun(CurvedBody b, std::shared_ptr<const nbm::RigidObstacle> obstacle, double dt,
           double rayleigh_stiffness = 0)
      : body(std::move(b)) {
    const long n = body.a.K.rows();
    std::vector<nbm::Index> dofs(body.contact_dofs.begin(), body.contact_dofs.end());
    problem = std::make_unique<nbm::ContactProblem>(
        body.a.M, body.a.K, nbm::ContactSet::in_user_axes(n, dofs, body.dim),
        std::vector<nbm::Index>{});
    nbm::Damping damping;
    damping.b_K = rayleigh_stiffness;
    stepper = std::make_unique<nbm::FollowingFrameStepper>(
        *problem, body.a.M, body.positions, std::move(obstacle), dt, nbm::FollowingFrameOptions{},
        damping);
    stepper->initialize(Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), body.a.F);
  }
  void step() {
    max_frame_iterations =
        std::max(max_frame_iterations, stepper->step(body.a.F).active_set_iterations);
  }
  // Total energy plus what the damping took, minus what a moving obstacle gave.
  double balance() const {
    const nbm::Energies e = stepper->energies();
    return e.total() + e.dissipated - e.obstacle_work;
  }
  Eigen::VectorXd centre() const {
    return nbm_test::centre_of_mass(stepper->mass(), body.positions, stepper->u());
  }
  // The true penetration and hovering of the contact nodes now, relative to
  // the body size: max(-phi) over all nodes and max |phi| over closed ones.
  void expect_on_surface(double tolerance) const {
    const Eigen::VectorXd phi = stepper->gaps();
    const auto& closed = stepper->active();
    const double L = stepper->body_size();
    for (Eigen::Index k = 0; k < phi.size(); ++k) {
      ASSERT_GE(phi(k), -tolerance * L) << "node " << k << " penetrates at t = " << stepper->time();
      if (closed[k]) {
        ASSERT_LE(phi(k), tolerance * L) << "closed node " << k << " hovers at t = " << stepper->time();
      }
    }
  }
};

// Stated tolerance of impenetrability: 1e-12 of the body size.
constexpr double kSurface = 1e-12;

// Largest error of the disc's angle in a bowl against the rigid pendulum over
// one period, and the largest drift of the energy (in m g h).
std::pair<double, double> disc_in_bowl(int rings, double E, double nu, double dt) {
  // Disc r = 0.5 released at rest 30 degrees up a circular bowl R = 1.25:
  // its centre swings on the circle rho = R - r like a pendulum.
  const double r = 0.5, R = 1.25, rho = R - r, g = 10, theta0 = pi / 6;
  const Eigen::Vector2d c(rho * std::sin(theta0), -rho * std::cos(theta0));
  FrameRun run(nbm_test::disc(r, c, rings, 1, E, nu, g),
               nbm::make_ball(Eigen::Vector2d(0, 0), R, nbm::Side::kInside), dt);
  const double E0 = run.balance(), mgh = run.body.a.mass * g * rho * (1 - std::cos(theta0));
  const int steps = static_cast<int>(2 * pi * std::sqrt(rho / g) * 1.02 / dt);
  double angle_error = 0, energy_error = 0, theta_ref = theta0, omega_ref = 0;
  for (int n = 1; n <= steps; ++n) {
    run.step();
    run.expect_on_surface(kSurface);
    nbm_test::rigid_step(theta_ref, omega_ref, g, rho, -1, dt, 10);
    const Eigen::VectorXd cm = run.centre();
    angle_error = std::max(angle_error, std::abs(std::atan2(cm(0), -cm(1)) - theta_ref));
    energy_error = std::max(energy_error, std::abs(run.balance() - E0) / mgh);
  }
  EXPECT_LE(run.max_frame_iterations, 6) << "the frame's fixed point converges in a few iterations";
  std::printf("disc in bowl, %d rings, E = %g, nu = %g, dt = %g: angle error %.2e rad, energy "
              "drift %.2e m g h, at most %d frame iterations\n",
              rings, E, nu, dt, angle_error, energy_error, run.max_frame_iterations);
  return {angle_error, energy_error};
}

TEST(FollowingFrame, DiscSlidingInBowlConvergesToTheRigidPendulum) {
  // The polygonal disc's centre rides r (1 - cos(pi / n_boundary)) up and
  // down: the error to the rigid disc falls with the mesh.
  for (auto [E, nu] : {std::pair{1e5, 0.3}, {1e4, 0.45}}) {
    const auto [coarse, coarse_energy] = disc_in_bowl(6, E, nu, 5e-4);
    const auto [fine, fine_energy] = disc_in_bowl(12, E, nu, 5e-4);
    EXPECT_LT(fine, 0.6 * coarse);
    EXPECT_LT(fine, 5e-3);
    EXPECT_LT(coarse_energy, 3e-3) << "energy conserved to the scheme's accuracy";
    EXPECT_LT(fine_energy, 5e-4) << "energy conserved to the scheme's accuracy";
  }
}

// The angle of the centre from the top of the obstacle when the body leaves
// it for good (no contact force for 0.2 s after).
double slide_off(nbm_test::CurvedBody body, std::shared_ptr<const nbm::RigidObstacle> obstacle,
                 double dt, double b_K, double t_end, int up) {
  FrameRun run(std::move(body), std::move(obstacle), dt, b_K);
  const double E0 = run.balance(), scale = run.body.a.mass * 10 * 0.5;
  double theta_detach = -1;
  int free_steps = 0;
  bool touched = false;
  while (run.stepper->time() < t_end && free_steps * dt < 0.2) {
    run.step();
    run.expect_on_surface(kSurface);
    const Eigen::VectorXd cm = run.centre();
    const Eigen::VectorXd radial = cm.head(up + 1);
    const double theta = std::atan2(radial.head(up).norm(), radial(up));
    if ((run.stepper->reactions().array() > 0).any()) {
      touched = true;
      free_steps = 0;
    } else if (touched && free_steps++ == 0) {
      theta_detach = theta;
    }
    EXPECT_LT(std::abs(run.balance() - E0), 5e-3 * scale) << "energy balance at t = " << run.stepper->time();
  }
  EXPECT_TRUE(touched);
  EXPECT_GE(free_steps * dt, 0.2) << "the body left the obstacle";
  return theta_detach;
}

TEST(FollowingFrame, DiscSlidesOffACylinderWhereTheRigidDiscLeaves) {
  // A rigid frictionless disc on top of a cylinder, from rest at theta0,
  // leaves it where the normal force m (g cos theta - rho theta'^2) vanishes:
  // with rho theta'^2 = 2 g (cos theta0 - cos theta), cos theta = 2/3 cos theta0.
  // Stiffness-proportional damping calms the bouncing of the dropped elastic
  // disc without acting on its rigid motion.
  const double r = 0.5, R = 1, rho = R + r, theta0 = 0.2;
  const double rigid = std::acos(2.0 / 3 * std::cos(theta0));
  std::vector<double> errors;
  for (int rings : {6, 12}) {
    const Eigen::Vector2d c(rho * std::sin(theta0), rho * std::cos(theta0));
    const double theta = slide_off(nbm_test::disc(r, c, rings, 1, 1e5, 0.3, 10),
                                   nbm::make_ball(Eigen::Vector2d(0, 0), R, nbm::Side::kOutside),
                                   5e-4, 2e-3, 1.5, 1);
    errors.push_back(std::abs(theta - rigid));
    std::printf("disc off a cylinder, %d rings: leaves at %.4f rad, rigid %.4f\n", rings, theta, rigid);
  }
  EXPECT_LT(errors[1], 0.5 * errors[0]);
  EXPECT_LT(errors[1], 0.06);
}

TEST(FollowingFrame, BallSlidesOffASphereAndAlongACylinder) {
  const double r = 0.5, R = 1, rho = R + r, theta0 = 0.2;
  const double rigid = std::acos(2.0 / 3 * std::cos(theta0));
  const Eigen::Vector3d c(rho * std::sin(theta0), 0, rho * std::cos(theta0));
  const double on_sphere =
      slide_off(nbm_test::ball(r, c, 4, 1, 1e5, 0.3, 10),
                nbm::make_ball(Eigen::Vector3d(0, 0, 0), R, nbm::Side::kOutside), 1e-3, 2e-3, 1.5, 2);
  std::printf("ball off a sphere: leaves at %.4f rad, rigid %.4f\n", on_sphere, rigid);
  EXPECT_NEAR(on_sphere, rigid, 0.05);
  // The same in the plane across a cylinder along y (phi ignores y).
  const double on_cylinder = slide_off(
      nbm_test::ball(r, c, 4, 1, 1e5, 0.3, 10),
      nbm::make_cylinder(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0), R, nbm::Side::kOutside),
      1e-3, 2e-3, 1.5, 2);
  std::printf("ball off a cylinder: leaves at %.4f rad, rigid %.4f\n", on_cylinder, rigid);
  EXPECT_NEAR(on_cylinder, rigid, 0.05);
}

TEST(FollowingFrame, MovingBowlBalancesItsWork) {
  // The bowl shakes sideways and breathes (its radius changes): the energy
  // the body gains is the obstacle's work, to the scheme's accuracy.
  nbm::TimeLaw shake, breathe;
  shake.harmonics = {{8.0, 0.0, 0.02}};
  breathe.offset = -0.005, breathe.harmonics = {{12.0, 0.005, 0.0}};
  const double r = 0.5, R = 1.25, rho = R - r;
  const Eigen::Vector2d c(rho * std::sin(0.3), -rho * std::cos(0.3));
  for (double dt : {1e-3, 5e-4}) {
    FrameRun run(nbm_test::disc(r, c, 8, 1, 1e4, 0.3, 10),
                 nbm::make_ball(Eigen::Vector2d(0, 0), R, nbm::Side::kInside, Eigen::Vector2d(1, 0),
                                shake, breathe),
                 dt);
    const double E0 = run.balance();
    double drift = 0, work = 0;
    while (run.stepper->time() < 1.0) {
      run.step();
      run.expect_on_surface(kSurface);
      drift = std::max(drift, std::abs(run.balance() - E0));
      work = std::max(work, std::abs(run.stepper->energies().obstacle_work));
    }
    std::printf("moving bowl, dt = %g: obstacle work up to %.3e, balance off by %.2e\n", dt, work, drift);
    EXPECT_GT(work, 1e-2) << "the bowl does work";
    EXPECT_LT(drift, 0.02 * work);
  }
}

TEST(FollowingFrame, TurningEccentricBowlHoldsTheDiscAndBalancesItsWork) {
  // A bowl of radius 1.25 centred at (0.1, 0) turning about the origin at
  // omega = 2: its centre runs on a circle of radius 0.1 and drives the disc.
  // The same run against the closed form of that moving circle (a distance
  // function: phi = R - |x - c(t)|, grad and d phi / dt by hand) must give the
  // same motion: the turned shape and its rate are checked through stepping.
  const double R = 1.25, omega = 2, e = 0.1, rho = R - 0.5;
  nbm::TimeLaw angle;
  angle.rate = omega;
  const Eigen::Vector2d c(rho * std::sin(0.3), -rho * std::cos(0.3));
  auto closed_form = [=](const double* x, double t) {
    const Eigen::Vector2d ct(e * std::cos(omega * t), e * std::sin(omega * t));
    const Eigen::Vector2d vt(-omega * ct(1), omega * ct(0));
    const Eigen::Vector2d r = Eigen::Vector2d(x[0], x[1]) - ct;
    nbm::ObstaclePoint p;
    p.phi = R - r.norm();
    p.grad.head(2) = -r / r.norm();
    p.phi_t = r.dot(vt) / r.norm();
    return p;
  };
  std::vector<double> drifts;
  for (double dt : {1e-3, 5e-4}) {
    FrameRun run(nbm_test::disc(0.5, c, 8, 1, 1e4, 0.3, 10),
                 nbm::make_rotating(nbm::make_ball(Eigen::Vector2d(e, 0), R, nbm::Side::kInside),
                                    Eigen::Vector2d(0, 0), Eigen::VectorXd(), angle),
                 dt);
    FrameRun reference(nbm_test::disc(0.5, c, 8, 1, 1e4, 0.3, 10),
                       nbm::make_distance_obstacle(2, closed_form, true, "moving circle"), dt);
    const double E0 = run.balance();
    double drift = 0, work = 0, difference = 0;
    while (run.stepper->time() < 1.0) {
      run.step();
      reference.step();
      run.expect_on_surface(kSurface);
      drift = std::max(drift, std::abs(run.balance() - E0));
      work = std::max(work, std::abs(run.stepper->energies().obstacle_work));
      difference = std::max(difference, (run.stepper->u() - reference.stepper->u()).cwiseAbs().maxCoeff());
    }
    const double size = run.stepper->u().cwiseAbs().maxCoeff();
    std::printf("turning bowl, dt = %g: obstacle work up to %.3e, balance off by %.2e, against the "
                "closed form %.2e of %.2e\n",
                dt, work, drift, difference, size);
    EXPECT_GT(work, 1e-2) << "the bowl does work";
    EXPECT_LT(drift, 0.005 * work);
    EXPECT_LT(difference, 1e-9 * size);
    drifts.push_back(drift);
  }
  EXPECT_LT(drifts[1], 0.6 * drifts[0]) << "the balance converges with dt";
}

TEST(FollowingFrame, RestartIsExactAcrossFrameUpdates) {
  const Eigen::Vector2d c(0.75 * std::sin(0.5), -0.75 * std::cos(0.5));
  auto bowl = [] { return nbm::make_ball(Eigen::Vector2d(0, 0), 1.25, nbm::Side::kInside); };
  FrameRun whole(nbm_test::disc(0.5, c, 5, 1, 1e4, 0.3, 10), bowl(), 1e-3);
  FrameRun second(nbm_test::disc(0.5, c, 5, 1, 1e4, 0.3, 10), bowl(), 1e-3);
  for (int n = 0; n < 150; ++n) whole.step();
  for (int n = 0; n < 37; ++n) second.step();  // a history of its own, then the restart
  const auto& s = *whole.stepper;
  second.stepper->restore(s.u(), s.v(), s.a(), s.active(), whole.body.a.F, s.time());
  for (int n = 0; n < 150; ++n) whole.step(), second.step();
  EXPECT_EQ((whole.stepper->u() - second.stepper->u()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((whole.stepper->v() - second.stepper->v()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(whole.stepper->time(), second.stepper->time());
}

// A disc (r = 0.5, E = 1e4) centred at c with its whole boundary as contact
// nodes, and the bowl of radius 1.25 around the origin.
struct DiscAndBowl {
  CurvedBody body;
  nbm::ContactProblem problem;
  std::shared_ptr<const nbm::RigidObstacle> bowl;
  DiscAndBowl(const Eigen::Vector2d& c, int rings)
      : body(nbm_test::disc(0.5, c, rings, 1, 1e4, 0.3, 10)),
        problem(body.a.M, body.a.K,
                nbm::ContactSet::in_user_axes(
                    body.a.K.rows(),
                    std::vector<nbm::Index>(body.contact_dofs.begin(), body.contact_dofs.end()), 2),
                std::vector<nbm::Index>{}),
        bowl(nbm::make_ball(Eigen::Vector2d(0, 0), 1.25, nbm::Side::kInside)) {}
};

TEST(FollowingFrame, KeptAndRecomputedContactColumnsStepAlike) {
  // Y = L^-1 P E_N kept (substitutions and products with Y) or not (whole
  // solves): the same steps to round-off, through contact changes.
  const DiscAndBowl setup(Eigen::Vector2d(0.75 * std::sin(0.5), -0.75 * std::cos(0.5)), 5);
  const auto& [body, problem, bowl] = std::tie(setup.body, setup.problem, setup.bowl);
  const long n = body.a.K.rows();
  nbm::FollowingFrameOptions kept, recomputed;
  kept.columns = nbm::ContactColumns::kKept;
  recomputed.columns = nbm::ContactColumns::kRecomputed;
  nbm::FollowingFrameStepper a(problem, body.a.M, body.positions, bowl, 1e-3, kept);
  nbm::FollowingFrameStepper b(problem, body.a.M, body.positions, bowl, 1e-3, recomputed);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  a.initialize(zero, zero, body.a.F);
  b.initialize(zero, zero, body.a.F);
  double worst = 0;
  int closed_steps = 0;
  for (int s = 0; s < 300; ++s) {
    a.step(body.a.F);
    b.step(body.a.F);
    worst = std::max(worst, (a.u() - b.u()).cwiseAbs().maxCoeff() / a.u().cwiseAbs().maxCoeff());
    closed_steps += a.active() != std::vector<bool>(a.active().size(), false);
  }
  EXPECT_GT(closed_steps, 100);
  EXPECT_LT(worst, 1e-10);
}

TEST(FollowingFrame, NodesOutsideTheContactSetCrossingAreCountedAndCanBeAdded) {
  // The disc at 60 degrees up the bowl touches it 30 degrees below its
  // horizontal; with only the boundary nodes more than 44 degrees below it as
  // contact nodes, the others sink into the bowl: counted at every step.
  const double r = 0.5, rho = 0.75, theta0 = pi / 3;
  const Eigen::Vector2d c(rho * std::sin(theta0), -rho * std::cos(theta0));
  auto body = nbm_test::disc(r, c, 6, 1, 1e4, 0.3, 10);
  const long n = body.a.K.rows();
  std::vector<nbm::Index> all(body.contact_dofs.begin(), body.contact_dofs.end()), low;
  for (std::size_t i = 0; i < all.size(); i += 2)
    if (body.positions(all[i], 1) < c(1) - 0.7 * r) low.insert(low.end(), {all[i], all[i + 1]});
  std::shared_ptr<const nbm::RigidObstacle> bowl =
      nbm::make_ball(Eigen::Vector2d(0, 0), 1.25, nbm::Side::kInside);
  const nbm::ContactProblem partial(body.a.M, body.a.K, nbm::ContactSet::in_user_axes(n, low, 2),
                                    std::vector<nbm::Index>{});
  nbm::FollowingFrameStepper s(partial, body.a.M, body.positions, bowl, 1e-3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  s.initialize(zero, zero, body.a.F);
  // Independently, at every step: the boundary nodes outside the partial set
  // inside the bowl (the stepper evaluates phi only for nodes that may have
  // reached it; here every one is looked at).
  int inside = 0;
  for (int k = 0; k < 20; ++k) {
    const int crossings = s.step(body.a.F).crossings;
    inside = 0;
    for (std::size_t i = 0; i < all.size(); i += 2) {
      if (std::find(low.begin(), low.end(), all[i]) != low.end()) continue;
      const Eigen::Vector2d x(body.positions(all[i], 0) + s.u()(all[i]),
                              body.positions(all[i + 1], 1) + s.u()(all[i + 1]));
      inside += x.norm() > 1.25 * (1 + 1e-12);
    }
    ASSERT_EQ(crossings, inside) << "step " << k;
  }
  EXPECT_GT(inside, 0);
  // Added (one setup): the whole boundary, continued from that state.
  const nbm::ContactProblem whole(body.a.M, body.a.K, nbm::ContactSet::in_user_axes(n, all, 2),
                                  std::vector<nbm::Index>{});
  nbm::FollowingFrameStepper t(whole, body.a.M, body.positions, bowl, 1e-3);
  const nbm::Obstacle rest = nbm::Obstacle::at_rest(whole.gaps());
  t.continue_from(s.u(), s.v(), nbm::ContactLoad{body.a.F, rest}, s.time());
  for (int k = 0; k < 50; ++k) {
    EXPECT_EQ(t.step(body.a.F).crossings, 0);
    ASSERT_GE(t.gaps().minCoeff(), -1e-12 * t.body_size());
  }
}

TEST(FollowingFrame, BadInputNamed) {
  const DiscAndBowl setup(Eigen::Vector2d(0, 0), 2);
  const auto& [body, problem, bowl] = std::tie(setup.body, setup.problem, setup.bowl);
  const long n = body.a.K.rows();
  const std::vector<nbm::Index> dofs(body.contact_dofs.begin(), body.contact_dofs.end());
  const auto expect_throw_with = nbm_test::expect_throw_with<nbm::InputError>;
  const auto make = [&](const nbm::ContactProblem& p, const Eigen::MatrixXd& X,
                        std::shared_ptr<const nbm::RigidObstacle> o, double dt,
                        const nbm::Damping& damping = {}) {
    nbm::FollowingFrameStepper(p, body.a.M, X, std::move(o), dt, {}, damping);
  };
  expect_throw_with([&] { make(problem, body.positions, bowl, 0); }, {"dt", "positive"});
  nbm::Damping damping;
  damping.b_K = -1;
  expect_throw_with([&] { make(problem, body.positions, bowl, 1e-3, damping); }, {"damping"});
  damping.b_K = 0;
  damping.C_user = body.a.M;
  expect_throw_with([&] { make(problem, body.positions, bowl, 1e-3, damping); },
                    {"damping matrix", "Rayleigh damping only"});
  expect_throw_with(
      [&] { make(problem, body.positions, nbm::make_ball(Eigen::Vector3d(0, 0, 0), 1, nbm::Side::kInside), 1e-3); },
      {"obstacle", "dimension 3", "expected 2"});
  expect_throw_with([&] { make(problem, body.positions.leftCols(1), bowl, 1e-3); },
                    {"positions", "expected"});
  // A rotated contact set: its redistributed mass would depend on the normals.
  std::vector<double> normals;
  for (std::size_t k = 0; k < dofs.size() / 2; ++k) normals.insert(normals.end(), {0.6, 0.8});
  const nbm::ContactProblem tilted(
      body.a.M, body.a.K, nbm::ContactSet(n, dofs, normals, Eigen::VectorXd::Zero(dofs.size() / 2)),
      std::vector<nbm::Index>{});
  expect_throw_with([&] { make(tilted, body.positions, bowl, 1e-3); }, {"user's axes"});
  // A disc of radius 0.5 centred in a bowl of radius 0.4 starts inside the obstacle.
  nbm::FollowingFrameStepper s(problem, body.a.M, body.positions,
                               nbm::make_ball(Eigen::Vector2d(0, 0), 0.4, nbm::Side::kInside), 1e-3);
  expect_throw_with([&] { s.step(body.a.F); }, {"no initial state"});
  expect_throw_with([&] { s.initialize(Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), body.a.F); },
                    {"initial penetration", "circle of radius"});
  expect_throw_with([&] { s.initialize(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(n), body.a.F); },
                    {"u", "expected " + std::to_string(n)});
}

}  // namespace
