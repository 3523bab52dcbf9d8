// Small numerical helpers shared by the unit tests: random matrices with a
// prescribed spectrum, a brute-force LCP solver, and error-message checks.
// Everything here is independent of the nbm core (it only uses Eigen), so the
// tests compare the core against separate computations. The helpers are
// compiled once, in test_util.cpp: as inline functions every test file
// instantiated their dense decompositions (long double LU among them) again.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace nbm_test {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

/// Random orthogonal matrix (Q factor of a Gaussian matrix).
Mat random_orthogonal(int n, std::mt19937& rng);

/// SPD matrix with eigenvalues log-spaced in [1, cond] and random eigenvectors,
/// exactly symmetric.
Mat random_spd(int n, double cond, std::mt19937& rng);

Vec random_vector(int n, std::mt19937& rng, double scale = 1.0);

/// The rows of the constraint matrix G of an active set: per node k, column
/// k of B (open) or column n_c + k (closed), B = [B_open B_closed].
Mat constraint_rows(const Mat& B, const std::vector<bool>& closed);

/// x of X x = r + G^T mu, G x = h, G = constraint_rows(B, closed), from the
/// dense KKT system [X -G^T; G 0] [x; mu] = [r; h].
Vec kkt_solution(const Mat& X, const Mat& B, const std::vector<bool>& closed, const Vec& r,
                 const Vec& h);

/// Brute-force LCP: enumerates all 2^n complementary bases (free set F with
/// z_F = -A_FF^{-1} q_F, z elsewhere 0) in extended precision and returns the
/// z of the basis with the smallest sign violation (for a P-matrix exactly one
/// z is feasible; degenerate problems have several bases giving that z).
Vec brute_force_lcp(const Mat& A, const Vec& q);

/// Runs f, expects it to throw E, and checks that the message contains every
/// string of `parts` (the argument name and what went wrong).
template <class E>
void expect_throw_with(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "expected an exception mentioning \"" << (parts.empty() ? "" : parts[0])
                  << "\", nothing was thrown";
  } catch (const E& e) {
    const std::string msg = e.what();
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "message \"" << msg << "\" lacks \"" << p << "\"";
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type, message: " << e.what();
  }
}

}  // namespace nbm_test
