// Curved bodies for the tests of obstacles that the body slides or rolls
// along (method.md §10), assembled here independently of the nbm core: a P1
// disc (concentric rings of triangles) and a P1 ball (a cube of tetrahedra
// mapped onto the ball), with their boundary nodes; and the rigid-body
// reference of a frictionless round body on a round obstacle.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "test_problems.hpp"

namespace nbm_test {

struct CurvedBody {
  Assembled a;
  Eigen::MatrixXd positions;       // one row per dof: its node's coordinates
  std::vector<long> contact_dofs;  // the boundary nodes' dofs, d per node
  int dim = 2;
};

inline Eigen::MatrixXd dof_positions(const std::vector<Eigen::VectorXd>& x, int dim) {
  Eigen::MatrixXd X(dim * x.size(), dim);
  for (std::size_t i = 0; i < x.size(); ++i)
    for (int c = 0; c < dim; ++c) X.row(dim * i + c) = x[i].transpose();
  return X;
}

/// A disc of radius r centred at c: a centre node and `rings` rings of 6 i
/// nodes at radius r i / rings, triangulated ring to ring; gravity g along -y.
inline CurvedBody disc(double r, const Eigen::Vector2d& c, int rings, double rho, double E,
                       double nu, double g) {
  std::vector<Eigen::Vector2d> x{c};
  std::vector<int> first{0};  // index of the first node of each ring
  const double pi = std::acos(-1.0);
  for (int i = 1; i <= rings; ++i) {
    first.push_back(static_cast<int>(x.size()));
    for (int j = 0; j < 6 * i; ++j) {
      const double t = 2 * pi * j / (6 * i);
      x.push_back(c + r * i / rings * Eigen::Vector2d(std::cos(t), std::sin(t)));
    }
  }
  std::vector<std::array<int, 3>> triangles;
  auto add = [&](int a, int b, int d) {
    const Eigen::Vector2d e1 = x[b] - x[a], e2 = x[d] - x[a];
    if (e1.x() * e2.y() - e1.y() * e2.x() > 0)
      triangles.push_back({a, b, d});
    else
      triangles.push_back({a, d, b});
  };
  for (int i = 1; i <= rings; ++i) {
    const int n_in = i == 1 ? 1 : 6 * (i - 1), n_out = 6 * i;
    // Merge the two rings by angle: each triangle advances one of them.
    int a = 0, b = 0;
    // (The centre, a ring of one node, only takes the fan of ring 1.)
    while (b < n_out || (n_in > 1 && a < n_in)) {
      const double ta = n_in == 1 ? 1e9 : 2 * pi * (a + 1) / n_in;
      const double tb = 2 * pi * (b + 1) / n_out;
      const int ia = first[i - 1] + a % n_in, ib = first[i] + b % n_out;
      if (tb <= ta && b < n_out) {
        add(ia, ib, first[i] + (b + 1) % n_out);
        ++b;
      } else {
        add(ia, ib, first[i - 1] + (a + 1) % n_in);
        ++a;
      }
    }
  }
  CurvedBody body;
  body.a = assemble_triangles(x, triangles, rho, E, nu, g, Eigen::Vector2d(0, -1));
  std::vector<Eigen::VectorXd> xs(x.begin(), x.end());
  body.positions = dof_positions(xs, 2);
  for (int j = 0; j < 6 * rings; ++j) {
    body.contact_dofs.push_back(2 * (first[rings] + j));
    body.contact_dofs.push_back(2 * (first[rings] + j) + 1);
  }
  return body;
}

/// P1 elasticity on tetrahedra: consistent mass, stiffness, gravity along -z.
inline Assembled assemble_tetrahedra(const std::vector<Eigen::Vector3d>& x,
                                     const std::vector<std::array<int, 4>>& tets, double rho,
                                     double E, double nu, double g) {
  const int n = 3 * static_cast<int>(x.size());
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>().setConstant(lam);
  for (int i = 0; i < 3; ++i) D(i, i) += 2 * mu, D(i + 3, i + 3) = mu;
  std::vector<Trip> m, k;
  Assembled a;
  a.F = Eigen::VectorXd::Zero(n);
  for (const auto& t : tets) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = x[t[c + 1]] - x[t[0]];
    const double volume = std::abs(J.determinant()) / 6;
    // Gradients of the barycentric coordinates: rows of J^-1 (and minus their sum).
    const Eigen::Matrix3d Jinv = J.inverse();
    Eigen::Matrix<double, 4, 3> grad;
    grad.row(0) = -Jinv.colwise().sum();
    for (int i = 0; i < 3; ++i) grad.row(i + 1) = Jinv.row(i);
    Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
    for (int i = 0; i < 4; ++i) {
      const double gx = grad(i, 0), gy = grad(i, 1), gz = grad(i, 2);
      B(0, 3 * i) = gx, B(1, 3 * i + 1) = gy, B(2, 3 * i + 2) = gz;
      B(3, 3 * i + 1) = gz, B(3, 3 * i + 2) = gy;
      B(4, 3 * i) = gz, B(4, 3 * i + 2) = gx;
      B(5, 3 * i) = gy, B(5, 3 * i + 1) = gx;
    }
    const Eigen::Matrix<double, 12, 12> Ke = volume * B.transpose() * D * B;
    for (int i = 0; i < 4; ++i) {
      a.F(3 * t[i] + 2) -= rho * g * volume / 4;
      for (int j = 0; j < 4; ++j)
        for (int c = 0; c < 3; ++c) {
          m.emplace_back(3 * t[i] + c, 3 * t[j] + c, rho * volume / 20 * (i == j ? 2 : 1));
          for (int e = 0; e < 3; ++e)
            k.emplace_back(3 * t[i] + c, 3 * t[j] + e, Ke(3 * i + c, 3 * j + e));
        }
    }
    a.mass += rho * volume;
  }
  set_matrices(a, n, m, k);
  return a;
}

/// The cube [-1, 1]^3 with n cells a side, each cut into 6 tetrahedra,
/// mapped by `map`; the boundary nodes (of the cube's faces) are the contact
/// candidates; gravity along -z.
template <class Map>
CurvedBody mapped_cube(int n, const Map& map, double rho, double E, double nu, double g) {
  auto node = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  std::vector<Eigen::Vector3d> x((n + 1) * (n + 1) * (n + 1));
  std::vector<bool> boundary(x.size(), false);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        x[node(i, j, k)] = map(Eigen::Vector3d(-1 + 2.0 * i / n, -1 + 2.0 * j / n, -1 + 2.0 * k / n));
        boundary[node(i, j, k)] = i == 0 || j == 0 || k == 0 || i == n || j == n || k == n;
      }
  std::vector<std::array<int, 4>> tets;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int v[8] = {node(i, j, k),         node(i + 1, j, k),     node(i + 1, j + 1, k),
                          node(i, j + 1, k),     node(i, j, k + 1),     node(i + 1, j, k + 1),
                          node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        // Six tetrahedra around the diagonal v0-v6 (a conforming split).
        const int paths[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
        for (const auto& p : paths) tets.push_back({v[0], v[p[0]], v[p[1]], v[6]});
      }
  CurvedBody body;
  body.dim = 3;
  body.a = assemble_tetrahedra(x, tets, rho, E, nu, g);
  std::vector<Eigen::VectorXd> xs(x.begin(), x.end());
  body.positions = dof_positions(xs, 3);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (boundary[i])
      for (int cc = 0; cc < 3; ++cc) body.contact_dofs.push_back(3 * static_cast<long>(i) + cc);
  return body;
}

/// A ball of radius r centred at c: mapped_cube with x -> r |x|_inf x / |x|_2
/// (the cube's faces onto the sphere).
inline CurvedBody ball(double r, const Eigen::Vector3d& c, int n, double rho, double E, double nu,
                       double g) {
  const auto onto_ball = [&](const Eigen::Vector3d& y) -> Eigen::Vector3d {
    const double norm = y.norm();
    return norm > 0 ? Eigen::Vector3d(c + r * y.cwiseAbs().maxCoeff() / norm * y) : c;
  };
  return mapped_cube(n, onto_ball, rho, E, nu, g);
}

/// The centre of mass of a displacement u (M-weighted, component by component).
inline Eigen::VectorXd centre_of_mass(const Sparse& M, const Eigen::MatrixXd& positions,
                                      const Eigen::VectorXd& u) {
  const int d = static_cast<int>(positions.cols());
  Eigen::VectorXd c(d);
  for (int j = 0; j < d; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(u.size()), xj = Eigen::VectorXd::Zero(u.size());
    for (int i = j; i < u.size(); i += d) e(i) = 1, xj(i) = positions(i, j) + u(i);
    c(j) = e.dot(M * xj) / e.dot(M * e);
  }
  return c;
}

/// Rigid reference: the centre of a frictionless round body (no torque about
/// its centre, so no rotation) on a circle of radius rho around the obstacle's
/// centre, angle theta from the vertical: theta'' = s (g / rho) sin theta, s =
/// -1 inside a bowl (theta from the bottom), +1 on top of a cylinder (theta
/// from the top). Advances (theta, omega) by dt in n classical RK4 steps.
inline void rigid_step(double& theta, double& omega, double g, double rho, double s, double dt,
                       int n) {
  const double h = dt / n, c = s * g / rho;
  for (int i = 0; i < n; ++i) {
    const double k1t = omega, k1w = c * std::sin(theta);
    const double k2t = omega + h / 2 * k1w, k2w = c * std::sin(theta + h / 2 * k1t);
    const double k3t = omega + h / 2 * k2w, k3w = c * std::sin(theta + h / 2 * k2t);
    const double k4t = omega + h * k3w, k4w = c * std::sin(theta + h * k3t);
    theta += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    omega += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
}

}  // namespace nbm_test
