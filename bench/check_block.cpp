// Sanity of the 3D benchmark matrices (bench/block.cpp), P1 and P2: the six
// rigid motions are in the kernel of K, mass and load are those of the
// block, uniform strains have their exact elastic energy, and the contact
// regions (bench/contact_region.cpp) hold the nodes and gaps they should. Exit code 1
// on a failure.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "block.hpp"
#include "contact_region.hpp"

int main() {
  int failures = 0;
  auto check = [&](const char* what, double got, double want, double tol) {
    const bool ok = std::abs(got - want) <= tol;
    std::printf("%-48s %14.6e  (expected %14.6e) %s\n", what, got, want, ok ? "ok" : "FAIL");
    failures += !ok;
  };
  for (int order : {1, 2}) {
    nbm_bench::Block b;  // distinct cell sizes along x, y, z
    b.order = order;
    b.nx = 3;
    b.ny = 2;
    b.nz = 2;
    b.Lx = 1.5;
    b.Ly = 0.7;
    b.Lz = 0.4;
    const nbm_bench::Assembled a = nbm_bench::assemble(b);
    const Eigen::MatrixXd X = nbm_bench::dof_positions(b);
    const long n = b.n_dofs();
    const double scale = a.K.diagonal().maxCoeff(), volume = b.Lx * b.Ly * b.Lz;
    std::printf("P%d, %ld dofs\n", order, n);
    for (int c = 0; c < 3; ++c) {  // translation along c, rotation about axis c
      Eigen::VectorXd t = Eigen::VectorXd::Zero(n), r = Eigen::VectorXd::Zero(n);
      const int p = (c + 1) % 3, q = (c + 2) % 3;
      for (long d = 0; d < n; ++d) {
        t(d) = d % 3 == c;
        if (d % 3 == p) r(d) = -X(d, q);
        if (d % 3 == q) r(d) = X(d, p);
      }
      check("|K translation| / max K_ii", (a.K * t).norm() / scale, 0, 1e-12);
      check("|K rotation| / max K_ii", (a.K * r).norm() / scale, 0, 1e-12);
      check("mass of a translation", t.dot(a.M * t), b.rho * volume, 1e-12);
      check("gravity load along the axis", a.F.dot(t), c == 2 ? -b.rho * b.g * volume : 0, 1e-12);
    }
    // Second moment: integral of x^2 rho (exact: P1 interpolates x exactly).
    Eigen::VectorXd x(n), stretch = Eigen::VectorXd::Zero(n), shear = Eigen::VectorXd::Zero(n);
    for (long d = 0; d < n; ++d) {
      x(d) = d % 3 == 0 ? X(d, 0) : 0;
      if (d % 3 == 0) stretch(d) = X(d, 0);  // u = (x, 0, 0): eps_xx = 1
      if (d % 3 == 0) shear(d) = X(d, 2);    // u = (z, 0, 0): eps_xz = 1/2
    }
    check("integral of rho x^2", x.dot(a.M * x), b.rho * volume * b.Lx * b.Lx / 3, 1e-12);
    const double lam = b.E * b.nu / ((1 + b.nu) * (1 - 2 * b.nu)), mu = b.E / (2 * (1 + b.nu));
    check("energy of the uniform stretch", 0.5 * stretch.dot(a.K * stretch),
          0.5 * (lam + 2 * mu) * volume, 1e-9);
    check("energy of the uniform shear", 0.5 * shear.dot(a.K * shear), 0.5 * mu * volume, 1e-9);
    // Contact regions: the bottom face, both faces, the first third along x.
    const long face = static_cast<long>(b.nodes_x()) * b.nodes_y();
    nbm_bench::ContactRegion region;
    check("bottom-face contact nodes", nbm_bench::contact_on(X, region).gaps.size(), face, 0);
    region.top = true;
    check("bottom + top contact nodes", nbm_bench::contact_on(X, region).gaps.size(), 2 * face, 0);
    region.top = false;
    region.fraction = 1.0 / 3;
    check("contact nodes of a third of the bottom face",
          nbm_bench::contact_on(X, region).gaps.size(), (order + 1.0) * b.nodes_y(), 0);
    // Inclined obstacle: gap g0 + slope (x + tilt y), largest at the far corner.
    region.fraction = 1;
    region.gap = 0.5;
    region.slope = 2;
    const nbm::ContactDescription inclined = nbm_bench::contact_on(X, region);
    check("largest gap of the inclined obstacle",
          *std::max_element(inclined.gaps.begin(), inclined.gaps.end()),
          0.5 + 2 * (b.Lx + region.tilt * b.Ly), 1e-12);
    check("sweep length", nbm_bench::sweep_length(X, region), b.Lx + region.tilt * b.Ly, 1e-12);
  }
  std::printf("block assembly: %d failed\n", failures);
  return failures ? 1 : 0;
}
