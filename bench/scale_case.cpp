#include "scale_case.hpp"

#include <cmath>

#include "time/central_difference_stepper.hpp"

namespace nbm_bench {

Case assemble_body(int body, int order, double dofs) {
  Case c;
  if (body == kBlock) {
    const Block b = Block::with_dofs(order, dofs);
    c.a = assemble(b);
    c.X = dof_positions(b);
  } else {
    const Plate p = Plate::with_dofs(order, dofs, body == kStrip ? 80 : 2);
    c.a = assemble(p);
    c.X = dof_positions(p);
  }
  return c;
}

ContactRegion scale_region(int contact_pct) {
  ContactRegion r;
  r.fraction = contact_pct >= 100 ? 1 : contact_pct / 100.0;
  r.top = contact_pct == 200;
  return r;
}

ContactRegion sweeping(ContactRegion r, const Eigen::MatrixXd& X, double dt) {
  r.gap = 0.5 * kSweepSpeed * dt;
  r.slope = kSweepSpeed * kSweepSteps * dt / sweep_length(X, r);
  return r;
}

Eigen::VectorXd falling(const Eigen::MatrixXd& X) {
  const Eigen::Index dim = X.cols();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(X.rows());
  for (Eigen::Index d = dim - 1; d < v.size(); d += dim) v(d) = -kSweepSpeed;
  return v;
}

double explicit_dt(const nbm::SparseMatrix& K, const Eigen::VectorXd& m) {
  return 0.5 * 2 / std::sqrt(nbm::max_eigenvalue(K, m));
}

}  // namespace nbm_bench
