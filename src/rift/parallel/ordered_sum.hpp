// Reductions that give the same bits for any thread count: ordered_sums cuts the range into fixed
// blocks (independent of the number of threads), each block summed in order and the block sums
// added in order; exact_sums adds exactly (exact_sum.hpp), the same bits for any cut of the terms
// among threads and ranks. OpenMP's reduction clause does not promise an order for floating point.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "rift/core/index_range.hpp"
#include "rift/parallel/exact_sum.hpp"

namespace rift::parallel {

/// The particles of one block of the sums.
inline constexpr std::size_t ordered_sum_block = 4096;

/// Each block's sums of K quantities over i in [first, first + n), blocks from `first` on.
template <std::size_t K, class F>
std::vector<std::array<double, K>> block_sums(std::size_t first, std::size_t n, F&& f) {
  constexpr std::size_t block = ordered_sum_block;
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::array<double, K>> partial(blocks);
#pragma omp parallel for if(blocks > 1) schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) {
    std::array<double, K> acc{};
    const std::size_t end = first + std::min(n, (b + 1) * block);
    for (std::size_t i = first + b * block; i < end; ++i) f(i, acc);
    partial[b] = acc;
  }
  return partial;
}

template <std::size_t K>
std::array<double, K> add_in_order(const std::vector<std::array<double, K>>& partial) {
  std::array<double, K> total{};
  for (const auto& p : partial)
    for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
  return total;
}

/// Sums of K quantities over i in [0, n): f(i, acc) adds particle i's contributions into acc.
template <std::size_t K, class F>
std::array<double, K> ordered_sums(std::size_t n, F&& f) {
  return add_in_order<K>(block_sums<K>(0, n, f));
}

/// Sums of K quantities over the particles of `owned` (ranges) on every rank of `comm`, in units
/// that no rank cuts: continues(i) says whether particle i belongs to the unit of particle i - 1 (a
/// peridynamic run's lattice lines along x, pd/model.hpp continues_line; each range starts one).
/// Each unit's terms are summed in order in doubles, f(i, acc) adding particle i's into acc, and
/// the units' sums are added exactly (exact_sum.hpp), the threads' and the ranks' alike, and rounded
/// once. The bits do not depend on how the units are cut among threads and ranks: any partition of
/// a distributed peridynamic run (pd/window.hpp: slabs, pencils) gives the one-rank run's.
template <std::size_t K, class Continues, class F>
std::array<double, K> exact_sums(const Communicator& comm, const std::vector<IndexRange>& owned, Continues&& continues, F&& f) {
  constexpr std::size_t block = ordered_sum_block;
  std::vector<std::pair<std::size_t, std::size_t>> blocks;  // [first, last) of each: about `block` particles, whole units
  for (const IndexRange& r : owned)
    for (std::size_t i = r.first; i < r.last;) {
      std::size_t j = std::min(r.last, i + block);
      while (j < r.last && continues(j)) ++j;
      blocks.emplace_back(i, j);
      i = j;
    }
  std::array<ExactSum, K> total;
#pragma omp parallel if(blocks.size() > 1)
  {
    std::array<ExactSum, K> mine;
#pragma omp for schedule(static) nowait
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      std::array<double, K> unit{};
      for (std::size_t i = blocks[b].first; i < blocks[b].second; ++i) {
        if (i > blocks[b].first && !continues(i)) {
          for (std::size_t k = 0; k < K; ++k) mine[k].add(unit[k]);
          unit.fill(0.0);
        }
        f(i, unit);
      }
      for (std::size_t k = 0; k < K; ++k) mine[k].add(unit[k]);
    }
#pragma omp critical(rift_exact_sums)
    for (std::size_t k = 0; k < K; ++k) total[k].add(mine[k]);
  }
  return rounded_over_ranks<K>(comm, total);
}

}  // namespace rift::parallel
