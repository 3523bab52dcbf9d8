// Sanity of the benchmark matrices (bench/plate.cpp), P1 and P2: rigid
// motions are in the kernel of K, mass and load are those of the plate, and a
// uniform strain has the exact elastic energy. Exit code 1 on a failure.
#include <cmath>
#include <cstdio>

#include "plate.hpp"

int main() {
  int failures = 0;
  auto check = [&](const char* what, double got, double want, double tol) {
    const bool ok = std::abs(got - want) <= tol;
    std::printf("%-48s %14.6e  (expected %14.6e) %s\n", what, got, want, ok ? "ok" : "FAIL");
    failures += !ok;
  };
  for (int order : {1, 2}) {
    nbm_bench::Plate p;
    p.order = order;
    p.nx = 6;
    p.ny = 3;
    const nbm_bench::Assembled a = nbm_bench::assemble(p);
    const Eigen::MatrixXd X = nbm_bench::dof_positions(p);
    Eigen::VectorXd tx(p.n_dofs()), rot(p.n_dofs()), stretch(p.n_dofs()), ey(p.n_dofs());
    for (int d = 0; d < p.n_dofs(); ++d) {
      const bool is_x = d % 2 == 0;
      tx(d) = is_x ? 1 : 0;
      ey(d) = is_x ? 0 : 1;
      rot(d) = is_x ? -X(d, 1) : X(d, 0);  // infinitesimal rotation (-y, x)
      stretch(d) = is_x ? X(d, 0) : 0;     // u = (x, 0): eps_xx = 1
    }
    const double scale = a.K.diagonal().maxCoeff();
    std::printf("P%d, %d dofs\n", order, p.n_dofs());
    check("|K translation| / max K_ii", (a.K * tx).norm() / scale, 0, 1e-12);
    check("|K rotation| / max K_ii", (a.K * rot).norm() / scale, 0, 1e-12);
    check("mass of a translation", tx.dot(a.M * tx), p.rho * p.W * p.H, 1e-12);
    check("gravity load", a.F.dot(ey), -p.rho * p.g * p.W * p.H, 1e-12);
    const double lam = p.E * p.nu / ((1 + p.nu) * (1 - 2 * p.nu)), mu = p.E / (2 * (1 + p.nu));
    check("energy of the uniform stretch", 0.5 * stretch.dot(a.K * stretch),
          0.5 * (lam + 2 * mu) * p.W * p.H, 1e-9);
  }
  std::printf("plate assembly: %d failed\n", failures);
  return failures ? 1 : 0;
}
