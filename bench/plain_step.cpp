#include "plain_step.hpp"

namespace nbm_bench {

PlainNewmark::PlainNewmark(const nbm::CholeskyInverse& S, const Assembled& a, double dt)
    : S_(S), a_(a), dt_(dt), bdt2_(0.25 * dt * dt) {
  const Eigen::Index n = a.K.rows();
  u_ = v_ = acc_ = Eigen::VectorXd::Zero(n);
  r_.resize(n);
  u_pred_.resize(n);
  acc_new_.resize(n);
}

void PlainNewmark::step() {
  // (M + beta dt^2 K) u = M u_pred + beta dt^2 F, no allocation.
  u_pred_ = u_ + dt_ * v_ + bdt2_ * acc_;
  r_.noalias() = a_.M * u_pred_;
  r_ += bdt2_ * a_.F;
  S_.solve_in_place(r_);
  acc_new_ = (r_ - u_pred_) / bdt2_;
  v_ += (0.5 * dt_) * (acc_ + acc_new_);
  acc_.swap(acc_new_);
  u_.swap(r_);
}

PlainCentralDifference::PlainCentralDifference(const Assembled& a, Eigen::VectorXd m, double dt)
    : a_(a), m_(std::move(m)), dt_(dt) {
  const Eigen::Index n = a.K.rows();
  u_ = v_ = Eigen::VectorXd::Zero(n);
  acc_ = a.F.cwiseQuotient(m_);
  acc_new_.resize(n);
}

void PlainCentralDifference::step() {
  u_ += dt_ * v_ + (0.5 * dt_ * dt_) * acc_;
  acc_new_.noalias() = a_.F - a_.K * u_;
  acc_new_.array() /= m_.array();
  v_ += (0.5 * dt_) * (acc_ + acc_new_);
  acc_.swap(acc_new_);
}

}  // namespace nbm_bench
