#include "periodic/trig_sum.hpp"

#include <cmath>

namespace nbm {

Vector TrigSum::value(double t) const {
  Vector h = c + t * p + (t * t) * q;
  for (Index k = 0; k < nu.size(); ++k)
    h += std::cos(nu(k) * t) * a.col(k) + std::sin(nu(k) * t) * b.col(k);
  return h;
}

Vector TrigSum::rate(double t) const {
  Vector r = p + (2 * t) * q;
  for (Index k = 0; k < nu.size(); ++k)
    r += nu(k) * (std::cos(nu(k) * t) * b.col(k) - std::sin(nu(k) * t) * a.col(k));
  return r;
}

Vector TrigSum::curvature(double t) const {
  Vector k = 2 * q;
  for (Index j = 0; j < nu.size(); ++j)
    k -= (nu(j) * nu(j)) * (std::cos(nu(j) * t) * a.col(j) + std::sin(nu(j) * t) * b.col(j));
  return k;
}

Vector TrigSum::curvature_bound(double) const {
  Vector L = 2 * q.cwiseAbs();
  for (Index k = 0; k < nu.size(); ++k)
    L += (nu(k) * nu(k)) * (a.col(k).cwiseAbs2() + b.col(k).cwiseAbs2()).cwiseSqrt();
  return L;
}

Vector TrigSum::magnitude(double span) const {
  Vector m = c.cwiseAbs() + span * p.cwiseAbs() + (span * span) * q.cwiseAbs();
  for (Index k = 0; k < nu.size(); ++k) m += a.col(k).cwiseAbs() + b.col(k).cwiseAbs();
  return m;
}

}  // namespace nbm
