// A distributed peridynamic run's windows (pd/window.hpp): the numbering of a window that holds
// several ranges of the whole run's particles (pd/numbering.hpp). The runs on N ranks themselves
// are tests/test_mpi.sh (bitwise the one-rank run).
#include <gtest/gtest.h>

#include <vector>

#include "rift/pd/numbering.hpp"

namespace {

using rift::pd::Numbering;

TEST(WindowNumbering, OneRankNumbersEveryParticleAsItsOwn) {
  const Numbering one;
  EXPECT_TRUE(one.one_rank());
  EXPECT_EQ(one.whole(17), 17u);
  EXPECT_EQ(one.here(123456), 123456u);
}

TEST(WindowNumbering, RangesAreNumberedHereInTheWholeRunsOrder) {
  // three lines of a box, the first two adjacent in the whole numbering (joined into one range)
  const Numbering w({{10, 14}, {14, 16}, {30, 33}, {50, 50}, {60, 62}});
  ASSERT_EQ(w.ranges().size(), 3u);
  const std::vector<std::size_t> whole{10, 11, 12, 13, 14, 15, 30, 31, 32, 60, 61};
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(w.whole(i), whole[i]) << "particle " << i << " here";
    EXPECT_EQ(w.here(whole[i]), i) << "particle " << whole[i] << " of the whole run";
  }
  // numbers between, before and after the ranges are not held
  for (const std::size_t g : {0u, 9u, 16u, 29u, 33u, 50u, 59u, 62u, 1000u}) EXPECT_EQ(w.here(g), Numbering::none) << g;
  EXPECT_FALSE(w.holds(16));
  EXPECT_TRUE(w.holds(61));
}

TEST(WindowNumbering, OneRangeIsAnOffset) {
  const auto w = Numbering::range(400, 100);
  EXPECT_FALSE(w.one_rank());
  EXPECT_EQ(w.whole(0), 400u);
  EXPECT_EQ(w.whole(99), 499u);
  EXPECT_EQ(w.here(399), Numbering::none);
  EXPECT_EQ(w.here(450), 50u);
  EXPECT_EQ(w.here(500), Numbering::none);
  // an empty window holds nothing
  EXPECT_EQ(Numbering::range(400, 0).here(400), Numbering::none);
}

}  // namespace
