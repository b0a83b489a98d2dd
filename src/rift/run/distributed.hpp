// What a distributed peridynamic run (pd/window.hpp) reduces to one answer: the history's sums over
// the ranks' owned particles, and the fields gathered to rank 0 in the whole run's numbering (the
// ranks own consecutive ranges of it, in rank order), which writes them as one rank would.
#pragma once
#include <algorithm>
#include <vector>

#include "rift/parallel/communicator.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/model.hpp"

namespace rift::run {

/// The whole run's energies and broken bonds from each rank's (pd::summarize).
inline pd::EnergySummary reduce(const parallel::Communicator& comm, pd::EnergySummary e) {
  if (!comm.distributed()) return e;
  double sums[4] = {e.kinetic, e.strain, e.failed_directed, e.directed};
  comm.sum(sums, 4);
  e.kinetic = sums[0], e.strain = sums[1], e.failed_directed = sums[2], e.directed = sums[3];
  e.broken_bonds = static_cast<std::int64_t>(e.failed_directed) / 2;
  e.broken_fraction = e.directed > 0.0 ? e.failed_directed / e.directed : 0.0;
  return e;
}

/// A per-particle field (`width` values each) of the owned particles, the whole run's on rank 0.
template <int D>
std::vector<double> gather_owned(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<double>& field,
                                 std::size_t width) {
  if (!comm.distributed()) return field;
  const auto first = static_cast<std::ptrdiff_t>(m.owned_begin * width), last = static_cast<std::ptrdiff_t>(m.owned_last() * width);
  return comm.gather(std::vector<double>(field.begin() + first, field.begin() + last));
}

/// The largest damage of the owned particles, over every rank.
template <int D>
double max_damage(const parallel::Communicator& comm, const pd::Model<D>& m) {
  double d = 0.0;
  for (std::size_t i = m.owned_begin; i < m.owned_last(); ++i) d = std::max(d, m.damage[i]);
  return comm.max(d);
}

}  // namespace rift::run
