// Backbones of nonsmooth modes from grazing (method.md §6, "Backbones from
// grazing"): the linear mode's orbit that just touches the obstacle, in
// closed form, and the family of nonsmooth orbits continued from it
// (autonomous, undamped) with monitors at every orbit.
#pragma once

#include <string>
#include <vector>

#include "periodic/continuation.hpp"
#include "periodic/user_backbone.hpp"

namespace nbm {

/// The grazing orbit of one linear mode. On the region with every contact
/// open (the linear system, contact dofs slaved as for an open contact) the
/// static state u_s solves K_S u_s = f_S and the mode's orbits are
///     u(t) = u_s + s a phi cos(omega t),  v = u',  period 2 pi / omega;
/// the open switching functions (gaps) are h(t) = h_s + s a (H phi) cos(omega t)
/// with h_s = H u_s + d, so the smallest gap over the period is
/// min_k h_s,k - a |(H phi)_k| and it is exactly 0 for
///     a = min_k h_s,k / |(H phi)_k|
/// (zero load: h_s = g and H phi = -(normal displacements of the contact
/// nodes), a = gap / the largest normal displacement). s = sign (H phi)_k*
/// puts t = 0 at the turning point away from the obstacle: the orbit
/// starts in the open region and grazes at T / 2.
struct GrazingOrbit {
  PeriodicOrbit orbit;   ///< analysed (analyse_orbit)
  Vector static_state;   ///< u_s
  Vector mode;           ///< phi, M_S-normalised
  double omega = 0;
  double amplitude = 0;  ///< a
  Index contact = -1;    ///< k*, the contact that grazes
  Index probe = -1;      ///< interior unknown of largest |phi|: phase condition
};

/// Throws InputError if the field has no contact, a gap <= 0, `mode` is out
/// of [0, n) or rigid (omega = 0), the load moves a rigid mode or closes a
/// contact in the static state, or the mode does not move any contact node
/// along its normal (it never grazes).
GrazingOrbit grazing_orbit(const ReducedField& field, Index mode);

struct BackbonePoint {
  PeriodicOrbit orbit;
  double energy = 0;     ///< total energy minus the static state's
  double amplitude = 0;  ///< max_i |u0_i - u_s,i|
  std::string events;    ///< as in BackbonePointReport
};

struct Backbone {
  GrazingOrbit grazing;
  std::vector<BackbonePoint> points;  ///< points[0]: the grazing orbit
  std::string stop_reason;
};

/// The backbone from the grazing orbit of `mode`: pseudo-arclength
/// continuation (the driver of arclength_continuation.hpp on the family of
/// continuation.hpp) whose first secant is the linear family's direction
/// (from the same mode's orbit at half the grazing amplitude, an exact
/// orbit of the affine linear family): beyond grazing the orbits leave the
/// linear family, which penetrates the obstacle. From the second step on, a
/// corrected orbit farther than twice the step is rejected (a jump to
/// another branch) and the step retried shorter. With mass on the
/// contact nodes, if that first step fails, the first orbit past grazing is
/// sought at fixed periods just below the linear one (the vertical start,
/// backbone.cpp; method.md §6). Ends after
/// options.points orbits, past options.max_energy, when the corrector fails
/// at step/64 or at an orbit without contact (no switch, no closed contact:
/// the family went back to the linear system); stop_reason says which. Throws as grazing_orbit, and
/// InputError on bad options.
Backbone backbone(const ReducedField& field, Index mode, const BackboneOptions& options);

}  // namespace nbm
