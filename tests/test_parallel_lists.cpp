// The team's lists: its sort (parallel/sort.hpp), chunks sorted by the threads and merged pairwise,
// gives std::sort's order on any team, whole chunks or not; the indices where a test holds
// (parallel/indices_where.hpp) come in the order of a loop on one thread. ctest runs the tests with
// OMP_NUM_THREADS=1, so the teams here are asked for explicitly.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "rift/parallel/indices_where.hpp"
#include "rift/parallel/sort.hpp"

namespace {

TEST(ParallelLists, SortGivesTheOrderOfStdSortOnAnyTeam) {
  const int before = omp_get_max_threads();
  std::mt19937_64 next(7);  // a fixed sequence (the standard's engine)
  for (const std::size_t n : {std::size_t{0}, std::size_t{5}, std::size_t{40000}, std::size_t{100003}}) {
    // (particle, bond) pairs as the passes sort them: few particles, so many pairs share the first
    std::vector<std::pair<std::size_t, std::int64_t>> pairs(n);
    for (auto& p : pairs) p = {next() % 5000, static_cast<std::int64_t>(next() % 1000)};
    auto expected = pairs;
    std::sort(expected.begin(), expected.end());
    for (const int threads : {1, 2, 3, 4, 7}) {
      omp_set_num_threads(threads);
      auto sorted = pairs;
      rift::parallel::sort(sorted);
      EXPECT_EQ(sorted, expected) << n << " pairs on " << threads << " threads";
    }
  }
  omp_set_num_threads(before);
}

TEST(ParallelLists, IndicesWhereATestHoldsComeInTheOrderOfOneThread) {
  const int before = omp_get_max_threads();
  auto holds = [](std::size_t i) { return (i * 2654435761u) % 7 < 2; };
  for (const std::size_t first : {std::size_t{0}, std::size_t{13}})
    for (const std::size_t last : {std::size_t{13}, std::size_t{1500}, std::size_t{100003}}) {
      std::vector<std::size_t> expected{42};  // appended after what the list holds
      for (std::size_t i = first; i < last; ++i)
        if (holds(i)) expected.push_back(i);
      for (const int threads : {1, 2, 3, 8}) {
        omp_set_num_threads(threads);
        std::vector<std::size_t> found{42};
        rift::parallel::append_indices_where(first, last, found, holds);
        EXPECT_EQ(found, expected) << "[" << first << ", " << last << ") on " << threads << " threads";
      }
    }
  omp_set_num_threads(before);
}

}  // namespace
