// Plane-strain elasticity of a rectangular plate, assembled here for the
// benchmarks (no FreeFEM, no synthetic matrices): Lagrange P1 or P2 triangles
// on a structured mesh of nx x ny cells (two triangles each), consistent mass,
// stiffness and gravity load (bench/contact_region.hpp describes its
// contacts). Node (i, j) of the (k nx + 1) x (k ny + 1) grid of a Pk mesh has
// dofs 2 node (x) and 2 node + 1 (y).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <array>
#include <vector>

#include "api/solver.hpp"

namespace nbm_bench {

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

struct Plate {
  int order = 1;  ///< 1 or 2
  int nx = 40, ny = 20;
  double W = 1, H = 0.5, E = 1000, nu = 0.3, rho = 1, g = 10;
  int nodes_x() const { return order * nx + 1; }
  int nodes_y() const { return order * ny + 1; }
  int node(int i, int j) const { return j * nodes_x() + i; }
  int n_dofs() const { return 2 * nodes_x() * nodes_y(); }
  Eigen::Vector2d position(int i, int j) const {
    return {W * i / (order * nx), H * j / (order * ny)};
  }
  /// Mesh with about `dofs` degrees of freedom, square cells and aspect
  /// ratio W/H = `aspect` (80: the 2000 x 25 strip of issue 14 at 1e5 P1 dofs).
  static Plate with_dofs(int order, double dofs, int aspect = 2);
  /// P1 mesh of nx x ny square cells of side `cell` (the hand-run tools').
  static Plate of_cells(int nx, int ny, double cell = 0.02);
};

struct Assembled {
  Sparse M, K;
  Eigen::VectorXd F;
};

Assembled assemble(const Plate& p);

/// Node coordinates of every dof (n_dofs x 2), for mass redistribution.
Eigen::MatrixXd dof_positions(const Plate& p);

}  // namespace nbm_bench
