// Periodic orbits on the user's dofs: the front end of the periodic-orbit
// solvers for the FreeFEM binding. Like api/solver.hpp, free of Eigen and
// FreeFEM types.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "periodic/periodic_defaults.hpp"

namespace nbm {

class ContactProblem;
/// The reduced equations an orbit lives on (full or on a reduced basis).
struct OrbitModel;

struct OrbitOptions {
  std::string method = "shooting";  ///< "shooting" or "harmonic-balance"
  /// User dof whose amplitude over the period is reported (OrbitReport::
  /// amplitude), as in every periodic call: any dof that is not fixed,
  /// contact dofs included. -1: the dof of largest amplitude along the orbit.
  long probe = -1;
  /// User dof of the phase and displacement conditions: an interior dof
  /// (not fixed, not the normal component of a contact node). -1: the probe
  /// if it is interior, else the interior dof of largest |u| in the guess.
  /// Not with a reduced basis (modes > 0), whose conditions use the reduced
  /// coordinate of largest amplitude.
  long phase = -1;
  /// Which orbit of the family: "displacement" (u[phase](0) = amplitude),
  /// "energy" (total energy = amplitude) or "period" (period = amplitude).
  std::string condition = "displacement";
  double amplitude = std::numeric_limits<double>::quiet_NaN();  ///< NaN: the guess's
  bool half_period = false;  ///< shooting: orbits through a state at rest
  int harmonics = 20;        ///< harmonic balance
  bool cosine_only = false;  ///< harmonic balance: orbits even in time
  std::string integration = "exact";  ///< harmonic balance: "exact" or "aft"
  bool adaptive = false;              ///< harmonic balance: double H until truncation <= tol
  double truncation_tolerance = 1e-6;
  int max_iterations = periodic_max_iterations;
  /// Reduced basis (reduced_basis.hpp): this many fixed-interface modes plus
  /// the static contact shapes; 0: the full interior (at most 3000 dofs).
  int modes = 0;
};

struct OrbitReport {
  double period = 0;
  std::vector<double> u0, v0;  ///< user vectors at t = 0
  std::vector<double> energies;  ///< kinetic, elastic, load, total at t = 0
  double energy_change = 0;      ///< over one period of the exact flow
  double contact_time = 0;
  long switches = 0;             ///< contact switches per period
  double periodicity_residual = 0, complementarity_residual = 0, trivial_residual = 0;
  std::vector<double> multipliers_re, multipliers_im;  ///< by decreasing modulus
  bool stable = false;
  int iterations = 0;
  // Harmonic balance only:
  int harmonics = 0;
  double balance_residual = 0, truncation = 0;
  /// User dof i, column k of (c0, a1, b1, a2, b2, ...): coefficients[i * (2H+1) + k].
  std::vector<double> coefficients;
  /// With a reduced basis: the largest relative residual of the full
  /// model's reduced equations along the orbit (the reduction error), and
  /// the retained cutoff frequency times T / (2 pi).
  double reduction_residual = 0, cutoff_ratio = 0;
  long probe = -1;      ///< user dof of the amplitude below
  /// Extremes of u[probe] over one period (the exact flow sampled 512 times
  /// and at every switch), and amplitude = (max - min) / 2.
  double probe_min = 0, probe_max = 0, amplitude = 0;
  double energy_max = 0;  ///< largest total energy at those samples
  // Forced orbits only (user_forced_orbit.hpp):
  double omega = 0;     ///< excitation frequency; 0 for an autonomous orbit
  int subharmonic = 0;  ///< m: period = 2 pi m / omega
  std::string summary;
  std::shared_ptr<const OrbitModel> model;  ///< for orbit_states
};

/// The orbits of a backbone or of a response curve by index (0: the first
/// point), each reported as periodic_orbit and forced_orbit report theirs:
/// state (orbit_states), period, multipliers, stability, probe amplitude.
/// Reports are made on demand: each one samples its orbit over a period.
class OrbitSequence {
 public:
  using Reporter = std::function<OrbitReport(std::size_t)>;
  OrbitSequence(std::size_t size, Reporter reporter)
      : size_(size), reporter_(std::move(reporter)) {}
  std::size_t size() const { return size_; }
  /// The report of orbit k; InputError naming "point" if k >= size().
  OrbitReport report(std::size_t k) const;

 private:
  std::size_t size_;
  Reporter reporter_;
};

/// Computes a periodic orbit of the reduced NBM equations of `problem`
/// under the constant load F (user vector) from the guess (u, v, T) (user
/// vectors). Throws InputError naming the argument, NumericalError if the
/// solver does not converge.
OrbitReport periodic_orbit(const ContactProblem& problem, const std::vector<double>& F,
                           const std::vector<double>& u, const std::vector<double>& v, double T,
                           const OrbitOptions& options);

/// The next orbit of the family through `previous` and `last`, two orbits
/// computed by shooting (periodic_orbit or continue_orbit) on the same
/// problem, load and reduced basis: pseudo-arclength continuation
/// (continuation.hpp), `step` further along the family in unknowns scaled by
/// the last orbit's amplitude, velocity scale and period; if the corrector
/// fails, step/4, step/16 and step/64. Throws InputError on orbits that do
/// not belong together, NumericalError if no step converges.
OrbitReport continue_orbit(const OrbitReport& previous, const OrbitReport& last, double step);

/// The user displacement (and velocity) along the orbit at the given times
/// (exact flow from the orbit's initial state), one vector per time.
void orbit_states(const OrbitReport& orbit, const std::vector<double>& times,
                  std::vector<std::vector<double>>& u, std::vector<std::vector<double>>& v);

}  // namespace nbm
