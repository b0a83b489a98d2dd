// Loops in shared blocks (parallel/shared_blocks.hpp): every item is taken exactly once, whether
// the team is as large as the blocks, smaller (the blocks without an owner taken by the others), or
// the loop too short for a team. ctest runs the tests with OMP_NUM_THREADS=1, so the teams here are
// asked for explicitly.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "rift/parallel/shared_blocks.hpp"

namespace {

using rift::parallel::SharedBlocks;

// How many times each item of [0, n) was taken; each item is written by the one thread that takes it.
std::vector<int> times_taken(std::size_t n, int threads) {
  std::vector<int> taken(n, 0);
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  rift::parallel::for_each_in_shared_blocks(n, [&](std::size_t i) { ++taken[i]; });
  omp_set_num_threads(before);
  return taken;
}

TEST(SharedBlocks, EveryItemIsTakenOnceOnAnyTeam) {
  for (const int threads : {1, 2, 3, 5})
    for (const std::size_t n : {std::size_t{10}, std::size_t{1023}, std::size_t{1024}, std::size_t{100003}}) {
      const auto taken = times_taken(n, threads);
      EXPECT_EQ(std::count(taken.begin(), taken.end(), 1), static_cast<long>(n)) << n << " items on " << threads << " threads";
    }
}

// Four blocks and a team of two: each thread takes its own block, then the blocks of threads that
// never came.
TEST(SharedBlocks, ATeamSmallerThanTheBlocksTakesThemAll) {
  const std::size_t n = 50000;
  std::vector<int> taken(n, 0);
  SharedBlocks blocks;
  blocks.split(n, 4);
#pragma omp parallel num_threads(2)
  blocks.take(static_cast<std::size_t>(omp_get_thread_num()), [&](std::size_t i) { ++taken[i]; });
  EXPECT_EQ(std::count(taken.begin(), taken.end(), 1), static_cast<long>(n));
}

}  // namespace
