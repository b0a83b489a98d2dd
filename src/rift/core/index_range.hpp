// A range [first, last) of indices: the particles a rank of a distributed run owns are a few of
// them (pd/window.hpp), one on one rank.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace rift {

struct IndexRange {
  std::size_t first = 0, last = 0;
  std::size_t size() const { return last - first; }
  bool contains(std::size_t i) const { return i >= first && i < last; }
};

/// How many indices the ranges hold.
inline std::size_t count_of(const std::vector<IndexRange>& ranges) {
  std::size_t n = 0;
  for (const IndexRange& r : ranges) n += r.size();
  return n;
}

/// Whether one of the ranges (ascending, apart) holds i.
inline bool any_contains(const std::vector<IndexRange>& ranges, std::size_t i) {
  const auto r = std::upper_bound(ranges.begin(), ranges.end(), i, [](std::size_t x, const IndexRange& a) { return x < a.first; });
  return r != ranges.begin() && (r - 1)->contains(i);
}

}  // namespace rift
