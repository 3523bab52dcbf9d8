// Solves with a mass matrix without factoring it: the steppers' start (the
// initial acceleration) needs M^-1 once, and a factor of M beside the
// stepper's own factor of M + beta dt^2 K doubles the memory of the setup
// (the 3D block of 1e6 dofs: 15 GB each, more than the machine holds).
#pragma once

#include <memory>
#include <string>

#include "base/types.hpp"
#include "linalg/spd_inverse.hpp"

namespace nbm {

/// x solves M x = r for a symmetric positive definite M (a mass matrix,
/// possibly with unit rows), by conjugate gradients preconditioned with M's
/// diagonal: a mass matrix is spectrally equivalent to its diagonal, with
/// bounds set by the element and not by the mesh size, so a few tens of
/// iterations bring the residual to round-off (|r - M x| <= 1e-14 |r|). If
/// they do not (high orders, degenerate elements), M is factored (Cholesky)
/// instead. Throws NumericalError naming `what` if M is found not positive
/// definite: a diagonal entry that is not positive, a direction of negative
/// curvature met by the iterations, or the factorization failing.
Vector solve_mass(const SparseMatrix& M, const Vector& r, const std::string& what);

/// The same for many right-hand sides of one M: the diagonal is checked once,
/// and a solve allocates nothing once the workspaces are sized (unless the
/// iterations fail and M is factored). M must outlive the solver; one solve
/// at a time.
///
/// A caller that solves often and can afford a factor of M beside its own
/// passes `factor_after` > 0: from that many solves on, M is factored once
/// (Cholesky) and every later solve is one substitution pair instead of the
/// few tens of products with M the iterations take.
class MassSolver {
 public:
  /// Throws NumericalError naming `what` if a diagonal entry of M is not
  /// positive.
  MassSolver(const SparseMatrix& M, std::string what, int factor_after = 0);
  ~MassSolver();
  /// x solves M x = r (x may not alias r).
  void solve(const Vector& r, Vector& x) const;
  /// Whether M has been factored.
  bool factored() const { return factor_ != nullptr; }

 private:
  /// M's factor, from now on.
  void factor() const;

  const SparseMatrix& M_;
  std::string what_;
  Vector inverse_diagonal_;
  int factor_after_;
  mutable int solves_ = 0;
  mutable std::unique_ptr<CholeskyInverse> factor_;
  mutable Vector residual_, z_, p_, Mp_;
};

/// The relative residual solve_mass reaches by iterating, or it factors.
constexpr double kMassSolveTolerance = 1e-14;

}  // namespace nbm
