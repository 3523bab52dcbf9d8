// nbm::ContactSet: input validation (each error names its argument) and the
// orthogonal rotation into (normal, tangential) coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/errors.hpp"
#include "contact/contact_set.hpp"
#include "test_util.hpp"

namespace {

using nbm::ContactSet;
using nbm::Index;
using nbm_test::expect_throw_with;

Eigen::VectorXd gaps(std::initializer_list<double> g) {
  Eigen::VectorXd v(g.size());
  int i = 0;
  for (double x : g) v(i++) = x;
  return v;
}

// A valid 2D set on 10 dofs: nodes (2,3) and (6,7), normals -e2 and e1.
TEST(ContactSetValidation, AcceptsAValidSet) {
  const ContactSet c(10, {2, 3, 6, 7}, {0, -1, 1, 0}, gaps({0.1, 0.0}), {0, 1});
  EXPECT_EQ(c.size(), 2);
  EXPECT_EQ(c.dim(), 2);
  EXPECT_EQ(c.dof(1, 1), 7);
  EXPECT_EQ(c.normal(0, 1), -1.0);
  EXPECT_EQ(c.gaps()(0), 0.1);
}

TEST(ContactSetValidation, EmptySet) {
  expect_throw_with<nbm::InputError>([] { ContactSet(4, {}, {}, Eigen::VectorXd(0)); },
                                     {"contact set is empty"});
}

TEST(ContactSetValidation, DofsNotAMultipleOfGaps) {
  expect_throw_with<nbm::InputError>(
      [] { ContactSet(10, {1, 2, 3}, {1, 0, 0}, gaps({0, 0})); },
      {"contact dofs", "not a multiple", "gaps"});
}

TEST(ContactSetValidation, MoreThanThreeDofsPerNode) {
  expect_throw_with<nbm::InputError>(
      [] { ContactSet(10, {0, 1, 2, 3}, {1, 0, 0, 0}, gaps({0})); },
      {"contact dofs", "expected 1, 2 or 3"});
}

TEST(ContactSetValidation, WrongNormalsSize) {
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2, 3}, {1}, gaps({0})); },
                                     {"normals", "size 1", "expected 2"});
}

TEST(ContactSetValidation, DofIndexOutOfRange) {
  expect_throw_with<nbm::InputError>([] { ContactSet(5, {5}, {1}, gaps({0})); },
                                     {"contact dofs", "index 5", "[0, 5)"});
  expect_throw_with<nbm::InputError>([] { ContactSet(5, {-1}, {1}, gaps({0})); },
                                     {"contact dofs", "index -1"});
}

TEST(ContactSetValidation, DuplicateDof) {
  expect_throw_with<nbm::InputError>(
      [] { ContactSet(10, {2, 3, 3, 4}, {0, 1, 0, 1}, gaps({0, 0})); },
      {"contact dofs", "dof 3", "twice"});
}

TEST(ContactSetValidation, OverlapWithFixedDof) {
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {4}, {1}, gaps({0}), {1, 4}); },
                                     {"contact dofs", "dof 4", "fixed"});
}

TEST(ContactSetValidation, FixedDofOutOfRange) {
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {4}, {1}, gaps({0}), {10}); },
                                     {"fixed: index 10", "outside"});
}

TEST(ContactSetValidation, NonFiniteNormal) {
  expect_throw_with<nbm::InputError>(
      [] { ContactSet(10, {2, 3}, {std::nan(""), 1}, gaps({0})); },
      {"normals", "non-finite", "contact node 0"});
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2, 3}, {INFINITY, 0}, gaps({0})); },
                                     {"normals", "non-finite"});
}

TEST(ContactSetValidation, NonFiniteGap) {
  expect_throw_with<nbm::InputError>(
      [] { ContactSet(10, {2, 5}, {1, -1}, gaps({0, std::nan("")})); },
      {"gaps", "non-finite", "contact node 1"});
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2}, {1}, gaps({INFINITY})); },
                                     {"gaps", "non-finite"});
}

TEST(ContactSetValidation, NonUnitNormal) {
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2, 3}, {0.6, 0.7}, gaps({0})); },
                                     {"normals", "unit"});
  // 1D: a normal must be +1 or -1.
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2}, {2.0}, gaps({0})); },
                                     {"normals", "unit"});
}

TEST(ContactSetValidation, ZeroNormal) {
  expect_throw_with<nbm::InputError>([] { ContactSet(10, {2, 3}, {0, 0}, gaps({0})); },
                                     {"normals", "|n| = 0"});
}

TEST(ContactSetValidation, NormalsNormalisedInDoublePrecisionAreAccepted) {
  // n = (1, 1)/sqrt(2) rounded: |n| differs from 1 by an ulp or so.
  const double c = 1 / std::sqrt(2.0);
  EXPECT_NO_THROW(ContactSet(10, {2, 3}, {c, c}, gaps({0})));
}

// ---------------------------------------------------------------- rotation

// Checks T for a set of normals of dimension `dim` on n_dofs dofs: T is
// orthogonal, its node blocks have the normal as first column, it is the
// identity away from contact nodes, and (T^T u) at the normal slot is n.u.
void check_rotation(const std::vector<std::vector<double>>& normals, int dim) {
  const Index n_nodes = static_cast<Index>(normals.size());
  const Index n_dofs = dim * n_nodes + 3;  // 3 dofs that are not contact dofs
  std::vector<Index> dofs;
  std::vector<double> flat;
  // Interleave contact nodes after the first extra dof: dofs 1 .. dim n_nodes.
  for (Index k = 0; k < n_nodes; ++k)
    for (int j = 0; j < dim; ++j) {
      dofs.push_back(1 + k * dim + j);
      flat.push_back(normals[k][j]);
    }
  const ContactSet c(n_dofs, dofs, flat, Eigen::VectorXd::Zero(n_nodes));
  const Eigen::MatrixXd T = Eigen::MatrixXd(c.rotation(n_dofs));
  ASSERT_EQ(T.rows(), n_dofs);
  EXPECT_LE((T.transpose() * T - Eigen::MatrixXd::Identity(n_dofs, n_dofs)).cwiseAbs().maxCoeff(),
            1e-15);
  for (Index k = 0; k < n_nodes; ++k)
    for (int i = 0; i < dim; ++i) {
      EXPECT_NEAR(T(c.dof(k, i), c.dof(k, 0)), normals[k][i], 4e-16)
          << "node " << k << ", normal " << normals[k][0] << " " << normals[k][1];
      // No coupling between different nodes.
      for (Index l = 0; l < n_nodes; ++l)
        if (l != k) {
          for (int j = 0; j < dim; ++j) EXPECT_EQ(T(c.dof(k, i), c.dof(l, j)), 0.0);
        }
    }
  for (Index d : {Index(0), n_dofs - 2, n_dofs - 1}) {
    EXPECT_EQ(T(d, d), 1.0);
    EXPECT_EQ(T.col(d).cwiseAbs().sum(), 1.0);
  }
  std::mt19937 rng(5);
  const Eigen::VectorXd u = nbm_test::random_vector(static_cast<int>(n_dofs), rng);
  const Eigen::VectorXd u_rot = T.transpose() * u;
  const Eigen::VectorXd un = c.normal_displacement(u);
  for (Index k = 0; k < n_nodes; ++k) {
    double expected = 0;
    for (int j = 0; j < dim; ++j) expected += normals[k][j] * u(c.dof(k, j));
    EXPECT_NEAR(un(k), expected, 1e-14);
    EXPECT_NEAR(u_rot(c.dof(k, 0)), expected, 1e-14);
  }
}

TEST(ContactSetRotation, OneDimensionalNormals) {
  check_rotation({{1.0}, {-1.0}}, 1);
}

TEST(ContactSetRotation, TwoDimensionalAxisAndRandomNormals) {
  std::vector<std::vector<double>> n = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int i = 0; i < 20; ++i) {
    const double a = angle(rng);
    n.push_back({std::sin(a), -std::cos(a)});
  }
  // Nearly axis-aligned normals: the reflection must stay well defined.
  n.push_back({std::cos(1e-9), std::sin(1e-9)});
  n.push_back({-std::cos(1e-9), std::sin(1e-9)});
  check_rotation(n, 2);
}

TEST(ContactSetRotation, ThreeDimensionalAxisAndRandomNormals) {
  std::vector<std::vector<double>> n = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::mt19937 rng(12);
  for (int i = 0; i < 20; ++i) {
    Eigen::Vector3d v = nbm_test::random_vector(3, rng);
    v.normalize();
    n.push_back({v(0), v(1), v(2)});
  }
  check_rotation(n, 3);
}

}  // namespace
