// Sums whose bits do not depend on the order of their terms, nor on how the terms are split among
// threads or ranks: each term is rounded to one fixed-point grid, 2^-e, and the grid's integers are
// added exactly (the pre-rounding of reproducible summation: Rump, Ogita and Oishi 2008; Demmel and
// Nguyen 2015). The grid comes from the largest term: with at most 2^40 terms in a sum nothing
// overflows 126 bits, and a term keeps its bits down to 2^-85 of the largest term (about 3e-26),
// below a double sum's own round-off. For sums that gather terms from scattered particles into
// shared entries (the coarse space's, pd/coarse_space.hpp), where ordered_sum.hpp's fixed blocks
// do not apply.
#pragma once
#include <cmath>
#include <cstddef>
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
  }
  /// Adds every rank's sums into every rank's (exact: the same bits in any rank order).
  void add_over(const Communicator& comm) {
    if (!comm.distributed()) return;
    finite_ = !comm.any(!finite_);
    const std::size_t count = sums_.size();
    if (count == 0) return;
    const std::vector<Integer> all = comm.all_gather(sums_);
    for (std::size_t k = 0; k < count; ++k) sums_[k] = 0;
    for (std::size_t q = 0; q < all.size(); ++q) sums_[q % count] += all[q];
  }
  double operator[](std::size_t k) const { return finite_ ? std::ldexp(static_cast<double>(sums_[k]), -scale_) : std::nan(""); }
  std::size_t size() const { return sums_.size(); }

 private:
  std::vector<Integer> sums_;
  int scale_ = 0;
  bool finite_ = true;
};

}  // namespace rift::parallel
