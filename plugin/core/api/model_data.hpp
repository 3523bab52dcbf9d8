// What a Model holds, in the core's own types: read by the time integrator
// (api/solver.cpp). Not part of the Eigen-free facade (api/model.hpp).
#pragma once

#include <memory>
#include <vector>

#include "api/model.hpp"
#include "base/types.hpp"
#include "contact/contact_problem.hpp"
#include "contact/damping.hpp"
#include "obstacle/rigid_obstacle.hpp"

namespace nbm {

struct Model::Data {
  ModelOptions options;
  std::vector<long> fixed;  // sorted, without repeats
  // The user's matrices as given: a new contact description (with_contacts)
  // is built on them, so that a model built from scratch with it is the same
  // bit for bit (internal ones rotate back only to round-off).
  SparseMatrix M_user, K_user;
  Damping damping_user;  // the damping with its matrix in user coordinates
  Damping damping;       // the same in the problem's internal coordinates
  // Mass "redistributed": the node coordinates, one row per user dof.
  Matrix positions;
  // The option obstacle (method.md §10): null without it.
  std::shared_ptr<const RigidObstacle> obstacle;
  std::unique_ptr<ContactProblem> problem;
};

}  // namespace nbm
