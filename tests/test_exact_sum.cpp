// The exact sum of doubles (parallel/exact_sum.hpp): the correctly rounded sum of its terms, so the
// same bits in any order and any split among threads and ranks. A distributed peridynamic run's
// sums over the owned particles take it (exact_sums), so any cut of the particles (slabs, pencils)
// gives the one-rank run's damping, residuals and energies (tests/test_mpi.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rift/parallel/ordered_sum.hpp"

namespace {

using rift::parallel::ExactSum;

double exact_sum_of(const std::vector<double>& terms) {
  ExactSum s;
  for (const double t : terms) s.add(t);
  return s.value();
}

// 100,000 terms m 2^e, |m| < 2^30 and e in [-70, 0], either sign: 2^70 times each is a whole
// number, so the sum is exact in 128-bit integers and the correctly rounded double is that integer
// converted (round to nearest, ties to even) and scaled by 2^-70. The accumulator gives those bits
// forward, backward, shuffled, and split into 7 parts added together.
TEST(ExactSum, IsTheCorrectlyRoundedSumInAnyOrderAndSplit) {
  std::mt19937_64 random(2026);
  std::uniform_int_distribution<std::int64_t> mantissa(-(std::int64_t{1} << 30), std::int64_t{1} << 30);
  std::uniform_int_distribution<int> exponent(-70, 0);
  std::vector<double> terms(100000);
  __int128 scaled = 0;  // the sum times 2^70
  for (auto& t : terms) {
    const std::int64_t m = mantissa(random);
    const int e = exponent(random);
    t = std::ldexp(static_cast<double>(m), e);
    scaled += static_cast<__int128>(m) << (e + 70);
  }
  const double expected = std::ldexp(static_cast<double>(scaled), -70);
  EXPECT_EQ(exact_sum_of(terms), expected);
  std::reverse(terms.begin(), terms.end());
  EXPECT_EQ(exact_sum_of(terms), expected);
  for (int k = 0; k < 3; ++k) {
    std::shuffle(terms.begin(), terms.end(), random);
    EXPECT_EQ(exact_sum_of(terms), expected);
  }
  ExactSum whole;
  for (std::size_t part = 0; part < 7; ++part) {
    ExactSum s;
    for (std::size_t i = part; i < terms.size(); i += 7) s.add(terms[i]);
    whole.add(s);
  }
  EXPECT_EQ(whole.value(), expected);
  // a double sum in these orders differs in its last bits: the point of the accumulator
  double naive = 0.0;
  for (const double t : terms) naive += t;
  EXPECT_NEAR(naive, expected, 1e-9 * std::abs(expected));
}

// What a double sum loses to cancellation and to the ends of the range of doubles, and the rounding
// of a tie (IEEE 754 round to nearest, ties to even).
TEST(ExactSum, KeepsCancellationSubnormalsAndRoundsTiesToEven) {
  EXPECT_EQ(exact_sum_of({1e300, 1.0, -1e300}), 1.0);
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact_sum_of({std::numeric_limits<double>::max(), tiny, -std::numeric_limits<double>::max()}), tiny);
  EXPECT_EQ(exact_sum_of({-2.5, 0.5}), -2.0);
  EXPECT_EQ(exact_sum_of({1.0, std::ldexp(1.0, -53)}), 1.0);  // a tie: to the even neighbour
  EXPECT_EQ(exact_sum_of({1.0, std::ldexp(1.0, -53), std::ldexp(1.0, -200)}), 1.0 + std::ldexp(1.0, -52));  // past the tie
  EXPECT_EQ(exact_sum_of({1.0 + std::ldexp(1.0, -52), std::ldexp(1.0, -53)}), 1.0 + std::ldexp(1.0, -51));  // a tie, up to even
  EXPECT_EQ(exact_sum_of({}), 0.0);
  EXPECT_EQ(exact_sum_of({std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}), std::numeric_limits<double>::infinity());
}

TEST(ExactSum, NonFiniteTermsGiveWhatADoubleSumGives) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exact_sum_of({1.0, inf, 2.0}), inf);
  EXPECT_EQ(exact_sum_of({1.0, -inf}), -inf);
  EXPECT_TRUE(std::isnan(exact_sum_of({inf, 1.0, -inf})));
  EXPECT_TRUE(std::isnan(exact_sum_of({std::nan(""), 1.0})));
}

// exact_sums over ranges of particles in units of 10 (a model's lattice lines): the same bits for
// any cut of the units into ranges (one rank's share of a pencil is one range per layer) and any
// thread count, and the units' sums added exactly.
TEST(ExactSum, SumsOverRangesOfUnitsDoNotDependOnTheCut) {
  const std::size_t n = 20000;
  std::vector<double> x(n);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& v : x) v = u(random) * std::exp(20.0 * u(random));
  const auto continues = [](std::size_t i) { return i % 10 != 0; };
  auto sums = [&](const std::vector<rift::IndexRange>& ranges) {
    return rift::parallel::exact_sums<2>(rift::parallel::Communicator::one(), ranges, continues, [&](std::size_t i, std::array<double, 2>& acc) {
      acc[0] += x[i];
      acc[1] += x[i] * x[i];
    });
  };
  const auto whole = sums({{0, n}});
  for (const auto& cut : std::vector<std::vector<rift::IndexRange>>{{{0, 10}, {10, n}}, {{0, 4090}, {4090, 9000}, {9000, n}}, {{0, 70}, {70, 130}, {130, 19990}, {19990, n}}}) {
    const auto parts = sums(cut);
    EXPECT_EQ(parts[0], whole[0]);
    EXPECT_EQ(parts[1], whole[1]);
  }
  // the units' double sums, added exactly
  rift::parallel::ExactSum expected;
  for (std::size_t unit = 0; unit < n; unit += 10) {
    double s = 0.0;
    for (std::size_t i = unit; i < unit + 10; ++i) s += x[i];
    expected.add(s);
  }
  EXPECT_EQ(whole[0], expected.value());
}

}  // namespace
