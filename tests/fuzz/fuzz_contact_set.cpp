// libFuzzer target: validation of the contact set (nbm::ContactSet constructor)
// on random dof lists, normals, gaps and fixed dofs, with NaN, infinities,
// out-of-range and duplicated indices and extreme scales.
//
// Properties: the constructor either throws nbm::InputError (nothing else) or
// returns a set that satisfies what it promises: dofs in range, distinct and
// not fixed; unit normals (to 1e-10) and finite gaps; rotation() orthogonal
// with the normal (to 1e-9) as the first column of each node block, the
// identity elsewhere; normal_displacement(u) = n . u per node.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "contact/contact_set.hpp"
#include "fuzz_common.hpp"

using nbm_fuzz::fail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider fdp(data, size);
  const long n_dofs = fdp.ConsumeIntegralInRange<long>(0, 40);
  const int n_nodes = fdp.ConsumeIntegralInRange<int>(0, 10);
  // Mostly a consistent dim; sometimes a dof count that is not a multiple.
  const int dim = fdp.ConsumeIntegralInRange<int>(1, 4);
  const int extra_dofs =
      fdp.ConsumeIntegralInRange<int>(0, 7) == 0 ? fdp.ConsumeIntegralInRange<int>(-2, 2) : 0;
  const int n_entries = std::max(0, n_nodes * dim + extra_dofs);

  // Dofs: mostly a random injection into [0, n_dofs), sometimes anything.
  std::vector<nbm::Index> dofs;
  std::vector<long> pool(static_cast<std::size_t>(n_dofs));
  for (long d = 0; d < n_dofs; ++d) pool[d] = d;
  for (int e = 0; e < n_entries; ++e) {
    const int how = fdp.ConsumeIntegralInRange<int>(0, 15);
    if (how == 0)
      dofs.push_back(fdp.ConsumeIntegralInRange<long>(-3, n_dofs + 3));
    else if (how == 1 && !dofs.empty())
      dofs.push_back(dofs[fdp.ConsumeIntegralInRange<std::size_t>(0, dofs.size() - 1)]);
    else if (!pool.empty()) {
      const std::size_t k = fdp.ConsumeIntegralInRange<std::size_t>(0, pool.size() - 1);
      dofs.push_back(pool[k]);
      pool.erase(pool.begin() + static_cast<long>(k));
    } else {
      dofs.push_back(fdp.ConsumeIntegralInRange<long>(-1, n_dofs));
    }
  }

  // Normals: unit vectors of random direction and scale of components (from
  // 1e-200 to 1e200 before normalisation), sometimes off the unit sphere by
  // about the tolerance, sometimes special values.
  const int normal_entries = fdp.ConsumeIntegralInRange<int>(0, 9) == 0
                                 ? fdp.ConsumeIntegralInRange<int>(0, n_entries + 2)
                                 : n_entries;
  std::vector<double> normals(static_cast<std::size_t>(normal_entries));
  const int node_dim = std::max(1, dim);
  for (int start = 0; start < normal_entries; start += node_dim) {
    const int len = std::min(node_dim, normal_entries - start);
    const double scale = nbm_fuzz::pow10_in(fdp, -200, 200);
    double nn = 0;
    for (int j = 0; j < len; ++j) {
      double c = nbm_fuzz::uniform(fdp, -1, 1) * scale;
      if (fdp.ConsumeIntegralInRange<int>(0, 5) == 0) c = 0;  // axis-aligned normals
      normals[start + j] = c;
      nn += c * c;
    }
    const double norm = std::sqrt(nn);
    if (norm > 0 && std::isfinite(norm) && fdp.ConsumeBool()) {
      const double off = fdp.ConsumeBool() ? nbm_fuzz::uniform(fdp, -3e-10, 3e-10) : 0.0;
      for (int j = 0; j < len; ++j) normals[start + j] = normals[start + j] / norm * (1 + off);
    }
    if (fdp.ConsumeIntegralInRange<int>(0, 15) == 0)
      normals[start + fdp.ConsumeIntegralInRange<int>(0, len - 1)] = nbm_fuzz::special(fdp);
  }

  const int gap_count = fdp.ConsumeIntegralInRange<int>(0, 15) == 0
                            ? fdp.ConsumeIntegralInRange<int>(0, n_nodes + 1)
                            : n_nodes;
  nbm::Vector gaps(gap_count);
  const double gap_scale = nbm_fuzz::pow10_in(fdp, -300, 300);
  for (int k = 0; k < gap_count; ++k)
    gaps(k) = fdp.ConsumeIntegralInRange<int>(0, 15) == 0
                  ? nbm_fuzz::special(fdp)
                  : nbm_fuzz::uniform(fdp, -1, 1) * gap_scale;

  std::vector<nbm::Index> fixed;
  const int n_fixed = fdp.ConsumeIntegralInRange<int>(0, 4);
  for (int f = 0; f < n_fixed; ++f)
    fixed.push_back(fdp.ConsumeIntegralInRange<long>(-2, n_dofs + 1));

  nbm::Vector probe = nbm::Vector::Zero(n_dofs);
  for (long d = 0; d < n_dofs; ++d) probe(d) = nbm_fuzz::uniform(fdp, -1, 1);

  nbm_fuzz::accepted([&] {
    const nbm::ContactSet set(n_dofs, dofs, normals, gaps, fixed);

    // Sizes and indices.
    if (set.size() != gap_count || set.size() < 1) fail("size %ld", (long)set.size());
    const int d = set.dim();
    if (d < 1 || d > 3 || static_cast<long>(dofs.size()) != set.size() * d)
      fail("dim %d for %zu dofs and %ld nodes", d, dofs.size(), (long)set.size());
    std::set<nbm::Index> seen;
    const std::set<nbm::Index> fixed_set(fixed.begin(), fixed.end());
    for (nbm::Index k = 0; k < set.size(); ++k) {
      double nn = 0;
      for (int j = 0; j < d; ++j) {
        const nbm::Index dof = set.dof(k, j);
        if (dof < 0 || dof >= n_dofs) fail("dof %ld out of range", (long)dof);
        if (!seen.insert(dof).second) fail("dof %ld twice", (long)dof);
        if (fixed_set.count(dof)) fail("dof %ld is fixed", (long)dof);
        nn += set.normal(k, j) * set.normal(k, j);
      }
      if (!(std::abs(std::sqrt(nn) - 1) <= 1e-10))
        fail("|n| = %.17g at node %ld", std::sqrt(nn), (long)k);
      if (!std::isfinite(set.gaps()(k))) fail("non-finite gap accepted");
    }
    for (nbm::Index f : fixed)
      if (f < 0 || f >= n_dofs) fail("fixed dof %ld out of range accepted", (long)f);

    // Rotation: orthogonal, first column of each node block = n / |n|.
    const nbm::Matrix T(set.rotation(n_dofs));
    if (T.rows() != n_dofs || T.cols() != n_dofs) fail("rotation size");
    const double orth =
        (T.transpose() * T - nbm::Matrix::Identity(n_dofs, n_dofs)).cwiseAbs().maxCoeff();
    if (!(orth <= 1e-13)) fail("rotation not orthogonal: |T'T - I| = %g", orth);
    for (nbm::Index k = 0; k < set.size(); ++k) {
      double nn = 0;
      for (int j = 0; j < d; ++j) nn += set.normal(k, j) * set.normal(k, j);
      for (int j = 0; j < d; ++j) {
        const double expected = set.normal(k, j) / std::sqrt(nn);
        // |n| = 1 only to 1e-10: the column (a unit vector) is n/|n| to 1e-9.
        if (!(std::abs(T(set.dof(k, j), set.dof(k, 0)) - expected) <= 1e-9))
          fail("rotation column of node %ld: %g, expected %g", (long)k,
               T(set.dof(k, j), set.dof(k, 0)), expected);
      }
    }
    for (long r = 0; r < n_dofs; ++r)
      if (!seen.count(r))
        for (long c = 0; c < n_dofs; ++c)
          if (T(r, c) != (r == c ? 1.0 : 0.0) || T(c, r) != (r == c ? 1.0 : 0.0))
            fail("rotation touches the non-contact dof %ld", r);

    // Normal displacement.
    const nbm::Vector un = set.normal_displacement(probe);
    if (un.size() != set.size()) fail("normal_displacement size");
    for (nbm::Index k = 0; k < set.size(); ++k) {
      double expected = 0;
      for (int j = 0; j < d; ++j) expected += set.normal(k, j) * probe(set.dof(k, j));
      if (!(std::abs(un(k) - expected) <= 1e-14 * d))
        fail("normal displacement of node %ld", (long)k);
    }
  });
  return 0;
}
