// The indices of [first, last) where a test holds, ascending, found by the team: each thread takes
// one stretch of the range in order (a static schedule) and the threads' finds are joined in that
// order, so the list is the one a loop on one thread makes. A thesis-size step compares 4 million
// particles' bond counts to find the few hundred thousand whose bonds changed.
#pragma once
#include <cstddef>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "rift/parallel/team.hpp"

namespace rift::parallel {

/// Appends to `out` the indices i of [first, last) with holds(i), ascending.
template <class Holds>
void append_indices_where(std::size_t first, std::size_t last, std::vector<std::size_t>& out, Holds&& holds) {
  if (last <= first) return;
  int threads = 1;
#ifdef _OPENMP
  if (worth_a_team(last - first) && !omp_in_parallel()) threads = omp_get_max_threads();
#endif
  if (threads < 2) {
    for (std::size_t i = first; i < last; ++i)
      if (holds(i)) out.push_back(i);
    return;
  }
  std::vector<std::vector<std::size_t>> found(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    std::size_t t = 0, team = 1;
#ifdef _OPENMP
    t = static_cast<std::size_t>(omp_get_thread_num()), team = static_cast<std::size_t>(omp_get_num_threads());
#endif
    // one stretch per thread, in thread order
    const std::size_t count = last - first;
    for (std::size_t i = first + count * t / team; i < first + count * (t + 1) / team; ++i)
      if (holds(i)) found[t].push_back(i);
  }
  for (const auto& list : found) out.insert(out.end(), list.begin(), list.end());
}

}  // namespace rift::parallel
