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
    if (scale_ >= -1022 && scale_ <= 1023) unit_ = std::ldexp(1.0, scale_);
  }
  /// A term that is not finite makes every sum NaN.
  void add(std::size_t k, double term) {
    if (std::isfinite(term)) sums_[k] += on_grid(term);
    else finite_ = false;
    first_ = std::min(first_, k), last_ = std::max(last_, k + 1);
  }
  /// Adds another's sums (of the same count and largest term: a thread's share of the terms), exactly.
  void merge(const FixedPointSums& other) {
    for (std::size_t k = other.first_; k < other.last_; ++k) sums_[k] += other.sums_[k];
    finite_ = finite_ && other.finite_;
    first_ = std::min(first_, other.first_), last_ = std::max(last_, other.last_);
  }
  /// A finite term on the grid: term 2^scale rounded to the nearest integer. A product by the power
  /// of two is ldexp's correctly rounded result, and the integer (under 2^87 in magnitude) is
  /// converted exactly in two halves, without the library's conversion to 128 bits.
  Integer on_grid(double term) const {
    const double r = std::nearbyint(unit_ > 0.0 ? term * unit_ : std::ldexp(term, scale_));
    if (std::abs(r) < 0x1p62) return static_cast<std::int64_t>(r);
    const double high = std::trunc(r * 0x1p-32);  // exact: a power of two, then an integer under 2^56
    const double low = r - high * 0x1p32;          // exact: an integer under 2^32 in magnitude
    return static_cast<Integer>(static_cast<std::int64_t>(high)) * (Integer{1} << 32) + static_cast<std::int64_t>(low);
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
  double unit_ = 0.0;  // 2^scale_ where a normal double holds it
  bool finite_ = true;
  std::size_t first_ = static_cast<std::size_t>(-1), last_ = 0;  // the sums added to: [first_, last_)
};

}  // namespace rift::parallel
