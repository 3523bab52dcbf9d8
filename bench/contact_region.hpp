// Contact descriptions of the benchmark bodies (bench/plate.hpp,
// bench/block.hpp) from their node positions: the bottom face (edge in 2D),
// optionally the top one too, or the part x <= fraction of the bottom face;
// normals along the last coordinate (bottom -e, top +e), gap g0 + slope s
// with s = (x - x_min) + tilt (y - y_min) in 3D, x - x_min in 2D: with
// slope > 0 the obstacle is inclined, and a body falling onto it touches it
// along a front sweeping the contact set (the active set changing at every
// step; the tilt makes the nodes of a column of the grid arrive one after
// another).
#pragma once

#include <Eigen/Dense>

#include "api/solver.hpp"

namespace nbm_bench {

struct ContactRegion {
  double fraction = 1;    ///< part x <= x_min + fraction (x_max - x_min) of the bottom face
  bool top = false;       ///< the whole top face too (candidates a falling body never touches)
  double gap = 1e-3;      ///< g0
  double slope = 0;       ///< gap growth per unit of s
  double tilt = 0.25;     ///< weight of y in s (3D)
};

/// The extent of s over the contact region (x only in 2D).
double sweep_length(const Eigen::MatrixXd& X, const ContactRegion& region);

/// X: node coordinates of every dof (n_dofs x dim), dofs dim node + c.
nbm::ContactDescription contact_on(const Eigen::MatrixXd& X, const ContactRegion& region);

}  // namespace nbm_bench
