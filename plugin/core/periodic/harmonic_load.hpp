// The periodic excitation of a forced orbit (method.md §9): a load
//
//     F(t) = F0 + sum_{k=1..H} ( cos_k cos(k omega t) + sin_k sin(k omega t) )
//
// whose constant part F0 is the ReducedField's load. The harmonics are
// internal vectors (size N, like F0) that must vanish on the contact dofs:
// a time-varying load there moves the offset e(t) of the nodal boundary
// relation (method.md §8), which the exact flow does not model yet.
#pragma once

#include <algorithm>
#include <vector>

#include "types.hpp"

namespace nbm {

struct HarmonicLoad {
  double omega = 0;              ///< circular frequency of the excitation (> 0 if harmonics)
  std::vector<Vector> cos, sin;  ///< k = 1..H; either list may be shorter (zero harmonics)

  int harmonics() const { return static_cast<int>(std::max(cos.size(), sin.size())); }
};

}  // namespace nbm
