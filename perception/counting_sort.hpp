// Internal to perception: a stable counting sort by a small integer key (the Delaunay cells by
// their lowest vertex, the homology's columns by their lowest entry). Not installed.
#pragma once

#include <utility>
#include <vector>

namespace claspplan::perception::detail {

/// `items` stably sorted by key(item), an integer in [0, keys). With `start`, where each key's run
/// begins: keys + 1 entries, the last the number of items.
template <class T, class Key>
std::vector<T> sorted_by_key(const std::vector<T>& items, int keys, const Key& key,
                             std::vector<int>* start = nullptr) {
  std::vector<int> at(keys + 1, 0);
  for (const T& x : items) ++at[key(x) + 1];
  for (int k = 0; k < keys; ++k) at[k + 1] += at[k];
  std::vector<int> fill(at.begin(), at.end() - 1);
  std::vector<T> out(items.size());
  for (const T& x : items) out[fill[key(x)]++] = x;
  if (start) *start = std::move(at);
  return out;
}

}  // namespace claspplan::perception::detail
