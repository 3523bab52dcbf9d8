#include "test_util.hpp"

#include <algorithm>

namespace nbm_test {

Mat random_orthogonal(int n, std::mt19937& rng) {
  std::normal_distribution<double> N(0, 1);
  Mat G(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) G(i, j) = N(rng);
  Eigen::HouseholderQR<Mat> qr(G);
  return qr.householderQ() * Mat::Identity(n, n);
}

Mat random_spd(int n, double cond, std::mt19937& rng) {
  const Mat Q = random_orthogonal(n, rng);
  Vec d(n);
  for (int i = 0; i < n; ++i) d(i) = n == 1 ? 1.0 : std::pow(cond, double(i) / (n - 1));
  Mat A = Q * d.asDiagonal() * Q.transpose();
  return 0.5 * (A + A.transpose());
}

Vec random_vector(int n, std::mt19937& rng, double scale) {
  std::normal_distribution<double> N(0, scale);
  Vec v(n);
  for (int i = 0; i < n; ++i) v(i) = N(rng);
  return v;
}

Mat constraint_rows(const Mat& B, const std::vector<bool>& closed) {
  const Eigen::Index nc = B.cols() / 2;
  Mat G(nc, B.rows());
  for (Eigen::Index k = 0; k < nc; ++k) G.row(k) = B.col(closed[k] ? nc + k : k).transpose();
  return G;
}

Vec kkt_solution(const Mat& X, const Mat& B, const std::vector<bool>& closed,
                        const Vec& r, const Vec& h) {
  const Eigen::Index n = X.rows(), nc = B.cols() / 2;
  const Mat G = constraint_rows(B, closed);
  Mat kkt = Mat::Zero(n + nc, n + nc);
  kkt.topLeftCorner(n, n) = X;
  kkt.topRightCorner(n, nc) = -G.transpose();
  kkt.bottomLeftCorner(nc, n) = G;
  Vec rhs(n + nc);
  rhs << r, h;
  return kkt.fullPivLu().solve(rhs).head(n);
}

Vec brute_force_lcp(const Mat& A, const Vec& q) {
  using LMat = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  using LVec = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const int n = static_cast<int>(q.size());
  const LMat Al = A.cast<long double>();
  const LVec ql = q.cast<long double>();
  long double best_violation = INFINITY;
  LVec best = LVec::Zero(n);
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    std::vector<int> F;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) F.push_back(i);
    const int m = static_cast<int>(F.size());
    LVec z = LVec::Zero(n);
    if (m > 0) {
      LMat AFF(m, m);
      LVec qF(m);
      for (int a = 0; a < m; ++a) {
        qF(a) = ql(F[a]);
        for (int b = 0; b < m; ++b) AFF(a, b) = Al(F[a], F[b]);
      }
      const LVec zF = AFF.partialPivLu().solve(-qF);
      for (int a = 0; a < m; ++a) z(F[a]) = zF(a);
    }
    const LVec w = ql + Al * z;
    // Violation relative to the scales of z and w.
    const long double zs = std::max<long double>(z.cwiseAbs().maxCoeff(), 1e-300L);
    const long double ws = std::max<long double>(
        std::max(ql.cwiseAbs().maxCoeff(), (Al * z).cwiseAbs().maxCoeff()), 1e-300L);
    long double violation = 0;
    for (int i = 0; i < n; ++i) {
      const bool free = mask & (1u << i);
      violation = std::max(violation, free ? -z(i) / zs : -w(i) / ws);
    }
    if (violation < best_violation) {
      best_violation = violation;
      best = z;
    }
  }
  return best.cast<double>();
}

}  // namespace nbm_test
