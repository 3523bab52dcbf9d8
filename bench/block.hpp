// Linear elasticity of a rectangular block, assembled here for the 3D
// benchmarks (no FreeFEM): Lagrange P1 or P2 tetrahedra on a structured mesh
// of nx x ny x nz cells, each cut into the six tetrahedra of Kuhn's
// subdivision (the same in every cell, so the mesh is conforming and the
// edge midpoints of P2 are the nodes of the grid refined twice), consistent
// mass, stiffness and gravity load (along -z). Node (i, j, k) of the
// (o nx + 1) x (o ny + 1) x (o nz + 1) grid of a Po mesh has dofs 3 node + c.
#pragma once

#include "plate.hpp"

namespace nbm_bench {

struct Block {
  int order = 1;  ///< 1 or 2
  int nx = 8, ny = 8, nz = 2;
  double Lx = 1, Ly = 1, Lz = 0.25, E = 1000, nu = 0.3, rho = 1, g = 10;
  int nodes_x() const { return order * nx + 1; }
  int nodes_y() const { return order * ny + 1; }
  int nodes_z() const { return order * nz + 1; }
  int node(int i, int j, int k) const { return (k * nodes_y() + j) * nodes_x() + i; }
  long n_dofs() const { return 3L * nodes_x() * nodes_y() * nodes_z(); }
  Eigen::Vector3d position(int i, int j, int k) const {
    return {Lx * i / (order * nx), Ly * j / (order * ny), Lz * k / (order * nz)};
  }
  /// Mesh with about `dofs` degrees of freedom and cells nx = ny = 4 nz
  /// (the 32 x 32 x 8 block of issue 14 at 3e4 P1 dofs: 29403).
  static Block with_dofs(int order, double dofs);
};

Assembled assemble(const Block& b);

/// Node coordinates of every dof (n_dofs x 3).
Eigen::MatrixXd dof_positions(const Block& b);

}  // namespace nbm_bench
