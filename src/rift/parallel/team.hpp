// When a loop is worth an OpenMP team. Forking a team and meeting at its closing barrier costs a
// few microseconds on idle CPUs and can cost milliseconds when the CPUs are shared (threads spin in
// the barrier while the thread they wait for is descheduled). A loop over a few hundred particles
// or grid nodes does less work than that, so it runs on the calling thread: small problems stepped
// many thousands of times (unit tests, 2D benchmarks) then cost the same on any machine.
#pragma once
#include <cstddef>

namespace rift::parallel {

/// Loops over fewer items (particles, grid nodes, bond blocks) than this run on one thread.
inline constexpr std::size_t min_items_per_team = 1024;

/// Whether a loop over `items` items should fork a team (use in `#pragma omp parallel if(...)`).
inline bool worth_a_team(std::size_t items) { return items >= min_items_per_team; }

}  // namespace rift::parallel
