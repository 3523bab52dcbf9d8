// One periodic problem (method.md §6, §9): the flow whose periodic orbits
// are sought and what fixes their period. Shooting (shooting.hpp) and
// harmonic balance (harmonic_balance.hpp) are its two methods; both take
// either kind.
//
// Autonomous (undamped, no excitation): the period is an unknown, and two
// conditions close the system, a phase condition (the time origin) and an
// amplitude condition (which orbit of the family); ShootingOptions and
// HarmonicBalanceOptions say which.
//
// Forced: the excitation of the flow (exact_flow.hpp, FlowForcing) fixes the
// period, T = 2 pi m / omega (m = 1: harmonic response; m > 1: a
// subharmonic), and the time origin; there are no conditions.
#pragma once

#include <memory>
#include <string>

#include "periodic/exact_flow.hpp"

namespace nbm {

/// The period of the forced orbit of subharmonic order m: 2 pi m / omega.
/// Throws InputError if the flow has no harmonic load or m < 1.
double forced_period(const ExactFlow& flow, int subharmonic);

class PeriodicProblem {
 public:
  /// The autonomous orbits of a field: its flow without excitation.
  /// Implicit, so that a field is read as its autonomous problem.
  PeriodicProblem(const ReducedField& field);  // NOLINT(google-explicit-constructor)
  /// The forced orbits of subharmonic order m of an excited flow (kept by
  /// reference). Throws InputError if the flow has no harmonic load or m < 1.
  PeriodicProblem(const ExactFlow& flow, int subharmonic);
  PeriodicProblem(const PeriodicProblem&) = delete;
  PeriodicProblem& operator=(const PeriodicProblem&) = delete;

  const ExactFlow& flow() const { return *flow_; }
  const ReducedField& field() const { return flow_->field(); }
  bool forced() const { return subharmonic_ > 0; }
  /// m of a forced problem, 0 for an autonomous one.
  int subharmonic() const { return subharmonic_; }
  /// The fixed period of a forced problem (2 pi m / omega); NaN if autonomous.
  double period() const { return period_; }
  /// Checks a solver's guess (the solver named in the message): u0, v0 of
  /// the field's size and finite; the period T finite and > 0 for an
  /// autonomous problem, the fixed period (to 1e-12 relative) for a forced
  /// one. Throws InputError.
  void check_guess(const Vector& u0, const Vector& v0, double T, const std::string& solver) const;

 private:
  std::unique_ptr<const ExactFlow> own_;  ///< the autonomous flow
  const ExactFlow* flow_;
  int subharmonic_ = 0;
  double period_;
};

}  // namespace nbm
