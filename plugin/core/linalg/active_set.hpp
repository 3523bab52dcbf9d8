// Active sets {contact nodes with gap = 0} and a cache, bounded in bytes, of
// the dense factorizations that depend on them.
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "base/types.hpp"
#include "linalg/dense_cholesky.hpp"

namespace nbm {

using ActiveSet = std::vector<bool>;

/// Bytes held by a dense Cholesky factorization (its factor, the object).
inline std::size_t factor_bytes(const DenseCholesky& f) { return sizeof(f) + f.bytes(); }
/// Bytes held by a shared factor that has a bytes() method.
template <class Factor>
std::size_t factor_bytes(const std::shared_ptr<const Factor>& f) {
  return sizeof(f) + f->bytes();
}

/// Default byte budget of one cache: 64 MiB, two dense factors of 2000
/// contact nodes (32 MB each). A stepper has up to two such caches (Schur
/// complements; the principal blocks of K_CC, which the LCP and the open
/// blocks of the nodal boundary relation share).
constexpr std::size_t kActiveSetCacheBytes = std::size_t(64) << 20;
/// Default bound on the entries of one cache: with few contact nodes the
/// budget would hold thousands of small factors, and a long run meeting ever
/// new sets would grow its memory for that long (tests/scripts/long-run.edp
/// requires it flat); a bouncing body recurs through far fewer sets.
constexpr std::size_t kActiveSetCacheEntries = 64;

/// Remembers per-active-set dense factorizations. Active sets recur (a
/// bouncing body alternates between a handful of them), so recomputing is
/// avoided. The memory is bounded in bytes (a factor of n_c contact nodes
/// holds 8 n_c^2 bytes) and in entries: once the factors and their keys
/// exceed the budget, or the entries the bound, the least recently used are
/// dropped. The newest entry is always kept, even alone above the budget (its
/// caller is using it), so a reference returned by get() is valid until the
/// next get().
/// A lookup of a known set allocates nothing.
template <class Factor>
class ActiveSetCache {
 public:
  explicit ActiveSetCache(std::size_t budget_bytes = kActiveSetCacheBytes,
                          std::size_t max_entries = kActiveSetCacheEntries)
      : budget_(budget_bytes), max_entries_(max_entries) {}

  /// The factor of a known set (now the most recently used), or null.
  const Factor* find(const ActiveSet& set) {
    auto it = map_.find(set);
    if (it == map_.end()) return nullptr;
    entries_.splice(entries_.begin(), entries_, it->second);
    return &it->second->factor;
  }

  /// Stores the factor of a new set, dropping the least recently used ones
  /// while the budget or the bound on entries would be exceeded.
  const Factor& insert(const ActiveSet& set, Factor factor) {
    Entry entry{set, std::move(factor), 0};
    entry.bytes = entry_bytes(entry);
    while (!entries_.empty() &&
           (bytes_ + entry.bytes > budget_ || entries_.size() >= max_entries_)) {
      bytes_ -= entries_.back().bytes;
      map_.erase(entries_.back().set);
      entries_.pop_back();
    }
    bytes_ += entry.bytes;
    entries_.push_front(std::move(entry));
    map_.emplace(entries_.front().set, entries_.begin());
    return entries_.front().factor;
  }

  /// The factor of `set`, made by make() if the set is new.
  template <class Make>
  const Factor& get(const ActiveSet& set, Make make) {
    if (const Factor* known = find(set)) return *known;
    return insert(set, make());
  }

  /// Drops the entries whose factor satisfies `drop`.
  template <class Drop>
  void remove_if(Drop drop) {
    for (auto it = entries_.begin(); it != entries_.end();)
      if (drop(it->factor)) {
        bytes_ -= it->bytes;
        map_.erase(it->set);
        it = entries_.erase(it);
      } else {
        ++it;
      }
  }

  std::size_t size() const { return entries_.size(); }
  /// Bytes held by the entries (factors, keys, bookkeeping).
  std::size_t bytes() const { return bytes_; }
  std::size_t budget() const { return budget_; }

 private:
  struct Entry {
    ActiveSet set;
    Factor factor;
    std::size_t bytes;
  };
  // The factor, the key stored twice (list and map) and the nodes around them.
  static std::size_t entry_bytes(const Entry& e) {
    return factor_bytes(e.factor) + 2 * (e.set.size() / 8 + sizeof(ActiveSet)) + 4 * sizeof(void*) +
           sizeof(Entry);
  }

  std::size_t budget_, max_entries_;
  std::size_t bytes_ = 0;
  std::list<Entry> entries_;  // most recently used first
  std::unordered_map<ActiveSet, typename std::list<Entry>::iterator> map_;
};

}  // namespace nbm
