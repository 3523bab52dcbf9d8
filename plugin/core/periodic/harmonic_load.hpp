// The periodic excitation of a forced orbit (method.md §8, §9): a load
//
//     F(t) = F0 + sum_{k=1..H} ( cos_k cos(k omega t) + sin_k sin(k omega t) )
//
// and moving gaps (a periodic obstacle motion)
//
//     g(t) = g0 + sum_{k=1..H} ( gap_cos_k cos(k omega t) + gap_sin_k sin(k omega t) )
//
// whose constant parts F0, g0 are the ReducedField's load and gaps. The load
// harmonics are internal vectors (size N, like F0; on the contact dofs they
// move the offset e(t) of the nodal boundary relation like the gaps do), the
// gap harmonics have one entry per contact (ReducedField::contact() order).
#pragma once

#include <algorithm>
#include <vector>

#include "base/types.hpp"

namespace nbm {

struct HarmonicLoad {
  double omega = 0;              ///< circular frequency of the excitation (> 0 if harmonics)
  std::vector<Vector> cos, sin;  ///< k = 1..H; any list may be shorter (zero harmonics)
  std::vector<Vector> gap_cos, gap_sin;

  int harmonics() const {
    return static_cast<int>(
        std::max({cos.size(), sin.size(), gap_cos.size(), gap_sin.size()}));
  }
};

}  // namespace nbm
