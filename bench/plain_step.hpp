// The contact-free steps that every NBM step is measured against (the
// "plain" of the ratios in bench/RESULTS.md): average-acceleration Newmark in
// displacement form, one product with M and one solve with the factor of
// M + dt^2/4 K, and central differences with the row-sum lumped mass. Shared
// by bench/bench_step.cpp, bench/contact_front.cpp and bench/scale_probe.cpp
// so that all three divide by the same step.
#pragma once

#include <Eigen/Dense>

#include "linalg/spd_inverse.hpp"
#include "plate.hpp"

namespace nbm_bench {

class PlainNewmark {
 public:
  /// S: the factor of a.M + dt^2/4 a.K; both must outlive this. From rest.
  PlainNewmark(const nbm::CholeskyInverse& S, const Assembled& a, double dt);
  void step();
  const Eigen::VectorXd& u() const { return u_; }

 private:
  const nbm::CholeskyInverse& S_;
  const Assembled& a_;
  double dt_, bdt2_;
  Eigen::VectorXd u_, v_, acc_, r_, u_pred_, acc_new_;
};

class PlainCentralDifference {
 public:
  /// m: the row-sum lumped mass (positive); a must outlive this. From rest.
  PlainCentralDifference(const Assembled& a, Eigen::VectorXd m, double dt);
  void step();
  const Eigen::VectorXd& u() const { return u_; }

 private:
  const Assembled& a_;
  Eigen::VectorXd m_;
  double dt_;
  Eigen::VectorXd u_, v_, acc_, acc_new_;
};

}  // namespace nbm_bench
