// The first occurrence of each distinct item, found with an open-addressing hash table in one
// pass instead of a sort: O(n) and in input order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace claspplan::perception {

/// The indices i in [0, n), ascending, of the items equal to no earlier one. `hash(i)` is any
/// 64-bit hash of item i (its bits are mixed here); `equal(i, j)` compares two items.
template <class Hash, class Equal>
std::vector<int> first_occurrences(std::size_t n, Hash&& hash, Equal&& equal) {
  std::size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  std::vector<int> slot(capacity, -1);
  std::vector<int> firsts;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t h = static_cast<std::uint64_t>(hash(i)) * 0x9e3779b97f4a7c15ULL;
    h ^= h >> 29;
    for (std::size_t s = h & (capacity - 1);; s = (s + 1) & (capacity - 1)) {
      if (slot[s] < 0) {
        slot[s] = static_cast<int>(i);
        firsts.push_back(static_cast<int>(i));
        break;
      }
      if (equal(static_cast<std::size_t>(slot[s]), i)) break;
    }
  }
  return firsts;
}

}  // namespace claspplan::perception
