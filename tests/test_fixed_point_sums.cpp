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

TEST(FixedPointSums, ANonFiniteTermMakesTheSumNaN) {
  EXPECT_TRUE(std::isnan(sum_of({1.0, std::numeric_limits<double>::infinity(), 2.0}, 2.0)));
  EXPECT_EQ(sum_of({}, 0.0), 0.0);
}

}  // namespace
