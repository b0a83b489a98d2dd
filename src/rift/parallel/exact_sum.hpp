// The exact sum of doubles, rounded once at the end: a long fixed-point accumulator that spans the
// whole range of doubles (Kulisch's accumulator; Kulisch and Miranker 1981, Collange, Defour,
// Graillat and Iakymchuk 2015), so its result is the correctly rounded sum whatever the order of
// the terms and however they are split among threads and ranks. A distributed peridynamic run's
// sums over the owned particles use it (ordered_sum.hpp exact_sums): any cut of the particles among
// ranks (slabs, pencils) gives the one-rank run's bits.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/parallel/communicator.hpp"

namespace rift::parallel {

class ExactSum {
 public:
  // limb k holds the bits of weight 2^(32 k - 1074) .. 2^(32 k - 1043): a double's mantissa (53
  // bits, shifted by up to 31) meets three limbs from 2^-1074 (the smallest subnormal) on; the top
  // limb takes the carries and the sign
  static constexpr int limb_bits = 32;
  static constexpr std::size_t limbs = 67;

  void add(double x) {
    const auto u = std::bit_cast<std::uint64_t>(x);
    const auto biased = static_cast<int>(u >> 52 & 0x7ff);
    std::uint64_t mantissa = u & ((std::uint64_t{1} << 52) - 1);
    if (biased == 0x7ff) {  // infinite or NaN: their sum, whose class does not depend on the order
      non_finite_ += x;
      return;
    }
    if (mantissa == 0 && biased == 0) return;  // a zero
    if (biased != 0) mantissa |= std::uint64_t{1} << 52;
    // x = mantissa 2^(position - 1074); a negative x's parts are negated as (v ^ sign) - sign
    const int position = biased == 0 ? 0 : biased - 1;
    const auto sign = -static_cast<std::int64_t>(u >> 63);
    // most terms of a sum lie within a few decades of each other: into one 128-bit integer of
    // weight 2^(window_ - 1074), exactly, as long as they fit
    if (window_ < 0 || position >= window_ + window_span) {
      flush_window();
      window_ = std::max(0, position - window_below);
    }
    if (position >= window_) {
      const __int128 v = static_cast<__int128>(mantissa) << (position - window_);
      window_sum_ += (v ^ static_cast<__int128>(sign)) - static_cast<__int128>(sign);
      if (++window_terms_ == window_limit) flush_window();
      return;
    }
    const auto k = static_cast<std::size_t>(position / limb_bits);
    const unsigned __int128 shifted = static_cast<unsigned __int128>(mantissa) << (position % limb_bits);
    const auto low = static_cast<std::int64_t>(shifted & 0xffffffffu), middle = static_cast<std::int64_t>((shifted >> 32) & 0xffffffffu),
               high = static_cast<std::int64_t>(shifted >> 64);
    limb_[k] += (low ^ sign) - sign, limb_[k + 1] += (middle ^ sign) - sign, limb_[k + 2] += (high ^ sign) - sign;
    if (++pending_ >= carry_every) normalize();
  }
  /// Adds another sum (a thread's, a rank's).
  void add(const ExactSum& other) {
    ExactSum o = other;
    o.normalize(), normalize();
    for (std::size_t k = 0; k < limbs; ++k) limb_[k] += o.limb_[k];
    non_finite_ += o.non_finite_;
    normalize();
  }
  /// The sum rounded to the nearest double (ties to even).
  double value() const {
    if (non_finite_ != 0.0 || std::isnan(non_finite_)) return non_finite_;
    ExactSum s = *this;
    s.normalize();
    double sign = 1.0;
    if (s.limb_[limbs - 1] < 0) {  // negative: its magnitude
      for (auto& l : s.limb_) l = -l;
      s.normalize();
      sign = -1.0;
    }
    std::size_t top = limbs;
    while (top > 0 && s.limb_[top - 1] == 0) --top;
    if (top == 0) return 0.0;
    // the top three limbs (at least 65 bits: the rounding falls well above the lowest), the lower
    // ones as a sticky bit
    const std::size_t h = top - 1;
    const auto bits = [&](std::size_t k) { return static_cast<unsigned __int128>(static_cast<std::uint64_t>(s.limb_[k])); };
    unsigned __int128 head = bits(h) << 64;
    if (h >= 1) head |= bits(h - 1) << 32;
    if (h >= 2) head |= bits(h - 2);
    bool sticky = false;
    for (std::size_t k = 0; k + 2 < h; ++k) sticky = sticky || s.limb_[k] != 0;
    if (sticky) head |= 1;
    return sign * std::ldexp(static_cast<double>(head), limb_bits * (static_cast<int>(h) - 2) - 1074);
  }
  /// Its limbs with their carries done (from_limbs makes it again), and limb-wise sums of them are sums.
  std::array<std::int64_t, limbs> normalized_limbs() const {
    ExactSum s = *this;
    s.normalize();
    return s.limb_;
  }
  static ExactSum from_limbs(const std::array<std::int64_t, limbs>& l, double non_finite) {
    ExactSum s;
    s.limb_ = l;
    s.non_finite_ = non_finite;
    return s;
  }
  double non_finite() const { return non_finite_; }

 private:
  // each add puts less than 2^32 into a limb: an int64 takes 2^31 of them before its carries move up
  static constexpr std::uint32_t carry_every = 1u << 30;
  // the window: terms from 2^(window_ - 1074) to 2^(window_ + window_span - 1074) in magnitude, a
  // mantissa of 53 bits shifted by up to 62, 2^12 of them under 2^127
  static constexpr int window_span = 62, window_below = 40;
  static constexpr std::uint32_t window_limit = 1u << 12;
  /// The window's sum into the limbs (its 127 bits, shifted, meet 5 limbs of 32 bits).
  void flush_window() {
    if (window_terms_ == 0) return;
    const bool negative = window_sum_ < 0;
    unsigned __int128 magnitude = negative ? -static_cast<unsigned __int128>(window_sum_) : static_cast<unsigned __int128>(window_sum_);
    const auto k = static_cast<std::size_t>(window_ / limb_bits);
    const int shift = window_ % limb_bits;
    const std::int64_t sign = negative ? -1 : 0;
    for (std::size_t j = 0; j < 4; ++j, magnitude >>= 32) {
      const std::uint64_t part = static_cast<std::uint64_t>(magnitude & 0xffffffffu) << shift;  // under 2^63
      const auto low = static_cast<std::int64_t>(part & 0xffffffffu), high = static_cast<std::int64_t>(part >> 32);
      limb_[k + j] += (low ^ sign) - sign, limb_[k + j + 1] += (high ^ sign) - sign;
    }
    window_sum_ = 0, window_terms_ = 0;
    pending_ += 2;  // a limb took two parts at most
    if (pending_ >= carry_every) normalize();
  }
  void normalize() {
    flush_window();
    for (std::size_t k = 0; k + 1 < limbs; ++k) {
      const std::int64_t carry = limb_[k] >> limb_bits;  // floor: the limb is left in [0, 2^32)
      limb_[k] -= carry * (std::int64_t{1} << limb_bits);
      limb_[k + 1] += carry;
    }
    pending_ = 0;
  }
  std::array<std::int64_t, limbs> limb_{};
  double non_finite_ = 0.0;
  std::uint32_t pending_ = 0;
  __int128 window_sum_ = 0;  // the window's terms, in units of 2^(window_ - 1074)
  int window_ = -1;          // none yet
  std::uint32_t window_terms_ = 0;
};

/// Each sum added over every rank of `comm` (exactly: its limbs are integers), rounded.
inline std::vector<double> rounded_over_ranks(const Communicator& comm, std::vector<ExactSum> sums) {
  const std::size_t count = sums.size();
  if (comm.distributed()) {
    std::vector<std::int64_t> limbs(count * ExactSum::limbs);
    std::vector<double> non_finite(count);
    for (std::size_t k = 0; k < count; ++k) {
      const auto l = sums[k].normalized_limbs();
      std::copy(l.begin(), l.end(), limbs.begin() + static_cast<std::ptrdiff_t>(k * ExactSum::limbs));
      non_finite[k] = sums[k].non_finite();
    }
    comm.sum(limbs.data(), limbs.size());
    comm.sum(non_finite.data(), count);
    for (std::size_t k = 0; k < count; ++k) {
      std::array<std::int64_t, ExactSum::limbs> l;
      std::copy_n(limbs.begin() + static_cast<std::ptrdiff_t>(k * ExactSum::limbs), ExactSum::limbs, l.begin());
      sums[k] = ExactSum::from_limbs(l, non_finite[k]);
    }
  }
  std::vector<double> out(count);
  for (std::size_t k = 0; k < count; ++k) out[k] = sums[k].value();
  return out;
}

template <std::size_t K>
std::array<double, K> rounded_over_ranks(const Communicator& comm, const std::array<ExactSum, K>& sums) {
  const std::vector<double> all = rounded_over_ranks(comm, std::vector<ExactSum>(sums.begin(), sums.end()));
  std::array<double, K> out{};
  std::copy(all.begin(), all.end(), out.begin());
  return out;
}

}  // namespace rift::parallel
