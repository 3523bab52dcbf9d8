#include "contact_region.hpp"

namespace nbm_bench {

double sweep_length(const Eigen::MatrixXd& X, const ContactRegion& region) {
  const double width = region.fraction * (X.col(0).maxCoeff() - X.col(0).minCoeff());
  return X.cols() == 3 ? width + region.tilt * (X.col(1).maxCoeff() - X.col(1).minCoeff()) : width;
}

nbm::ContactDescription contact_on(const Eigen::MatrixXd& X, const ContactRegion& region) {
  const int dim = static_cast<int>(X.cols()), up = dim - 1;
  const double x_min = X.col(0).minCoeff(), x_max = X.col(0).maxCoeff(), y_min = X.col(1).minCoeff();
  const double bottom = X.col(up).minCoeff(), top = X.col(up).maxCoeff();
  const double tol = 1e-9 * (top - bottom), x_end = x_min + region.fraction * (x_max - x_min);
  nbm::ContactDescription c;
  auto add = [&](long node, double normal) {
    for (int j = 0; j < dim; ++j) {
      c.dofs.push_back(dim * node + j);
      c.normals.push_back(j == up ? normal : 0.0);
    }
    double s = X(dim * node, 0) - x_min;
    if (dim == 3) s += region.tilt * (X(dim * node, 1) - y_min);
    c.gaps.push_back(region.gap + region.slope * s);
  };
  for (long node = 0; node < X.rows() / dim; ++node) {
    const double x = X(dim * node, 0), z = X(dim * node, up);
    if (z <= bottom + tol && x <= x_end + tol) add(node, -1);
    else if (region.top && z >= top - tol) add(node, 1);
  }
  return c;
}

}  // namespace nbm_bench
