// Passes that visit each bond once and act on both of its ends (Newton's third law: the pair force
// of PMB and of the state-based models is equal and opposite on the two particles), without atomics.
// Row i's bonds to higher-numbered neighbours are its forward bonds (rows are sorted by neighbour).
// The particles are cut into index ranges, slabs, no shorter than the farthest forward reach
// max(j - i) (the last takes the rest): a row's forward bonds end in its own slab or the next. Even
// slabs run in parallel, then odd ones, so no two slabs running at once write the same particle. The
// slabs depend on the bonds alone, not on the threads, so every sum is made in the same order on
// any thread count.
// An odd slab waits only for its two even neighbours, not for every even slab (for_each_slab).
#pragma once
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numeric>
#include <thread>
#include <utility>
#include <vector>

#include "rift/pd/bonds.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The first forward bond of row i (neighbour above i).
inline std::int64_t first_forward_bond(const Bonds& b, std::size_t i) {
  const auto first = b.neighbor.begin() + b.offset[i], last = b.neighbor.begin() + b.offset[i + 1];
  return std::upper_bound(first, last, static_cast<std::int32_t>(i)) - b.neighbor.begin();
}

/// The index of bond j-i, the reverse of bond k = i-j, in row j (both of `body`). A row that holds
/// every offset of the body's family lists them in family order (discretize.cpp: offsets in the
/// order the lattice is numbered), so the reverse sits at its offset's place; other rows (a surface,
/// a crack or a borehole cuts the family) are searched.
inline std::int64_t reverse_bond(const Bonds& b, const BodyInfo& body, std::size_t i, std::int64_t k) {
  const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
  if (static_cast<std::size_t>(b.offset[j + 1] - b.offset[j]) == body.family_count)
    return b.offset[j] + static_cast<std::int64_t>(b.family_of(k).mirror - body.first_family);
  const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
  return std::lower_bound(first, last, static_cast<std::int32_t>(i)) - b.neighbor.begin();
}

/// Where the VES history of the pair of particle i (its lower end) with the forward family offset
/// `family` sits (bonds.hpp): direction 0 is i's (i-j), 1 the upper end's (j-i). The family is
/// symmetric and ordered as the lattice is numbered, so its second half are the forward offsets.
inline std::size_t history_index(const BodyInfo& body, std::size_t i, std::size_t family, std::size_t direction) {
  constexpr std::size_t block = Bonds::history_block;
  const std::size_t forward = body.family_count / 2, local = static_cast<std::size_t>(static_cast<std::int64_t>(i) - body.origin);
  const std::size_t offset = family - body.first_family - forward;
  return static_cast<std::size_t>(body.history_base + static_cast<std::int64_t>(((local / block) * forward + offset) * 2 * block + direction * block + local % block));
}

/// Where the VES history of directed bond k = i-j sits.
inline std::size_t history_slot(const Bonds& b, const BodyInfo& body, std::size_t i, std::int64_t k) {
  const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
  const FamilyOffset& family = b.family_of(k);
  if (j > i) return history_index(body, i, b.family[static_cast<std::size_t>(k)], 0);
  return history_index(body, j, family.mirror, 1);
}

/// The history slot of the other direction of slot h's pair.
inline std::size_t mirror_history_slot(std::size_t h) { return h ^ Bonds::history_block; }

/// The pair's slot (Bonds::last_extension) of a history slot h of either direction: the same layout
/// with one direction per block (every body's history_base is a whole number of pairs of blocks).
inline std::size_t pair_slot(std::size_t h) {
  constexpr std::size_t block = Bonds::history_block;
  return h / (2 * block) * block + h % block;
}

/// After a pass broke the bonds `broken` ((i, k) of a row) from their lower ends' side, writing the
/// states in place: their reverses too, and the change counted (BondStates).
inline void break_mirror_bonds(Bonds& b, const BodyInfo& body, const std::vector<std::pair<std::size_t, std::int64_t>>& broken) {
  if (broken.empty()) return;
  std::uint8_t* const state = b.intact.writable();
  // each reverse its own byte: by the team (a thesis-size step breaks half a million pairs)
#pragma omp parallel for if(rift::parallel::worth_a_team(broken.size())) schedule(static)
  for (std::size_t q = 0; q < broken.size(); ++q)
    state[static_cast<std::size_t>(reverse_bond(b, body, broken[q].first, broken[q].second))] = bond_broken;
  b.intact.changed();
}

/// The per-particle buffers of the passes, by what the pass that fills them keeps there: the
/// dilatation pass's q_i and smallest stretch; the positions one component each; the pair forces
/// (the network load's sums) one component each; the force pass's p_i and a_i.
enum class PassBuffer {
  coupling,
  smallest_stretch,
  position_x, position_y, position_z,
  force_x, force_y, force_z,
  pressure,
  deviatoric_coefficient,
  count
};

/// Component k of a buffer of components (position_x, force_x).
constexpr PassBuffer component(PassBuffer x, int k) { return static_cast<PassBuffer>(static_cast<int>(x) + k); }

/// A per-particle buffer of the passes, the calling thread's (the team reads and writes it through
/// the pointer): n doubles.
inline double* pass_buffer(std::size_t n, PassBuffer which) {
  static thread_local std::vector<double> buffers[static_cast<int>(PassBuffer::count)];
  auto& buffer = buffers[static_cast<int>(which)];
  buffer.resize(n);
  return buffer.data();
}

/// s0_i = s00 - alpha s_min for the next step (alpha > 0), from each particle's smallest stretch
/// (max(): no intact bond, s0 kept).
template <int D>
void next_stretch_limits(Model<D>& m, const BodyInfo& body, const double* smallest) {
  const auto& c = body.constants;
  if (c.alpha <= 0.0) return;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i)
    if (smallest[i] < std::numeric_limits<double>::max()) m.next_stretch_limit[i] = c.critical_stretch - c.alpha * smallest[i];
}

/// How the particles [first, last) of a body are cut into slabs (BodyInfo::slab_length, slab_count).
struct SlabCut {
  std::size_t length = 1, count = 1;
};

/// The slabs of the particles [first, last): `count` slabs, each but the last `length` long, at
/// least the farthest forward reach, and more slabs than a few threads need for balance on large
/// bodies; the last takes the rest. Found once, when the bonds are made (BodyInfo): scanned in every
/// pass, it took 4% of a PMB step.
inline SlabCut cut_into_slabs(const Bonds& b, std::size_t first, std::size_t last) {
  const std::size_t count = last - first;
  // the farthest forward reach, and `forward[p]`: the forward bonds of the first p particles
  std::vector<std::int64_t> forward(count + 1, 0);
  std::size_t reach = 1;
#pragma omp parallel for if(rift::parallel::worth_a_team(count)) schedule(static) reduction(max : reach)
  for (std::size_t i = first; i < last; ++i) {
    forward[i - first + 1] = b.offset[i + 1] - first_forward_bond(b, i);
    if (b.offset[i + 1] > b.offset[i]) {
      const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(b.offset[i + 1] - 1)]);
      if (j > i) reach = std::max(reach, j - i);
    }
  }
  std::partial_sum(forward.begin(), forward.end(), forward.begin());
  std::size_t length = std::max(reach, (count + 255) / 256);
  // the slabs of each parity shared evenly by a team of two or four: their number a multiple of
  // eight where that keeps a slab at least the reach long (27 slabs would leave one of two threads
  // 7 of a parity's 14 and the other 6, then waiting). Not the team's size itself: the slabs order
  // the sums, which must not depend on it. Under sixteen slabs a multiple of four: the bench cube
  // (41^3, horizon 3 spacings: 13 slabs) then has 12, three a thread and parity on two threads
  // instead of two, so a thread slowed for a while by the rest of the machine holds the other back
  // for less (bench/README.md). A team of four then gets two slabs or one a parity, not one.
  std::size_t slabs = (count + length - 1) / length;
  const std::size_t multiple = slabs >= 16 ? 8 : 4;
  if (slabs >= multiple && slabs % multiple != 0) {
    length = (count + slabs / multiple * multiple - 1) / (slabs / multiple * multiple);
    // the slabs of that length: fewer than the multiple where a slab holds fewer particles than there
    // are slabs (a strip three particles wide and 1,000 long has 231 of 13, not 248)
    slabs = (count + length - 1) / length;
  }
  if (slabs < 2) return {std::max<std::size_t>(length, 1), 1};
  // A slab's work is its rows' forward bonds, and the rows of the last slab lose theirs past the
  // body's end: in equal slabs the bench cube's last has two thirds of the others' forward bonds,
  // and the thread that takes it waits for the other in every pass of odd slabs. So the others are
  // made shorter, down to the reach, until the last, which takes the rest, has the forward bonds of
  // an average other (the cube's slabs 5,581 particles, not 5,744, its last 7,530; the thesis-size
  // lattice's 85,796, not 86,944, its last 115,516; bench/README.md).
  const auto shortfall = [&](std::size_t l) {  // the last slab's forward bonds less an average other's, times (slabs - 1)
    const std::size_t cut = (slabs - 1) * l;
    return (forward[count] - forward[cut]) * static_cast<std::int64_t>(slabs - 1) - forward[cut];
  };
  const std::size_t equal = length;  // (slabs - 1) equal < count: the last slab holds a particle or more
  for (; length > reach && shortfall(length) < 0; --length) {
  }
  // the length whose last slab comes nearer an average other: this one or the one above
  if (length < equal && std::abs(shortfall(length + 1)) < std::abs(shortfall(length))) ++length;
  return {length, slabs};
}

/// The whole body's slab of its particle with whole-run number `whole` (Numbering::whole).
inline std::size_t slab_of(const BodyInfo& body, std::size_t whole) {
  return std::min((whole - body.whole_first) / body.slab_length, body.slab_count - 1);
}

/// Calls slab(q) for the local slabs q = 0 ... count - 1, whose whole-body numbers are first_slab + q
/// (BodyInfo::first_slab): slab q writes its own particles and the next slab's, so it must not run
/// beside q - 1 or q + 1. Each even slab (whole-body parity) comes before its odd neighbours, as one
/// sweep of the even slabs and then one of the odd ones would do: each particle gets its sums in the
/// same order on any thread count. An odd slab waits only until its two even neighbours are done, not
/// for every even slab: a barrier between the two sweeps would keep a thread that ends its even
/// slabs early waiting.
/// A team's thread t owns the t-th of equal blocks of consecutive slabs, as a static schedule over
/// the particles splits them (kick, drift, the passes' copies), and takes its own even slabs, then
/// what is left of the others' even ones, then its odd ones and the others'. So a slab runs where
/// its particles were last moved and summed, and where the next pass finds them: slabs handed out
/// from one counter would move every other slab's particles to the other core each pass, dear where
/// the two cores share no L3 cache (bench/README.md). A thread slowed by the rest of the machine
/// still holds the other back for at most a slab: the other takes what is left of its block.
template <class Slab>
void for_each_slab(std::size_t count, std::size_t first_slab, bool team, Slab&& slab) {
  const std::size_t skip = first_slab % 2;  // local number of the first even slab
  if (!team || count < 3) {
    for (std::size_t q = skip; q < count; q += 2) slab(q);
    for (std::size_t q = 1 - skip; q < count; q += 2) slab(q);
    return;
  }
  const auto done = std::make_unique<std::atomic<bool>[]>(count);
  for (std::size_t q = 0; q < count; ++q) done[q].store(false, std::memory_order_relaxed);
  const auto wait_for = [&](std::size_t q) {
    for (int spins = 0; !done[q].load(std::memory_order_acquire); ++spins)
      if (spins > 1000) std::this_thread::yield();  // its thread may be descheduled (a shared CPU)
  };
  const auto take = [&](std::size_t q) {
    if ((q + skip) % 2 == 1) {  // an odd slab: after its even neighbours, every one handed out before it
      if (q > 0) wait_for(q - 1);
      if (q + 1 < count) wait_for(q + 1);
    }
    slab(q);
    done[q].store(true, std::memory_order_release);
  };
  // the blocks: [count t / threads, count (t + 1) / threads), each handing out its even and its odd
  // slabs ascending
  struct alignas(64) Block {
    std::atomic<std::size_t> next[2];  // the block's next even and next odd slab
    std::size_t end = 0;
  };
  const auto threads = static_cast<std::size_t>(omp_get_max_threads());
  const auto blocks = std::make_unique<Block[]>(threads);
  for (std::size_t t = 0; t < threads; ++t) {
    const std::size_t first = count * t / threads;
    const bool odd_first = (first + skip) % 2 == 1;
    blocks[t].next[0].store(first + odd_first, std::memory_order_relaxed);
    blocks[t].next[1].store(first + !odd_first, std::memory_order_relaxed);
    blocks[t].end = count * (t + 1) / threads;
  }
#pragma omp parallel num_threads(static_cast<int>(threads))
  {
    // a thread goes on to the odd slabs once every even one is handed out: the even slabs an odd one
    // waits for are being done
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    for (std::size_t parity = 0; parity < 2; ++parity)
      for (std::size_t k = 0; k < threads; ++k) {
        Block& b = blocks[(t + k) % threads];
        for (std::size_t q; (q = b.next[parity].fetch_add(2, std::memory_order_relaxed)) < b.end;) take(q);
      }
  }
}

/// Calls row(i) for every particle of the body, slab by slab as above (`numbering`: a distributed
/// run's window's, pd/window.hpp).
template <class Row>
void for_each_row_by_slabs(const BodyInfo& body, const Numbering& numbering, Row&& row) {
  const std::size_t first = body.first, last = body.last, length = body.slab_length;
  if (last <= first) return;
  // the whole body's slabs (BodyInfo::whole_first): the first here may be cut short, and start
  // before the window's first particle (a distributed run's window, pd/window.hpp); the last takes
  // the rest of the body
  const auto start = [&](std::size_t slab) { return slab < body.slab_count ? numbering.first_from(body.whole_first + slab * length) : last; };
  const std::size_t first_slab = slab_of(body, numbering.whole(first));
  const std::size_t end_slab = slab_of(body, numbering.whole(last - 1)) + 1;
  for_each_slab(end_slab - first_slab, first_slab, rift::parallel::worth_a_team(last - first), [&](std::size_t q) {
    const std::size_t slab = first_slab + q;
    const std::size_t from = std::max(first, start(slab)), to = std::min(last, start(slab + 1));
    for (std::size_t i = from; i < to; ++i) row(i);
  });
}

}  // namespace rift::pd
