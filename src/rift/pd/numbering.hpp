// The whole run's numbers of a rank's particles in a distributed run (pd/window.hpp). A rank's
// window holds ranges of the whole run's numbering, in its order, and numbers its particles 0, 1,
// ... in that same order: rows sorted by neighbour here are sorted as the whole run's, so every sum
// over a row is made in the one-rank order. A window of slabs is one range; a box of a processor
// grid is one range per lattice line of it.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "rift/core/index_range.hpp"

namespace rift::pd {

class Numbering {
 public:
  struct Range {
    std::size_t whole = 0;  // the whole run's number of its first particle
    std::size_t here = 0;   // its first particle's number here
    std::size_t count = 0;
  };
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  Numbering() = default;
  /// The ranges of the whole numbering a window holds, ascending and apart: numbered here one after
  /// the other. Neighbouring ranges are joined.
  explicit Numbering(const std::vector<IndexRange>& whole_ranges) : one_rank_(false) {
    std::size_t here = 0;
    for (const auto& [first, last] : whole_ranges) {
      if (last <= first) continue;
      if (!ranges_.empty() && ranges_.back().whole + ranges_.back().count == first) ranges_.back().count += last - first;
      else ranges_.push_back({first, here, last - first});
      here += last - first;
    }
  }
  /// One range: the particles [first, first + count) of the whole run.
  static Numbering range(std::size_t first, std::size_t count) { return Numbering({{first, first + count}}); }

  /// The whole run's number of particle i here (one rank's: i).
  std::size_t whole(std::size_t i) const {
    if (one_rank_) return i;
    if (ranges_.size() == 1) return ranges_[0].whole + i;
    const auto r = std::upper_bound(ranges_.begin(), ranges_.end(), i, [](std::size_t x, const Range& a) { return x < a.here; }) - 1;
    return r->whole + (i - r->here);
  }
  /// The number here of the whole run's particle g, `none` where the window does not hold it.
  std::size_t here(std::size_t g) const {
    if (one_rank_) return g;
    const auto r = std::upper_bound(ranges_.begin(), ranges_.end(), g, [](std::size_t x, const Range& a) { return x < a.whole; });
    if (r == ranges_.begin()) return none;
    const Range& a = *(r - 1);
    return g - a.whole < a.count ? a.here + (g - a.whole) : none;
  }
  bool holds(std::size_t g) const { return here(g) != none; }
  /// The number here of the window's first particle whose whole-run number is g or above (the
  /// window's size, or one rank's g, where there is none).
  std::size_t first_from(std::size_t g) const {
    if (one_rank_) return g;
    const auto r = std::upper_bound(ranges_.begin(), ranges_.end(), g, [](std::size_t x, const Range& a) { return x < a.whole + a.count; });
    if (r == ranges_.end()) return ranges_.empty() ? 0 : ranges_.back().here + ranges_.back().count;
    return r->here + (g > r->whole ? g - r->whole : 0);
  }
  /// The window's numbers here of whole-run ranges it holds (ascending), each cut to the window.
  std::vector<IndexRange> here_of(const std::vector<IndexRange>& whole_ranges) const {
    if (one_rank_) return whole_ranges;
    std::vector<IndexRange> out;
    for (const IndexRange& w : whole_ranges)
      for (const Range& a : ranges_) {
        const std::size_t first = std::max(w.first, a.whole), last = std::min(w.last, a.whole + a.count);
        if (first < last) out.push_back({a.here + (first - a.whole), a.here + (last - a.whole)});
      }
    std::sort(out.begin(), out.end(), [](const IndexRange& x, const IndexRange& y) { return x.first < y.first; });
    return out;
  }
  /// One rank's: every particle's number its own (no ranges).
  bool one_rank() const { return one_rank_; }
  const std::vector<Range>& ranges() const { return ranges_; }

 private:
  std::vector<Range> ranges_;
  bool one_rank_ = true;
};

}  // namespace rift::pd
