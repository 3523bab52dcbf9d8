// Trajectories of a stepper compared between versions of the core
// (bench/contact_front.cpp, bench/scale_probe.cpp): a first run writes u, v,
// a after every step to a file, a run that finds the file reads them back
// and keeps the largest difference, step by step relative to the recorded
// vector's largest entry.
#pragma once

#include <cstdio>
#include <string>

#include <Eigen/Dense>

namespace nbm_bench {

class Trajectory {
 public:
  /// No file (null path): records nothing. Exits with a message if the file
  /// can be neither read nor written.
  explicit Trajectory(const char* path);
  ~Trajectory();
  Trajectory(const Trajectory&) = delete;
  Trajectory& operator=(const Trajectory&) = delete;

  /// The state after one more step: written, or compared with the file's.
  void record(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& a);
  bool comparing() const { return comparing_; }
  double largest_difference() const { return largest_; }
  /// Where the largest difference is: vector, step and dof.
  const std::string& where() const { return where_; }

 private:
  std::FILE* file_ = nullptr;
  bool comparing_ = false;
  Eigen::VectorXd recorded_;
  double largest_ = 0;
  int step_ = 0;
  std::string where_;
};

}  // namespace nbm_bench
