// The exact flow of the reduced NBM equations (reduced_field.hpp): modal
// solution on each region, switching times by root finding on the switching
// functions (trig_sum.hpp), and the state-transition (monodromy) matrix with
// saltation terms where the acceleration jumps (mass on the contact dofs).
#pragma once

#include <vector>

#include "reduced_field.hpp"
#include "trig_sum.hpp"

namespace nbm {

/// The flow on one region from (u0, v0) at local time 0. In the modal
/// coordinates q = Phi^T M_S u of the region every mode obeys
/// q'' + w^2 q = p, solved in closed form.
class RegionFlow {
 public:
  RegionFlow(const Region& region, const Vector& u0, const Vector& v0);
  void state(double t, Vector& u, Vector& v) const;
  /// The switching functions h(t) = H u(t) + d of the region.
  const TrigSum& switching() const { return h_; }
  /// d(u, v)(t) / d(u0, v0): 2n x 2n.
  Matrix transition(double t) const;

 private:
  const Region& r_;
  Vector q0_, w0_, p_;
  TrigSum h_;
};

struct SwitchEvent {
  double t;          ///< time of the switch
  Index contact;     ///< the contact whose state changed (the first, if several)
  ActiveSet after;   ///< the active set from then on
};

struct FlowResult {
  Vector u, v;                       ///< the state at the end
  Vector a;                          ///< u'' at the end
  ActiveSet active;                  ///< the active set at the end
  Matrix monodromy;                  ///< d(u, v)(T)/d(u, v)(0), if requested
  std::vector<SwitchEvent> switches;
  /// (u, v) at the requested sample times, columns of 2n-vectors.
  Matrix samples;
};

class ExactFlow {
 public:
  explicit ExactFlow(const ReducedField& field) : field_(field) {}
  /// Flows (u0, v0) over [0, T]. With `sensitivity`, also the monodromy
  /// matrix. `sample_times` (sorted, in [0, T]) asks for the state there.
  /// Throws NumericalError on more than 100000 switches (Zeno behaviour).
  FlowResult integrate(const Vector& u0, const Vector& v0, double T, bool sensitivity,
                       const std::vector<double>& sample_times = {}) const;
  const ReducedField& field() const { return field_; }

 private:
  const ReducedField& field_;
};

}  // namespace nbm
