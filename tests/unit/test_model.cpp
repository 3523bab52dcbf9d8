// nbm::Model, the structure built once and shared: time integrators built on
// it follow the shorthand Solver(M, K, contact, options) bit for bit, share
// its contact problem, and meet the same checks; a model needs no time step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "api/model.hpp"
#include "api/solver.hpp"
#include "base/errors.hpp"
#include "contact/contact_problem.hpp"
#include "test_problems.hpp"
#include "test_util.hpp"

namespace {

using nbm::Model;
using nbm::ModelOptions;
using nbm::SchemeOptions;
using nbm::Solver;
using nbm::SolverOptions;
using nbm_test::expect_throw_with;
using StdVec = std::vector<double>;

// A plate on an inclined ground (rotated contact nodes), dropped from a gap.
struct InclinedPlate {
  nbm_test::Plate plate;
  nbm_test::Assembled a;
  nbm::CooMatrix M, K;
  nbm::ContactDescription contact;
  StdVec F, positions;
  InclinedPlate() {
    plate.angle = 0.4;
    a = assemble(plate);
    M = nbm_test::to_coo(a.M);
    K = nbm_test::to_coo(a.K);
    contact = nbm_test::bottom_contact(plate, 0.01);
    F = nbm_test::to_std(a.F);
    const Eigen::MatrixXd X = nbm_test::node_positions(plate);
    for (Eigen::Index i = 0; i < X.rows(); ++i)
      for (Eigen::Index j = 0; j < X.cols(); ++j) positions.push_back(X(i, j));
  }
  ModelOptions model_options(const std::string& mass) const {
    ModelOptions o;
    o.mass = nbm_test::mass_named(mass);
    if (mass == "redistributed") o.positions = positions;
    o.rayleigh_mass = 0.5;  // the model carries the damping
    return o;
  }
};

class ModelShared : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelShared, IntegratorsOfOneModelFollowTheShorthandBitForBit) {
  const InclinedPlate p;
  const ModelOptions mo = p.model_options(GetParam());
  const auto model = std::make_shared<const Model>(p.M, p.K, p.contact, mo);
  for (const double dt : {1e-3, 2.5e-3}) {
    SchemeOptions so;
    so.dt = dt;
    Solver on_model(model, so);
    SolverOptions both;
    static_cast<ModelOptions&>(both) = mo;
    static_cast<SchemeOptions&>(both) = so;
    Solver shorthand(p.M, p.K, p.contact, both);
    // The integrator reads the model's problem, not a copy.
    EXPECT_EQ(&on_model.model()->problem(), &model->problem());
    const auto a = nbm_test::displacements(on_model, p.F, 120);
    const auto b = nbm_test::displacements(shorthand, p.F, 120);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "step " << k;
    long touching = 0;  // the plate rests on the ground at the end
    for (long a : on_model.active()) touching += a;
    EXPECT_GT(touching, 0) << "the plate never touched the ground: the comparison proves little";
    EXPECT_EQ(on_model.options().rayleigh_mass, 0.5);
    EXPECT_EQ(on_model.options().dt, dt);
  }
  EXPECT_EQ(model.use_count(), 1);  // the integrators are gone, the model stays
}

INSTANTIATE_TEST_SUITE_P(BothMasses, ModelShared,
                         ::testing::Values("consistent", "redistributed"));

TEST(Model, ReplacingContactsGivesTheIntegratorItsOwnModel) {
  const InclinedPlate p;
  const auto model = std::make_shared<const Model>(p.M, p.K, p.contact, p.model_options("consistent"));
  SchemeOptions so;
  so.dt = 1e-3;
  Solver s(model, so);
  StdVec u(p.F.size(), 0.0), v(p.F.size(), 0.0);
  s.initialize(u, v, p.F);
  nbm::ContactDescription fewer = p.contact;
  const long d = 2;
  fewer.dofs.resize(fewer.dofs.size() - d);
  fewer.normals.resize(fewer.normals.size() - d);
  fewer.gaps.pop_back();
  s.replace_contacts(fewer, u, v, p.F);
  EXPECT_NE(s.model(), model);
  EXPECT_EQ(s.n_contact(), model->n_contact() - 1);
  EXPECT_EQ(model->n_contact(), static_cast<long>(p.contact.gaps.size()));  // unchanged
  s.step(u, v, p.F);
}

TEST(Model, ThePeriodicToolsGetTheObstacleLinearisedAtTheReference) {
  // A model holding a circle below the plate (obstacle=): its linearised
  // model has, at each contact node x_k, the normal -(x_k - c)/|x_k - c| and
  // the gap |x_k - c| - R, computed here by hand.
  const InclinedPlate p;
  ModelOptions o = p.model_options("redistributed");
  double lowest = 1e300;
  for (std::size_t i = 1; i < p.positions.size(); i += 2) lowest = std::min(lowest, p.positions[i]);
  nbm::ObstacleDescription circle;
  circle.kind = "circle";
  circle.point = {0.3, lowest - 10};
  circle.radius = 9.5;
  o.obstacle = circle;
  const Model held(p.M, p.K, p.contact, o);
  const auto linear = held.with_obstacle_linearised();
  EXPECT_FALSE(linear->options().obstacle);
  const nbm::ContactSet& c = linear->problem().contacts();
  ASSERT_EQ(c.size(), static_cast<nbm::Index>(p.contact.gaps.size()));
  for (nbm::Index k = 0; k < c.size(); ++k) {
    const long dx = p.contact.dofs[2 * k], dy = p.contact.dofs[2 * k + 1];
    EXPECT_EQ(c.dof(k, 0), dx);
    const double rx = p.positions[2 * dx] - 0.3, ry = p.positions[2 * dy + 1] - (lowest - 10);
    const double r = std::hypot(rx, ry);
    EXPECT_NEAR(c.normal(k, 0), -rx / r, 1e-15);
    EXPECT_NEAR(c.normal(k, 1), -ry / r, 1e-15);
    EXPECT_NEAR(c.gaps()(k), r - 9.5, 1e-14);
  }
  EXPECT_TRUE(linear->massless_boundary());
  // Without an obstacle, or with one that moves: refused by name.
  expect_throw_with<nbm::InputError>(
      [&] { Model(p.M, p.K, p.contact, p.model_options("redistributed")).with_obstacle_linearised(); },
      {"obstacle", "no obstacle="});
  circle.translation.rate = 0.1;
  circle.direction = {0, 1};
  o.obstacle = circle;
  expect_throw_with<nbm::InputError>([&] { Model(p.M, p.K, p.contact, o).with_obstacle_linearised(); },
                                     {"obstacle: circle", "moves by its own law", "gapCos"});
}

TEST(Model, AForcedOrbitGetsTheMovingObstaclesGapHarmonics) {
  // A ground plane under the plate moving along its normal by
  // w(t) = a1 cos(omega t) + b1 sin(omega t) + a2 cos(2 omega t): every node's
  // gap is g0 - w(t), so the harmonics are -a1, -b1 (k = 1) and -a2 (k = 2),
  // the mean g0 = the distance at rest (to round-off of the discrete
  // Fourier sums: 1e-13 of the gaps).
  const InclinedPlate p;
  ModelOptions o = p.model_options("redistributed");
  double lowest = 1e300;
  for (std::size_t i = 1; i < p.positions.size(); i += 2) lowest = std::min(lowest, p.positions[i]);
  const double omega = 7, a1 = 0.003, b1 = -0.002, a2 = 0.001;
  nbm::ObstacleDescription ground;
  ground.kind = "plane";
  ground.point = {0, lowest - 0.01};
  ground.axis = {0, 1};
  ground.translation.harmonics = {omega, a1, b1, 2 * omega, a2, 0};
  o.obstacle = ground;
  const Model held(p.M, p.K, p.contact, o);
  EXPECT_TRUE(held.obstacle_moves());
  const nbm::ObstacleHarmonics h = held.with_obstacle_harmonics(omega);
  ASSERT_EQ(h.gap_cos.size(), 2u);
  ASSERT_EQ(h.gap_sin.size(), 2u);
  const nbm::ContactSet& c = h.model->problem().contacts();
  for (nbm::Index k = 0; k < c.size(); ++k) {
    const long dy = p.contact.dofs[2 * k + 1];
    EXPECT_NEAR(c.gaps()(k), p.positions[2 * dy + 1] - (lowest - 0.01), 1e-15);
    EXPECT_NEAR(h.gap_cos[0][k], -a1, 1e-15);
    EXPECT_NEAR(h.gap_sin[0][k], -b1, 1e-15);
    EXPECT_NEAR(h.gap_cos[1][k], -a2, 1e-15);
    EXPECT_NEAR(h.gap_sin[1][k], 0.0, 1e-15);
  }
  // A frequency the law is not a sum of harmonics of: refused.
  expect_throw_with<nbm::InputError>([&] { held.with_obstacle_harmonics(1.5 * omega); },
                                     {"not periodic with the excitation's period"});
  expect_throw_with<nbm::InputError>([&] { held.with_obstacle_linearised(); },
                                     {"moves by its own law", "nbmForcedOrbit"});
}

TEST(ModelErrors, TheModelChecksItsOwnOptions) {
  const InclinedPlate p;
  ModelOptions o;
  o.positions = p.positions;
  expect_throw_with<nbm::InputError>([&] { Model(p.M, p.K, p.contact, o); },
                                     {"positions: given with mass = \"consistent\""});
  o = ModelOptions();
  o.mass = nbm::MassTreatment::kRedistributed;
  expect_throw_with<nbm::InputError>([&] { Model(p.M, p.K, p.contact, o); }, {"positions: size 0"});
  o = ModelOptions();
  o.rayleigh_mass = -1;
  expect_throw_with<nbm::InputError>([&] { Model(p.M, p.K, p.contact, o); }, {"a_M: -1"});
}

TEST(ModelErrors, TheIntegratorChecksItsSchemeAgainstTheModel) {
  const InclinedPlate p;
  const auto massless =
      std::make_shared<const Model>(p.M, p.K, p.contact, p.model_options("redistributed"));
  SchemeOptions so;
  so.dt = 1e-3;
  so.scheme = nbm::TimeScheme::kExplicit;
  expect_throw_with<nbm::InputError>([&] { Solver(massless, so); },
                                     {"mass: \"redistributed\" needs scheme \"newmark\""});
  const auto damped =
      std::make_shared<const Model>(p.M, p.K, p.contact, p.model_options("consistent"));
  so = SchemeOptions();
  so.dt = 1e-3;
  so.energy = nbm::EnergyControl::kBounded;
  expect_throw_with<nbm::InputError>([&] { Solver(damped, so); }, {"energy: given without"});
  expect_throw_with<nbm::InputError>([&] { Solver(nullptr, so); }, {"model: none given"});
  so = SchemeOptions();
  expect_throw_with<nbm::InputError>([&] { Solver(damped, so); }, {"dt"});
}

}  // namespace
