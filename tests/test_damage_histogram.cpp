// The damage histogram (io/damage_histogram.hpp): intervals [k/10, (k+1)/10), damage 1 in the last.
#include <gtest/gtest.h>

#include "rift/io/damage_histogram.hpp"

TEST(DamageHistogram, IntervalsOfOneTenthWithFullDamageInTheLast) {
  const auto counts = rift::io::damage_histogram({0.0, 0.05, 0.0999, 0.1, 0.35, 0.5, 0.95, 0.99, 1.0, 1.0});
  const std::array<std::int64_t, 10> expected{3, 1, 0, 1, 0, 1, 0, 0, 0, 4};
  EXPECT_EQ(counts, expected);
}
