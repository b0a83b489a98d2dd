// The fields of a distributed peridynamic run's ghosts (pd/window.hpp) that are not doubles: flags
// and labels, refreshed from their owners through the halo's exchange of doubles (every int and
// byte is exact in a double), and the communicator of the run's ranks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/parallel/communicator.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// The ranks a model's sums and decisions are taken over: every rank of a distributed run, or this
/// process alone.
template <int D>
const parallel::Communicator& ranks_of(const Model<D>& m) {
  return m.ghosts ? parallel::Communicator::world() : parallel::Communicator::one();
}

/// Each flag set where it is set on any rank (in place; nothing on one rank).
inline void set_on_any_rank(const parallel::Communicator& ranks, std::vector<std::uint8_t>& flags) {
  if (!ranks.distributed() || flags.empty()) return;
  std::vector<double> any(flags.begin(), flags.end());
  ranks.max(any.data(), any.size());
  for (std::size_t q = 0; q < any.size(); ++q) flags[q] = any[q] > 0.0 ? 1 : 0;
}

/// The ghosts' copies of a per-particle field of integers or flags, from their owners (nothing on
/// one rank).
template <int D, class T>
void refresh_ghost_values(const Model<D>& m, std::vector<T>& field) {
  if (!m.ghosts || field.empty()) return;
  std::vector<double> copy(field.begin(), field.end());
  m.ghosts->refresh(copy.data(), 1);
  for (std::size_t i = 0; i < field.size(); ++i) field[i] = static_cast<T>(copy[i]);
}

}  // namespace rift::pd
