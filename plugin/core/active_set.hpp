// Active sets {contact nodes with gap = 0} and a small cache of the dense
// factorizations that depend on them.
#pragma once

#include <unordered_map>
#include <vector>

namespace nbm {

using ActiveSet = std::vector<bool>;

/// Remembers per-active-set dense factorizations. Active sets recur (a
/// bouncing body alternates between a handful of them), so recomputing is
/// avoided; the bound keeps memory flat on long runs with many sets.
template <class Factor>
class ActiveSetCache {
 public:
  explicit ActiveSetCache(std::size_t capacity = 64) : capacity_(capacity) {}

  template <class Make>
  const Factor& get(const ActiveSet& set, Make make) {
    auto it = map_.find(set);
    if (it != map_.end()) return it->second;
    if (map_.size() >= capacity_) map_.clear();
    return map_.emplace(set, make()).first->second;
  }

 private:
  std::size_t capacity_;
  std::unordered_map<ActiveSet, Factor> map_;
};

}  // namespace nbm
