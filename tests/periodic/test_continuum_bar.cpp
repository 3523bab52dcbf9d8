// The continuum family of the fixed-gap bar (benchmarks.md §C), the
// reference of the bar's periodic tests, rebuilt without its closed form:
// from the reflection rules of the end x = L alone. With L = c = 1, u =
// f(t - x) - f(t + x), phi = f'; the end reflects phi(t - 1) into
// phi(t + 1) = -phi(t - 1) (open) or +phi(t - 1) (closed, phi(t - 1) >= 0).
// At a rational period T = 2 q / p the rotation s -> s + 2 on the circle of
// length T closes on finite orbits, so phi = A sigma with sigma = +-1 on a
// grid of cells of size 1 / (4 p) is found by propagating the rules from the
// cells a closed contact fixes (sigma(t -+ 1) = +1 for t in the contact
// phase), with the contact phase of length 4 - T. The test asserts that the
// rules close without a conflict on every cell, that the end rests at one
// position -A m during the contact phase (m = int_{t-1}^{t+1} sigma) and stays
// below it in the open phase, and that the gap g = -A m is 2 (T - 3) A: the
// energy 2 A^2 = g^2 / (2 (T - 3)^2) of the closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

// Propagates the reflection rules at T = 2 q / p with the contact phase
// [0, 4 - T + extra h); cell i is s in [i h, (i + 1) h), h = 1 / (4 p).
struct Family {
  bool closes = true;      // no cell receives two signs
  bool every_cell = true;  // every cell receives one
  double gap_over_A = 0;   // -m at the first contact instant
  double spread = 0;       // max - min of m over the contact phase
  double above = 0;        // max over the open phase of (m_contact - m): <= 0 means u <= g
};

Family propagate(int p, int q, int extra = 0) {
  const int one = 4 * p, two = 2 * one;  // cells per unit and per 2 units of time
  const int N = 8 * q;                   // cells per period T = 2 q / p
  const int contact = 16 * p - 8 * q + extra;  // cells of the contact phase, 4 - T
  const double h = 1.0 / one;
  auto cell = [N](int i) { return ((i % N) + N) % N; };
  auto closed = [&](int i) { return cell(i) < contact; };
  Family f;
  std::vector<int> sigma(N, 0);
  for (int i = 0; i < N; ++i)
    if (closed(i + one) || closed(i - one)) sigma[i] = 1;  // phi(t -+ 1) >= 0 while closed
  for (bool changed = true; changed;) {
    changed = false;
    for (int i = 0; i < N; ++i) {
      if (sigma[i] == 0) continue;
      const int j = cell(i + two), s = closed(i + one) ? sigma[i] : -sigma[i];
      if (sigma[j] == 0) sigma[j] = s, changed = true;
      else if (sigma[j] != s) f.closes = false;
    }
  }
  for (int v : sigma) f.every_cell = f.every_cell && v != 0;
  auto m = [&](int i) {  // int_{t-1}^{t+1} sigma at t = i h
    int sum = 0;
    for (int k = i - one; k < i + one; ++k) sum += sigma[cell(k)];
    return sum * h;
  };
  const double m_contact = m(0);
  f.gap_over_A = -m_contact;
  for (int i = 0; i < N; ++i) {
    if (closed(i))
      f.spread = std::max(f.spread, std::abs(m(i) - m_contact));
    else
      f.above = std::max(f.above, m_contact - m(i));
  }
  return f;
}

TEST(ContinuumBar, TheReflectionRulesGiveTheClosedFormFamily) {
  // (p, q) coprime with 3 < T = 2 q / p < 4.
  const int pairs[][2] = {{3, 5}, {4, 7}, {5, 8}, {5, 9}, {7, 11}, {7, 12},
                          {7, 13}, {10, 19}, {11, 21}, {13, 20}};
  for (const auto& pq : pairs) {
    const int p = pq[0], q = pq[1];
    const double T = 2.0 * q / p;
    const Family f = propagate(p, q);
    std::printf("continuum bar, T = %.4f L/c: gap / A = %.12f (closed form 2 (T - 3) = %.12f)\n",
                T, f.gap_over_A, 2 * (T - 3));
    EXPECT_TRUE(f.closes) << T;
    EXPECT_TRUE(f.every_cell) << T;
    EXPECT_LE(f.spread, 1e-12) << T;  // the end rests at the wall while closed
    EXPECT_LE(f.above, 1e-12) << T;   // and stays off it while open
    EXPECT_NEAR(f.gap_over_A, 2 * (T - 3), 1e-12) << T;
  }
}

// The rules decide the contact duration: with a contact phase a few cells
// longer or shorter than 4 - T, no constant-amplitude motion satisfies them
// (a cell receives both signs, or the end does not rest at the wall while
// closed, or crosses it while open).
TEST(ContinuumBar, NoOtherContactDurationSatisfiesTheRules) {
  const int pairs[][2] = {{3, 5}, {4, 7}, {5, 9}, {7, 12}};
  for (const auto& pq : pairs)
    for (int extra : {-2, -1, 1, 2}) {
      const Family f = propagate(pq[0], pq[1], extra);
      const bool holds = f.closes && f.every_cell && f.spread <= 1e-12 && f.above <= 1e-12;
      EXPECT_FALSE(holds) << "T = 2 * " << pq[1] << " / " << pq[0] << ", extra " << extra;
    }
}

}  // namespace
