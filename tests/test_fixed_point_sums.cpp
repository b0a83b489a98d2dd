// Sums in fixed point (parallel/fixed_point_sums.hpp): the same bits in any order of the terms, and
// at least as accurate as a double sum. The coarse space of the in-situ stage sums with them, so a
// distributed run's K_c and right-hand sides are the one-rank run's bits (tests/test_mpi.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rift/parallel/fixed_point_sums.hpp"

namespace {

using rift::parallel::FixedPointSums;

double sum_of(const std::vector<double>& terms, double largest) {
  FixedPointSums s(1, largest);
  for (const double t : terms) s.add(0, t);
  return s[0];
}

// 100,000 terms of either sign over 16 decades: forward, backward and three shuffles give the
// same bits; the sum is within 2 ulp of a long-double sum of the terms sorted by magnitude
// (a double sum in this order differs in its last bits, which is the point).
TEST(FixedPointSums, AnyOrderGivesTheSameBits) {
  std::mt19937_64 random(2026);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> decade(-8, 8);
  std::vector<double> terms(100000);
  double largest = 0.0;
  for (auto& t : terms) t = mantissa(random) * std::pow(10.0, decade(random)), largest = std::max(largest, std::abs(t));
  const double forward = sum_of(terms, largest);
  std::vector<double> order = terms;
  std::reverse(order.begin(), order.end());
  EXPECT_EQ(sum_of(order, largest), forward);
  for (int shuffle = 0; shuffle < 3; ++shuffle) {
    std::shuffle(order.begin(), order.end(), random);
    EXPECT_EQ(sum_of(order, largest), forward);
  }
  std::sort(order.begin(), order.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  long double reference = 0.0L;
  for (const double t : order) reference += t;
  EXPECT_NEAR(forward, static_cast<double>(reference), 2.0 * std::abs(forward) * std::numeric_limits<double>::epsilon());
}

// Cancellation that a double sum gets wrong: 1e16 + 1 - 1e16 is 0 in doubles (1e16 + 1 rounds to
// 1e16), exactly 1 in fixed point (the grid is 2^-85 of the largest term, about 3e-10 here).
TEST(FixedPointSums, KeepsWhatADoubleSumLosesToCancellation) {
  const std::vector<double> terms{1e16, 1.0, -1e16};
  double naive = 0.0;
  for (const double t : terms) naive += t;
  EXPECT_EQ(naive, 0.0);
  EXPECT_EQ(sum_of(terms, 1e16), 1.0);
}

// A term's grid integer (on_grid: a product by the power of two and a conversion in two halves) is
// the library's, static_cast<__int128>(nearbyint(ldexp(term, scale))), bit for bit: terms of either
// sign from the largest down to 1e-30 of it and below the grid, around the two halves' seam (2^62,
// 2^64 on the grid) and at the largest itself, for largest terms from 1e-300 (scale past a double's
// exponent: ldexp) to 1e300 (a negative scale).
TEST(FixedPointSums, GridIntegersAreTheLibrarysConversion) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const double largest : {1e-300, 3e-200, 1e-9, 0.7, 1.0, 123.456, 6.02e23, 1e300}) {
    FixedPointSums s(1, largest);
    int exponent = 0;
    std::frexp(largest, &exponent);
    const int scale = 125 - FixedPointSums::max_terms_log2 - exponent;
    std::vector<double> terms{largest, -largest, 0.0, -0.0};
    for (const double seam : {0x1p62, 0x1p63, 0x1p64})
      for (const double near : {-2.0, -1.0, -0.5, 0.5, 1.0, 2.0}) terms.push_back(std::ldexp(seam + near * 0x1p10, -scale));
    for (int t = 0; t < 20000; ++t) terms.push_back(largest * unit(random) * std::pow(10.0, -30.0 * std::abs(unit(random))));
    for (int t = 0; t < 1000; ++t) terms.push_back(largest * unit(random) * 1e-27);  // about the grid's spacing
    std::size_t differ = 0;
    for (const double term : terms) {
      if (std::abs(term) > largest) continue;
      const auto expected = static_cast<FixedPointSums::Integer>(std::nearbyint(std::ldexp(term, scale)));
      differ += s.on_grid(term) != expected;
    }
    EXPECT_EQ(differ, 0u) << "largest " << largest;
  }
}

// Threads' partial sums merged give the one sum's bits.
TEST(FixedPointSums, MergedPartsGiveTheWholeSum) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> terms(30000);
  for (auto& t : terms) t = unit(random) * std::pow(10.0, 6.0 * unit(random));
  double largest = 0.0;
  for (const double t : terms) largest = std::max(largest, std::abs(t));
  FixedPointSums whole(4, largest), first(4, largest), second(4, largest);
  for (std::size_t t = 0; t < terms.size(); ++t) {
    whole.add(t % 3, terms[t]);  // the fourth sum stays empty
    (t % 5 < 2 ? first : second).add(t % 3, terms[t]);
  }
  first.merge(second);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(first[k], whole[k]) << k;
  EXPECT_NE(whole[0], 0.0);
}

TEST(FixedPointSums, ANonFiniteTermMakesTheSumNaN) {
  EXPECT_TRUE(std::isnan(sum_of({1.0, std::numeric_limits<double>::infinity(), 2.0}, 2.0)));
  EXPECT_EQ(sum_of({}, 0.0), 0.0);
}

}  // namespace
