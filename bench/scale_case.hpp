// The bodies and contact fronts of issue 14's benchmarks (bench/bench_step.cpp,
// BM_Scale*) and of bench/scale_probe.cpp: the plate (W/H = 2), the strip
// (W/H = 80) and the 3D block, with a contact front sweeping the contact set.
#pragma once

#include <Eigen/Dense>

#include "base/types.hpp"
#include "block.hpp"
#include "contact_region.hpp"
#include "plate.hpp"

namespace nbm_bench {

enum Body { kPlate = 0, kStrip = 1, kBlock = 2 };

/// An assembled body: its matrices and the coordinates of its dofs.
struct Case {
  Assembled a;
  Eigen::MatrixXd X;  ///< n_dofs x dim
};

/// Body `body` (Body), Lagrange order 1 or 2, about `dofs` dofs.
Case assemble_body(int body, int order, double dofs);

/// contact_pct % of the bottom face (along x), or (200) the bottom and top faces.
ContactRegion scale_region(int contact_pct);

/// Sweeping runs: the body falls at kSweepSpeed onto an obstacle inclined so
/// that the contact front crosses the contact set in kSweepSteps steps (the
/// first column touches during the first step).
constexpr int kSweepSteps = 20;
constexpr double kSweepSpeed = 0.1;

/// The region with gaps growing along the contact set so that the body,
/// falling at kSweepSpeed, reaches its end after kSweepSteps steps of `dt`.
ContactRegion sweeping(ContactRegion r, const Eigen::MatrixXd& X, double dt);

/// The initial velocity of a sweep: kSweepSpeed downwards (user dofs).
Eigen::VectorXd falling(const Eigen::MatrixXd& X);

/// Half the critical step of central differences with the lumped mass m.
double explicit_dt(const nbm::SparseMatrix& K, const Eigen::VectorXd& m);

}  // namespace nbm_bench
