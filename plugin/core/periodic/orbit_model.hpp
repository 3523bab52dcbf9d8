// The pieces the user-level orbit front ends share (user_orbit.cpp,
// user_forced_orbit.cpp): the field an orbit lives on with the maps between
// its unknowns and the user's vectors, the checks of user vectors and dofs,
// and the report of a computed orbit. Internal to the core (Eigen types);
// the front ends' public headers stay free of them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/contact_problem.hpp"
#include "periodic/exact_flow.hpp"
#include "periodic/harmonic_balance.hpp"
#include "periodic/periodic_orbit.hpp"
#include "periodic/reduced_basis.hpp"
#include "periodic/reduced_field.hpp"
#include "periodic/shooting.hpp"
#include "periodic/user_orbit.hpp"

namespace nbm {

// The field an orbit lives on and the maps between its unknowns and the
// user's vectors: the interior unknowns u_O, or the coordinates q of a
// reduced basis (u_O = V q).
struct OrbitModel {
  const ContactProblem& problem;
  Vector F;  ///< the (constant) load, internal coordinates
  std::unique_ptr<ReducedField> full;
  /// Shared by the models of a response curve's points.
  std::shared_ptr<const ReducedBasis> basis;
  int modes = 0;  ///< of the reduced basis; 0: none
  std::vector<Index> interior;  ///< internal indices of the interior dofs
  /// How the orbit was computed (continuation keeps it): shooting or not,
  /// the field unknown of the phase condition, half-period shooting.
  bool shooting = true;
  ShootingOptions conditions;
  /// A forced orbit's flow (damping and harmonic load, method.md §9) on
  /// field(); null for an autonomous orbit. It follows the excitation below
  /// in field()'s coordinates (forced_flow).
  std::unique_ptr<ExactFlow> forced;
  /// A forced orbit's damping and harmonic excitation on the full model
  /// (internal coordinates): what the reduction residual is measured with.
  Damping damping;
  HarmonicLoad excitation;

  explicit OrbitModel(const ContactProblem& p);
  const ReducedField& field() const { return basis ? basis->field() : *full; }
  /// The flow of a damping and an excitation of the full model (internal
  /// coordinates) on field(): reduced to its coordinates with a basis.
  ExactFlow forced_flow(const Damping& damping, const HarmonicLoad& excitation) const;
  /// Makes the forced flow of that damping and excitation the model's.
  void force(const Damping& damping, const HarmonicLoad& excitation);
  /// The flow the orbit follows: the forced one, or the field's own.
  ExactFlow flow() const { return forced ? *forced : ExactFlow(field()); }
  /// Field unknowns of a user displacement (or velocity).
  Vector unknowns(const Vector& user) const;
  /// Internal vector of interior values (contact dofs zero).
  Vector internal(const Vector& interior_values) const;
  /// User vector of field unknowns: displacement (contact dofs from the
  /// nodal boundary relation) or, with `v` given, the velocity; at time t
  /// along `flow` (default: the forced flow, if any), whose contacts may
  /// move (method.md §8).
  Vector user(const Vector& u, const Vector* v = nullptr, double t = 0,
              const ExactFlow* flow = nullptr) const;
};

/// A user vector of size n, checked: InputError naming it on a wrong size
/// or non-finite entries.
Vector user_vector(const std::vector<double>& x, Index n, const std::string& name);
std::vector<double> to_std(const Vector& x);
/// Position in u_O of a user dof, or -1 if it is not one of the field's
/// interior unknowns (out of range, fixed, a contact node's normal component).
Index find_interior(const ContactProblem& p, const ReducedField& field, long dof);
/// Position in u_O of a user dof; InputError naming `name` if it is out of
/// range, fixed or the normal component of a contact node.
Index interior_position(const ContactProblem& p, const ReducedField& field, long dof,
                        const std::string& name);

/// An orbit of `model` sampled over one period along `flow` (the model's
/// own, or a forced one), 512 times uniformly and at every switch (where a
/// contact closes or opens the motion has its kinks): the extremes of every
/// user dof and the largest total energy. The amplitude of a user dof i is
/// (hi(i) - lo(i)) / 2, for forced orbits and backbones alike.
struct OrbitSamples {
  Vector lo, hi;
  double energy_max = 0;
};
OrbitSamples sample_orbit(const OrbitModel& model, const ExactFlow& flow,
                          const PeriodicOrbit& orbit);
/// Checks the user dof of a reported amplitude: InputError naming "probe"
/// if it is out of range or fixed (-1, "choose the largest", passes).
void check_amplitude_probe(const ContactProblem& problem, long probe);
/// The probe asked for, or with -1 the (not fixed) dof of largest amplitude
/// in `s`.
long amplitude_probe(const ContactProblem& problem, const OrbitSamples& s, long probe);
/// The harmonic-balance fields of a report from a series on `model`:
/// harmonics, Galerkin residual, truncation estimate, and the coefficients
/// in user coordinates (the slaved contact normal components left at zero).
void report_series(const OrbitModel& model, const HarmonicBalanceResult& r, OrbitReport& report);

/// The report of an orbit found on `model`; `method` opens its summary. The
/// orbit is sampled along the model's flow (its forced one, if any) for the
/// amplitude of the user dof `probe` (-1: the dof of largest amplitude).
OrbitReport describe(std::shared_ptr<const OrbitModel> model, const PeriodicOrbit& orbit,
                     OrbitReport report, const std::string& method, long probe);

}  // namespace nbm
