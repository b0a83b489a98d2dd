// A sort by the team: each thread sorts a chunk, then the chunks are merged pairwise (each round's
// merges in parallel). The lists sorted after bonds break (a thesis-size step breaks half a million
// pairs) took one thread while the other waited. For elements whose equal elements are the same
// (pairs of indices, say) the result is std::sort's on any number of threads.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace rift::parallel {

/// Sorts v ascending, by the team where it is long enough to be worth one.
template <class T>
void sort(std::vector<T>& v) {
  constexpr std::size_t per_thread = 1 << 14;  // a shorter list sorts on one thread
  int threads = 1;
#ifdef _OPENMP
  if (!omp_in_parallel()) threads = std::min<int>(omp_get_max_threads(), static_cast<int>(v.size() / per_thread));
#endif
  if (threads < 2) {
    std::sort(v.begin(), v.end());
    return;
  }
  const auto chunks = static_cast<std::size_t>(threads);
  std::vector<std::ptrdiff_t> bound(chunks + 1);
  for (std::size_t c = 0; c <= chunks; ++c) bound[c] = static_cast<std::ptrdiff_t>(v.size() * c / chunks);
  const auto begin = v.begin();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::size_t c = 0; c < chunks; ++c) std::sort(begin + bound[c], begin + bound[c + 1]);
  for (std::size_t width = 1; width < chunks; width *= 2) {
    const std::size_t pairs = (chunks - width + 2 * width - 1) / (2 * width);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t p = 0; p < pairs; ++p) {
      const std::size_t c = 2 * width * p;
      std::inplace_merge(begin + bound[c], begin + bound[c + width], begin + bound[std::min(chunks, c + 2 * width)]);
    }
  }
}

}  // namespace rift::parallel
