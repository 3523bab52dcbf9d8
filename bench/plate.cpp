#include "plate.hpp"

#include <algorithm>
#include <cmath>

namespace nbm_bench {
namespace {

using Vec2 = Eigen::Vector2d;

// Degree-4 quadrature on the reference triangle (Dunavant, 6 points);
// weights sum to 1 (multiplied by the area).
struct QuadraturePoint {
  double xi, eta, w;
};
const std::array<QuadraturePoint, 6> kRule = {{
    {0.445948490915965, 0.445948490915965, 0.223381589678011},
    {0.108103018168070, 0.445948490915965, 0.223381589678011},
    {0.445948490915965, 0.108103018168070, 0.223381589678011},
    {0.091576213509771, 0.091576213509771, 0.109951743655322},
    {0.816847572980459, 0.091576213509771, 0.109951743655322},
    {0.091576213509771, 0.816847572980459, 0.109951743655322},
}};

// Values and reference gradients of the Pk basis (vertices first, then the
// midpoints of edges 01, 12, 20 for P2).
int basis(int order, double xi, double eta, double* phi, Vec2* dphi) {
  const double l[3] = {1 - xi - eta, xi, eta};
  const Vec2 dl[3] = {{-1, -1}, {1, 0}, {0, 1}};
  if (order == 1) {
    for (int i = 0; i < 3; ++i) {
      phi[i] = l[i];
      dphi[i] = dl[i];
    }
    return 3;
  }
  for (int i = 0; i < 3; ++i) {
    phi[i] = l[i] * (2 * l[i] - 1);
    dphi[i] = (4 * l[i] - 1) * dl[i];
  }
  const int e[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (int k = 0; k < 3; ++k) {
    const int a = e[k][0], b = e[k][1];
    phi[3 + k] = 4 * l[a] * l[b];
    dphi[3 + k] = 4 * (l[a] * dl[b] + l[b] * dl[a]);
  }
  return 6;
}

}  // namespace

Plate Plate::with_dofs(int order, double dofs, int aspect) {
  // 2 (k nx + 1)(k ny + 1) ~ dofs with nx = aspect ny.
  Plate p;
  p.order = order;
  p.ny = std::max(1, static_cast<int>(std::lround(std::sqrt(dofs / (2.0 * aspect)) / order)));
  p.nx = aspect * p.ny;
  p.W = aspect * p.H;
  return p;
}

Plate Plate::of_cells(int nx, int ny, double cell) {
  Plate p;
  p.nx = nx;
  p.ny = ny;
  p.W = cell * nx;
  p.H = cell * ny;
  return p;
}

Assembled assemble(const Plate& p) {
  const double lam = p.E * p.nu / ((1 + p.nu) * (1 - 2 * p.nu));
  const double mu = p.E / (2 * (1 + p.nu));
  std::vector<Eigen::Triplet<double, int>> m, k;
  Assembled a;
  a.F = Eigen::VectorXd::Zero(p.n_dofs());
  const int s = p.order;  // grid steps per cell
  auto triangle = [&](const std::array<std::array<int, 2>, 3>& v) {
    // Nodes: vertices, then edge midpoints on the refined grid (P2).
    std::vector<int> nodes;
    for (const auto& c : v) nodes.push_back(p.node(c[0], c[1]));
    if (s == 2)
      for (int e = 0; e < 3; ++e) {
        const auto& c0 = v[e];
        const auto& c1 = v[(e + 1) % 3];
        nodes.push_back(p.node((c0[0] + c1[0]) / 2, (c0[1] + c1[1]) / 2));
      }
    const Vec2 x0 = p.position(v[0][0], v[0][1]);
    Eigen::Matrix2d J;
    J.col(0) = p.position(v[1][0], v[1][1]) - x0;
    J.col(1) = p.position(v[2][0], v[2][1]) - x0;
    const double area = 0.5 * std::abs(J.determinant());
    const Eigen::Matrix2d Jinv_t = J.inverse().transpose();
    double phi[6];
    Vec2 dphi[6];
    for (const QuadraturePoint& q : kRule) {
      const int nb = basis(p.order, q.xi, q.eta, phi, dphi);
      const double w = q.w * area;
      for (int i = 0; i < nb; ++i) {
        const Vec2 gi = Jinv_t * dphi[i];
        a.F(2 * nodes[i] + 1) -= w * p.rho * p.g * phi[i];
        for (int j = 0; j < nb; ++j) {
          const Vec2 gj = Jinv_t * dphi[j];
          const double mij = w * p.rho * phi[i] * phi[j];
          m.emplace_back(2 * nodes[i], 2 * nodes[j], mij);
          m.emplace_back(2 * nodes[i] + 1, 2 * nodes[j] + 1, mij);
          // sigma(u) : eps(v) for u = phi_j e_c, v = phi_i e_d.
          for (int d = 0; d < 2; ++d)
            for (int c = 0; c < 2; ++c) {
              const double kij = lam * gi(d) * gj(c) + mu * gi(c) * gj(d) +
                                 (c == d ? mu * gi.dot(gj) : 0.0);
              k.emplace_back(2 * nodes[i] + d, 2 * nodes[j] + c, w * kij);
            }
        }
      }
    }
  };
  for (int b = 0; b < p.ny; ++b)
    for (int c = 0; c < p.nx; ++c) {
      const int i = s * c, j = s * b;
      triangle({{{i, j}, {i + s, j}, {i + s, j + s}}});
      triangle({{{i, j}, {i + s, j + s}, {i, j + s}}});
    }
  a.M.resize(p.n_dofs(), p.n_dofs());
  a.K.resize(p.n_dofs(), p.n_dofs());
  a.M.setFromTriplets(m.begin(), m.end());
  a.K.setFromTriplets(k.begin(), k.end());
  a.K = Sparse(0.5 * (a.K + Sparse(a.K.transpose())));
  return a;
}

Eigen::MatrixXd dof_positions(const Plate& p) {
  Eigen::MatrixXd X(p.n_dofs(), 2);
  for (int j = 0; j < p.nodes_y(); ++j)
    for (int i = 0; i < p.nodes_x(); ++i)
      for (int c = 0; c < 2; ++c) X.row(2 * p.node(i, j) + c) = p.position(i, j).transpose();
  return X;
}

}  // namespace nbm_bench
