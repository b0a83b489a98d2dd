// The fields of a distributed peridynamic run's ghosts (pd/window.hpp) that are not doubles: flags
// and labels, refreshed from their owners through the halo's exchange of doubles (every int and
// byte is exact in a double), and the communicator of the run's ranks.
#pragma once
#include <algorithm>
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

/// The ghosts' rows' bond states (intact, broken, interface failed) and their marks of having
/// crossed the crack when they broke (FluidNetwork::crossing_broken), from their owners, whose rows
/// are whole: a rank decides the bonds with an owned end (the bond passes), the owners those
/// between two ghosts, which the fluid's labels, fragments, network load and crack surface read.
/// Packed by family offset, 3 bits each and 16 to a double (48 bits, exact), so the halo's
/// exchange of doubles carries them (nothing on one rank).
template <int D>
void refresh_ghost_bond_states(Model<D>& m) {
  if (!m.ghosts) return;
  Bonds& b = m.bonds;
  m.fluid_network.settle_crossing_broken();
  std::vector<std::int64_t>& crossing = m.fluid_network.crossing_broken;
  const std::size_t n = m.size();
  const std::vector<IndexRange> owned = m.owned();
  constexpr std::size_t per_double = 16, bits = 3;
  std::size_t family = 0;
  for (const BodyInfo& body : m.bodies) family = std::max(family, body.family_count);
  const std::size_t width = (family + per_double - 1) / per_double;
  if (width == 0 || b.offset.size() != n + 1) return;
  auto place = [&](std::size_t i, std::int64_t k) { return b.family[static_cast<std::size_t>(k)] - m.bodies[m.body[i]].first_family; };
  std::vector<double> packed(n * width, 0.0);
  {
    std::vector<std::uint64_t> words(width);
    for (const IndexRange& r : owned) {
      auto marked = std::lower_bound(crossing.begin(), crossing.end(), b.offset[r.first]);
      for (std::size_t i = r.first; i < r.last; ++i) {
        std::fill(words.begin(), words.end(), 0);
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
          while (marked != crossing.end() && *marked < k) ++marked;
          const bool crossed = marked != crossing.end() && *marked == k;
          const std::uint64_t code = b.intact[static_cast<std::size_t>(k)] | (crossed ? 4u : 0u);
          const std::size_t a = place(i, k);
          words[a / per_double] |= code << (bits * (a % per_double));
        }
        for (std::size_t q = 0; q < width; ++q) packed[i * width + q] = static_cast<double>(words[q]);
      }
    }
  }
  m.ghosts->refresh(packed.data(), width);
  // the owned rows' marks kept, the ghosts' rows' from their owners
  std::vector<std::int64_t> marks;
  for (const IndexRange& r : owned)
    marks.insert(marks.end(), std::lower_bound(crossing.begin(), crossing.end(), b.offset[r.first]),
                 std::lower_bound(crossing.begin(), crossing.end(), b.offset[r.last]));
  for (const IndexRange& r : m.ghost_ranges())
    for (std::size_t i = r.first; i < r.last; ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const std::size_t a = place(i, k);
        const auto code = static_cast<std::uint64_t>(packed[i * width + a / per_double]) >> (bits * (a % per_double)) & 7u;
        const auto state = static_cast<std::uint8_t>(code & 3u);
        if (b.intact[static_cast<std::size_t>(k)] != state) b.intact.set(static_cast<std::size_t>(k), state);  // kept rows stay where nothing changed
        if (code & 4u) marks.push_back(k);
      }
  std::sort(marks.begin(), marks.end());
  crossing = std::move(marks);
}

}  // namespace rift::pd
