// Reductions that give the same bits for any thread count: the range is cut into fixed blocks
// (independent of the number of threads), each block is summed in order, and the block sums are
// added in order. OpenMP's reduction clause does not promise an order for floating point.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "rift/core/index_range.hpp"
#include "rift/parallel/communicator.hpp"

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

/// The same sums over a distributed run whose ranks own [first, first + n) each (pd/window.hpp),
/// cut at whole blocks of the whole numbering (Partition's granularity): every rank adds every
/// rank's block sums in rank order, which is the one-rank run's order, so the sums are its bits.
template <std::size_t K, class F>
std::array<double, K> ordered_sums(const Communicator& comm, std::size_t first, std::size_t n, F&& f) {
  auto partial = block_sums<K>(first, n, f);
  if (comm.distributed()) partial = comm.all_gather(partial);
  return add_in_order<K>(partial);
}

/// The same over ranks that own a few ranges each (ascending), each range cut at whole blocks of
/// the whole numbering: a rank's block sums range after range, then every rank's in rank order.
template <std::size_t K, class F>
std::array<double, K> ordered_sums(const Communicator& comm, const std::vector<IndexRange>& owned, F&& f) {
  std::vector<std::array<double, K>> partial;
  for (const IndexRange& r : owned) {
    const auto sums = block_sums<K>(r.first, r.size(), f);
    partial.insert(partial.end(), sums.begin(), sums.end());
  }
  if (comm.distributed()) partial = comm.all_gather(partial);
  return add_in_order<K>(partial);
}

}  // namespace rift::parallel
