#include "trajectory.hpp"

#include <algorithm>
#include <cstdlib>

namespace nbm_bench {

Trajectory::Trajectory(const char* path) {
  if (path == nullptr) return;
  file_ = std::fopen(path, "rb");
  comparing_ = file_ != nullptr;
  if (!comparing_) file_ = std::fopen(path, "wb");
  if (file_ == nullptr) {
    std::fprintf(stderr, "cannot open %s\n", path);
    std::exit(2);
  }
}

Trajectory::~Trajectory() {
  if (file_ != nullptr) std::fclose(file_);
}

void Trajectory::record(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                        const Eigen::VectorXd& a) {
  if (file_ == nullptr) return;
  ++step_;
  for (const Eigen::VectorXd* x : {&u, &v, &a}) {
    const auto size = static_cast<std::size_t>(x->size());
    if (!comparing_) {
      std::fwrite(x->data(), sizeof(double), size, file_);
      continue;
    }
    recorded_.resize(x->size());
    if (std::fread(recorded_.data(), sizeof(double), size, file_) != size) {
      std::fprintf(stderr, "the trajectory file is shorter than this run\n");
      std::exit(2);
    }
    const double scale = std::max(recorded_.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::Index at = 0;
    const double difference = (*x - recorded_).cwiseAbs().maxCoeff(&at) / scale;
    if (difference > largest_) {
      largest_ = difference;
      where_ = "in " + std::string(x == &u ? "u" : x == &v ? "v" : "a") + " at step " +
               std::to_string(step_) + ", dof " + std::to_string(at);
    }
  }
}

}  // namespace nbm_bench
