// Reductions that give the same bits for any thread count: the range is cut into fixed blocks
// (independent of the number of threads), each block is summed in order, and the block sums are
// added in order. OpenMP's reduction clause does not promise an order for floating point.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace rift::parallel {

/// Sums of K quantities over i in [0, n): f(i, acc) adds particle i's contributions into acc.
template <std::size_t K, class F>
std::array<double, K> ordered_sums(std::size_t n, F&& f) {
  constexpr std::size_t block = 4096;
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::array<double, K>> partial(blocks);
#pragma omp parallel for if(blocks > 1) schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) {
    std::array<double, K> acc{};
    const std::size_t end = std::min(n, (b + 1) * block);
    for (std::size_t i = b * block; i < end; ++i) f(i, acc);
    partial[b] = acc;
  }
  std::array<double, K> total{};
  for (const auto& p : partial)
    for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
  return total;
}

}  // namespace rift::parallel
