// Sums whose bits do not depend on the order of their terms, nor on how the terms are split among
// threads or ranks: each term is rounded to one fixed-point grid, 2^-e, and the grid's integers are
// added exactly (the pre-rounding of reproducible summation: Rump, Ogita and Oishi 2008; Demmel and
// Nguyen 2015). The grid comes from the largest term: with at most 2^40 terms in a sum nothing
// overflows 126 bits, and a term keeps its bits down to 2^-85 of the largest term (about 3e-26),
// below a double sum's own round-off. For sums that gather terms from scattered particles into
// shared entries (the coarse space's, pd/coarse_space.hpp), where ordered_sum.hpp's fixed blocks
// do not apply.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/parallel/communicator.hpp"

namespace rift::parallel {

class FixedPointSums {
 public:
  __extension__ typedef __int128 Integer;
  static constexpr int max_terms_log2 = 40;

  /// `count` sums of terms no larger than `largest` in magnitude (the same on every rank).
  FixedPointSums(std::size_t count, double largest) : sums_(count, 0) {
    int exponent = 0;  // largest < 2^exponent
    if (largest > 0.0 && std::isfinite(largest)) std::frexp(largest, &exponent);
    scale_ = 125 - max_terms_log2 - exponent;
  }
  /// A term that is not finite makes every sum NaN.
  void add(std::size_t k, double term) {
    if (std::isfinite(term)) sums_[k] += static_cast<Integer>(std::nearbyint(std::ldexp(term, scale_)));
    else finite_ = false;
    first_ = std::min(first_, k), last_ = std::max(last_, k + 1);
  }
  /// Adds every rank's sums into every rank's (exact: the same bits in any rank order). A rank sends
  /// the range of sums it added to, from the first to the last (the coarse space's aggregates are
  /// numbered in grid order, so a slab of particles adds to a range of them).
  void add_over(const Communicator& comm) {
    if (!comm.distributed()) return;
    finite_ = !comm.any(!finite_);
    if (first_ >= last_) first_ = last_ = 0;
    const std::vector<std::uint64_t> ranges = comm.all_gather(std::vector<std::uint64_t>{first_, last_});
    const std::vector<Integer> all = comm.all_gather(std::vector<Integer>(sums_.begin() + static_cast<std::ptrdiff_t>(first_),
                                                                           sums_.begin() + static_cast<std::ptrdiff_t>(last_)));
    std::fill(sums_.begin(), sums_.end(), Integer{0});
    std::size_t at = 0;
    for (std::size_t r = 0; r + 1 < ranges.size(); r += 2)
      for (std::uint64_t k = ranges[r]; k < ranges[r + 1]; ++k) sums_[k] += all[at++];
    first_ = 0, last_ = sums_.size();
  }
  double operator[](std::size_t k) const { return finite_ ? std::ldexp(static_cast<double>(sums_[k]), -scale_) : std::nan(""); }
  std::size_t size() const { return sums_.size(); }

 private:
  std::vector<Integer> sums_;
  int scale_ = 0;
  bool finite_ = true;
  std::size_t first_ = static_cast<std::size_t>(-1), last_ = 0;  // the sums added to: [first_, last_)
};

}  // namespace rift::parallel
