// Test problems assembled here, independently of the nbm core: a P1 bar and a
// P1 plane-strain rectangle, with consistent mass, stiffness and gravity load,
// plus their contact boundaries. All quantities are in user coordinates.
#pragma once

#include <array>
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <vector>

#include <stdexcept>
#include <string>

#include "api/solver.hpp"

namespace nbm_test {

// The core's options are typed; tests parameterized by the front end's names
// ("explicit", "redistributed", ...) read them through nbm::name.
inline nbm::TimeScheme scheme_named(const std::string& n) {
  for (nbm::TimeScheme s : {nbm::TimeScheme::kNewmark, nbm::TimeScheme::kGeneralizedAlpha,
                            nbm::TimeScheme::kHhtAlpha, nbm::TimeScheme::kExplicit,
                            nbm::TimeScheme::kMoreauJean})
    if (n == nbm::name(s)) return s;
  throw std::invalid_argument("no scheme " + n);
}
inline nbm::MassTreatment mass_named(const std::string& n) {
  for (nbm::MassTreatment m : {nbm::MassTreatment::kConsistent, nbm::MassTreatment::kRedistributed})
    if (n == nbm::name(m)) return m;
  throw std::invalid_argument("no mass treatment " + n);
}

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Trip = Eigen::Triplet<double, int>;

struct Assembled {
  Sparse M, K;
  Eigen::VectorXd F;  // gravity load
  double mass = 0;    // total mass rho * |Omega|
};

// ---------------------------------------------------------------- 1D bar

/// Bar on (0, L), cross-section 1, N P1 elements, nodes x_i = i h (dof i).
/// Gravity g acts along -x (towards the ground at x = 0).
struct Bar {
  double L = 1, rho = 1, E = 100, g = 10;
  int N = 20;
  double h() const { return L / N; }
  int n_dofs() const { return N + 1; }
  /// Wave speed and the exact free-free lumped-mass omega_max^2 = 4E/(rho h^2).
  double omega_max_lumped() const { return std::sqrt(4 * E / (rho * h() * h())); }
};

inline Assembled assemble(const Bar& b) {
  const int n = b.n_dofs();
  const double h = b.h();
  std::vector<Trip> m, k;
  Assembled a;
  a.F = Eigen::VectorXd::Zero(n);
  for (int e = 0; e < b.N; ++e) {
    const int d[2] = {e, e + 1};
    for (int i = 0; i < 2; ++i) {
      a.F(d[i]) -= b.rho * b.g * h / 2;
      for (int j = 0; j < 2; ++j) {
        m.emplace_back(d[i], d[j], b.rho * h / 6 * (i == j ? 2 : 1));
        k.emplace_back(d[i], d[j], b.E / h * (i == j ? 1 : -1));
      }
    }
  }
  a.M.resize(n, n);
  a.K.resize(n, n);
  a.M.setFromTriplets(m.begin(), m.end());
  a.K.setFromTriplets(k.begin(), k.end());
  a.mass = b.rho * b.L;
  return a;
}

// ------------------------------------------------- 2D plane-strain plate

/// Rectangle [0, W] x [0, H] in its own frame, nx x ny cells each cut into two
/// P1 triangles, rotated as a whole by `angle` (counter-clockwise). Node (i, j)
/// has index j (nx+1) + i and dofs 2 node, 2 node + 1 (x, y). Gravity acts along
/// the rotated -e_y, which is also the outward normal of the bottom edge j = 0:
/// n = (sin a, -cos a).
struct Plate {
  double W = 1, H = 0.5, rho = 1, E = 100, nu = 0.3, g = 10, angle = 0;
  int nx = 4, ny = 2;
  int n_nodes() const { return (nx + 1) * (ny + 1); }
  int n_dofs() const { return 2 * n_nodes(); }
  int node(int i, int j) const { return j * (nx + 1) + i; }
  Eigen::Vector2d normal() const { return {std::sin(angle), -std::cos(angle)}; }
  Eigen::Matrix2d rotation() const {
    Eigen::Matrix2d R;
    R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return R;
  }
  Eigen::Vector2d position(int i, int j) const {
    return rotation() * Eigen::Vector2d(W * i / nx, H * j / ny);
  }
  std::vector<int> bottom_nodes() const {
    std::vector<int> b;
    for (int i = 0; i <= nx; ++i) b.push_back(node(i, 0));
    return b;
  }
};

/// M and K of size n from their element triplets, K symmetric to the last
/// bit (the element matrices are, up to round-off).
inline void set_matrices(Assembled& a, int n, const std::vector<Trip>& m,
                         const std::vector<Trip>& k) {
  a.M.resize(n, n);
  a.K.resize(n, n);
  a.M.setFromTriplets(m.begin(), m.end());
  a.K.setFromTriplets(k.begin(), k.end());
  a.K = Sparse(0.5 * (a.K + Sparse(a.K.transpose())));
}

/// P1 plane-strain elasticity on triangles (counter-clockwise node lists):
/// consistent mass, stiffness and the load of gravity g along the unit
/// vector gdir. Node i has dofs 2 i, 2 i + 1.
inline Assembled assemble_triangles(const std::vector<Eigen::Vector2d>& x,
                                    const std::vector<std::array<int, 3>>& triangles, double rho,
                                    double E, double nu, double g, const Eigen::Vector2d& gdir) {
  const int n = 2 * static_cast<int>(x.size());
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  Eigen::Matrix3d D;
  D << lam + 2 * mu, lam, 0, lam, lam + 2 * mu, 0, 0, 0, mu;
  std::vector<Trip> m, k;
  Assembled a;
  a.F = Eigen::VectorXd::Zero(n);
  for (const auto& nodes : triangles) {
    const Eigen::Vector2d xe[3] = {x[nodes[0]], x[nodes[1]], x[nodes[2]]};
    const double area = 0.5 * ((xe[1] - xe[0]).x() * (xe[2] - xe[0]).y() -
                               (xe[2] - xe[0]).x() * (xe[1] - xe[0]).y());
    Eigen::Matrix<double, 3, 6> B = Eigen::Matrix<double, 3, 6>::Zero();
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d& xj = xe[(i + 1) % 3];
      const Eigen::Vector2d& xk = xe[(i + 2) % 3];
      const double bi = (xj.y() - xk.y()) / (2 * area), ci = (xk.x() - xj.x()) / (2 * area);
      B(0, 2 * i) = bi;
      B(1, 2 * i + 1) = ci;
      B(2, 2 * i) = ci;
      B(2, 2 * i + 1) = bi;
    }
    const Eigen::Matrix<double, 6, 6> Ke = area * B.transpose() * D * B;
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 2; ++c) {
        a.F(2 * nodes[i] + c) += rho * g * area / 3 * gdir(c);
        for (int j = 0; j < 3; ++j) {
          m.emplace_back(2 * nodes[i] + c, 2 * nodes[j] + c, rho * area / 12 * (i == j ? 2 : 1));
          for (int d = 0; d < 2; ++d)
            k.emplace_back(2 * nodes[i] + c, 2 * nodes[j] + d, Ke(2 * i + c, 2 * j + d));
        }
      }
    }
    a.mass += rho * area;
  }
  set_matrices(a, n, m, k);
  return a;
}

inline Assembled assemble(const Plate& p) {
  std::vector<Eigen::Vector2d> x(p.n_nodes());
  for (int j = 0; j <= p.ny; ++j)
    for (int i = 0; i <= p.nx; ++i) x[p.node(i, j)] = p.position(i, j);
  std::vector<std::array<int, 3>> triangles;
  for (int j = 0; j < p.ny; ++j)
    for (int i = 0; i < p.nx; ++i) {
      triangles.push_back({p.node(i, j), p.node(i + 1, j), p.node(i + 1, j + 1)});
      triangles.push_back({p.node(i, j), p.node(i + 1, j + 1), p.node(i, j + 1)});
    }
  Assembled a = assemble_triangles(x, triangles, p.rho, p.E, p.nu, p.g, p.normal());
  a.mass = p.rho * p.W * p.H;
  return a;
}

/// Bottom-edge contact of the plate: every bottom node, normal n, gap `gap`.
inline nbm::ContactDescription bottom_contact(const Plate& p, double gap) {
  nbm::ContactDescription c;
  const Eigen::Vector2d n = p.normal();
  for (int node : p.bottom_nodes()) {
    c.dofs.push_back(2 * node);
    c.dofs.push_back(2 * node + 1);
    c.normals.push_back(n.x());
    c.normals.push_back(n.y());
    c.gaps.push_back(gap);
  }
  return c;
}

/// Ground contact of the bar at x = 0: outward normal -1.
inline nbm::ContactDescription ground_contact(double gap = 0) {
  nbm::ContactDescription c;
  c.dofs = {0};
  c.normals = {-1.0};
  c.gaps = {gap};
  return c;
}

/// Node coordinates of every user dof, one row per dof (the `positions` of
/// the mass redistribution): x for the bar, (x, y) for the plate.
inline Eigen::MatrixXd node_positions(const Bar& b) {
  Eigen::MatrixXd X(b.n_dofs(), 1);
  for (int i = 0; i < b.n_dofs(); ++i) X(i, 0) = i * b.h();
  return X;
}
inline Eigen::MatrixXd node_positions(const Plate& p) {
  Eigen::MatrixXd X(p.n_dofs(), 2);
  for (int j = 0; j <= p.ny; ++j)
    for (int i = 0; i <= p.nx; ++i)
      for (int c = 0; c < 2; ++c) X.row(2 * p.node(i, j) + c) = p.position(i, j).transpose();
  return X;
}

// ----------------------------------------------------------- conversions

/// Coordinate form of a sparse matrix, full or lower triangle only.
inline nbm::CooMatrix to_coo(const Sparse& A, bool lower_half = false) {
  nbm::CooMatrix c;
  c.rows = A.rows();
  c.cols = A.cols();
  c.lower_half = lower_half;
  for (int j = 0; j < A.outerSize(); ++j)
    for (Sparse::InnerIterator it(A, j); it; ++it) {
      if (lower_half && it.row() < it.col()) continue;
      c.i.push_back(it.row());
      c.j.push_back(it.col());
      c.value.push_back(it.value());
    }
  return c;
}

inline std::vector<double> to_std(const Eigen::VectorXd& x) { return {x.data(), x.data() + x.size()}; }
inline Eigen::VectorXd to_eigen(const std::vector<double>& x) {
  return Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
}

/// Physical energy 1/2 v'Mv + 1/2 u'Ku - F'u, computed in user coordinates.
inline double total_energy(const Assembled& a, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(a.M * v) + 0.5 * u.dot(a.K * u) - a.F.dot(u);
}

/// The displacements of `steps` steps of `s` from u = u0 (every dof), v = 0
/// under the constant load F, the initial state first.
inline std::vector<std::vector<double>> displacements(nbm::Solver& s, const std::vector<double>& F,
                                                      int steps, double u0 = 0) {
  std::vector<double> u(F.size(), u0), v(F.size(), 0.0);
  s.initialize(u, v, F);
  std::vector<std::vector<double>> out{u};
  for (int k = 0; k < steps; ++k) {
    s.step(u, v, F);
    out.push_back(u);
  }
  return out;
}

}  // namespace nbm_test
