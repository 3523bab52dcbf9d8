#include "block.hpp"

#include <algorithm>
#include <cmath>

namespace nbm_bench {
namespace {

using Vec3 = Eigen::Vector3d;

// Gauss-Legendre, 4 points on [0, 1] (exact to degree 7).
constexpr double kGaussX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                               0.9305681557970263};
constexpr double kGaussW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                               0.1739274225687269};

// Barycentric coordinates and weights (summing to 1) of a rule on the
// tetrahedron: the collapsed (Duffy) product of three 4-point Gauss rules,
// exact for the degree-4 integrands of the P2 mass (degree 6 in the
// collapsed variable once multiplied by the Jacobian (1-u)^2 (1-v)).
struct QuadraturePoint {
  double l[4], w;
};
std::vector<QuadraturePoint> tetrahedron_rule() {
  std::vector<QuadraturePoint> rule;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 4; ++c) {
        const double u = kGaussX[a], v = kGaussX[b], w = kGaussX[c];
        const double x = u, y = v * (1 - u), z = w * (1 - u) * (1 - v);
        // 6: the reference tetrahedron has volume 1/6.
        const double weight = 6 * kGaussW[a] * kGaussW[b] * kGaussW[c] * (1 - u) * (1 - u) * (1 - v);
        rule.push_back({{1 - x - y - z, x, y, z}, weight});
      }
  return rule;
}

// Edges of a tetrahedron: P2 nodes 4..9 are their midpoints.
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 3}, {0, 2}, {1, 3}, {0, 3}};

// Values and gradients of the Po basis at barycentric coordinates l, given
// the (constant) gradients of the barycentric coordinates.
int basis(int order, const double* l, const Vec3* dl, double* phi, Vec3* dphi) {
  if (order == 1) {
    for (int i = 0; i < 4; ++i) {
      phi[i] = l[i];
      dphi[i] = dl[i];
    }
    return 4;
  }
  for (int i = 0; i < 4; ++i) {
    phi[i] = l[i] * (2 * l[i] - 1);
    dphi[i] = (4 * l[i] - 1) * dl[i];
  }
  for (int e = 0; e < 6; ++e) {
    const int a = kEdges[e][0], b = kEdges[e][1];
    phi[4 + e] = 4 * l[a] * l[b];
    dphi[4 + e] = 4 * (l[a] * dl[b] + l[b] * dl[a]);
  }
  return 10;
}

// One of the six Kuhn tetrahedra of the unit cell: vertices 0, e_p0,
// e_p0 + e_p1, (1, 1, 1) in grid steps of the cell.
struct Tetrahedron {
  std::array<std::array<int, 3>, 10> offsets;  ///< node offsets in grid steps of the Po grid
  int n_nodes;
  Eigen::MatrixXd M, K;  ///< element matrices, dofs 3 node + c (node-local)
  Eigen::VectorXd F;
};

std::vector<Tetrahedron> kuhn_elements(const Block& b) {
  const double lam = b.E * b.nu / ((1 + b.nu) * (1 - 2 * b.nu));
  const double mu = b.E / (2 * (1 + b.nu));
  const Vec3 h(b.Lx / b.nx, b.Ly / b.ny, b.Lz / b.nz);
  const std::vector<QuadraturePoint> rule = tetrahedron_rule();
  std::array<int, 3> perm = {0, 1, 2};
  std::vector<Tetrahedron> tets;
  do {
    Tetrahedron t;
    std::array<std::array<int, 3>, 4> v{};  // vertices in cell steps
    for (int s = 1; s < 4; ++s) {
      v[s] = v[s - 1];
      v[s][perm[s - 1]] += 1;
    }
    const int o = b.order;
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) t.offsets[i][c] = o * v[i][c];
    if (o == 2)
      for (int e = 0; e < 6; ++e)
        for (int c = 0; c < 3; ++c) t.offsets[4 + e][c] = v[kEdges[e][0]][c] + v[kEdges[e][1]][c];
    t.n_nodes = o == 1 ? 4 : 10;
    Eigen::Matrix3d J;
    for (int s = 0; s < 3; ++s)
      for (int c = 0; c < 3; ++c) J(c, s) = (v[s + 1][c] - v[0][c]) * h(c);
    const double volume = std::abs(J.determinant()) / 6;
    const Eigen::Matrix3d Jinv_t = J.inverse().transpose();
    Vec3 dl[4];
    for (int s = 0; s < 3; ++s) dl[s + 1] = Jinv_t.col(s);
    dl[0] = -(dl[1] + dl[2] + dl[3]);
    const int nd = 3 * t.n_nodes;
    t.M = Eigen::MatrixXd::Zero(nd, nd);
    t.K = Eigen::MatrixXd::Zero(nd, nd);
    t.F = Eigen::VectorXd::Zero(nd);
    double phi[10];
    Vec3 dphi[10];
    for (const QuadraturePoint& q : rule) {
      basis(o, q.l, dl, phi, dphi);
      const double w = q.w * volume;
      for (int i = 0; i < t.n_nodes; ++i) {
        t.F(3 * i + 2) -= w * b.rho * b.g * phi[i];
        for (int j = 0; j < t.n_nodes; ++j) {
          const double mij = w * b.rho * phi[i] * phi[j];
          for (int c = 0; c < 3; ++c) t.M(3 * i + c, 3 * j + c) += mij;
          // sigma(u) : eps(v) for u = phi_j e_c, v = phi_i e_d.
          for (int d = 0; d < 3; ++d)
            for (int c = 0; c < 3; ++c)
              t.K(3 * i + d, 3 * j + c) += w * (lam * dphi[i](d) * dphi[j](c) + mu * dphi[i](c) * dphi[j](d) +
                                                (c == d ? mu * dphi[i].dot(dphi[j]) : 0.0));
        }
      }
    }
    tets.push_back(std::move(t));
  } while (std::next_permutation(perm.begin(), perm.end()));
  return tets;
}

}  // namespace

Block Block::with_dofs(int order, double dofs) {
  // The nz whose 3 (4 o nz + 1)^2 (o nz + 1) dofs are closest to `dofs`.
  Block b;
  b.order = order;
  auto count = [&](int nz) { return 3.0 * std::pow(4 * order * nz + 1, 2) * (order * nz + 1); };
  b.nz = 1;
  while (std::abs(count(b.nz + 1) - dofs) < std::abs(count(b.nz) - dofs)) ++b.nz;
  b.nx = b.ny = 4 * b.nz;
  return b;
}

Assembled assemble(const Block& b) {
  const std::vector<Tetrahedron> tets = kuhn_elements(b);
  const long n = b.n_dofs();
  Assembled a;
  a.F = Eigen::VectorXd::Zero(n);
  a.M.resize(n, n);
  a.K.resize(n, n);
  // Triplets in slabs of cells (bounded memory at 1e6 dofs), each slab summed
  // into the matrices.
  std::vector<Eigen::Triplet<double, int>> m, k;
  const size_t flush_at = 20'000'000;
  auto flush = [&] {
    Sparse Ms(n, n), Ks(n, n);
    Ms.setFromTriplets(m.begin(), m.end());
    Ks.setFromTriplets(k.begin(), k.end());
    a.M += Ms;
    a.K += Ks;
    m.clear();
    k.clear();
  };
  const int o = b.order;
  int dofs[30];
  for (int kz = 0; kz < b.nz; ++kz) {
    for (int jy = 0; jy < b.ny; ++jy)
      for (int ix = 0; ix < b.nx; ++ix)
        for (const Tetrahedron& t : tets) {
          for (int i = 0; i < t.n_nodes; ++i) {
            const int node = b.node(o * ix + t.offsets[i][0], o * jy + t.offsets[i][1],
                                    o * kz + t.offsets[i][2]);
            for (int c = 0; c < 3; ++c) dofs[3 * i + c] = 3 * node + c;
          }
          const int nd = 3 * t.n_nodes;
          for (int i = 0; i < nd; ++i) {
            a.F(dofs[i]) += t.F(i);
            for (int j = 0; j < nd; ++j) {
              if (t.M(i, j) != 0) m.emplace_back(dofs[i], dofs[j], t.M(i, j));
              k.emplace_back(dofs[i], dofs[j], t.K(i, j));
            }
          }
        }
    if (k.size() > flush_at) flush();
  }
  flush();
  a.K = Sparse(0.5 * (a.K + Sparse(a.K.transpose())));
  return a;
}

Eigen::MatrixXd dof_positions(const Block& b) {
  Eigen::MatrixXd X(b.n_dofs(), 3);
  for (int k = 0; k < b.nodes_z(); ++k)
    for (int j = 0; j < b.nodes_y(); ++j)
      for (int i = 0; i < b.nodes_x(); ++i)
        for (int c = 0; c < 3; ++c) X.row(3L * b.node(i, j, k) + c) = b.position(i, j, k).transpose();
  return X;
}

}  // namespace nbm_bench
