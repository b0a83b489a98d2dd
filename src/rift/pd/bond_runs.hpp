// Runs of bonds: the forward bonds of a body (bond_slabs.hpp) grouped so that a pass takes many at
// once. On a lattice numbered x fastest, consecutive particles along a line have the same family,
// so the bonds of one family offset from particles i, i + 1, ..., i + L - 1 go to j, j + 1, ...,
// j + L - 1. Their positions, stretch limits and forces are then contiguous on both ends, and the
// pair forces of a run are a loop the compiler turns into vector instructions (two, four or eight
// bonds per instruction) where a row's loop gathers every neighbour. A run stays inside one slab, so
// the slabs' even-odd order keeps the passes free of races, and its sums are made in an order that
// depends on the bonds alone. The bonds' states stay in their rows: a pass looks at them only for a
// run with a row that is not whole (intact_rows), by the run's place in the rows where the rows
// have it in common (inside the body), else by a search.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The longest run: a pass's buffers for one run live on the stack.
inline constexpr std::size_t max_run_length = Bonds::history_block;

/// Runs shorter than this are taken bond by bond: a vector's set-up would cost more.
inline constexpr std::size_t short_run = 4;

/// The widest vector a clone may use (eight doubles; core/vector_isa.hpp). A run whose upper ends
/// start at least this far past its lower ends (j - i, or past the run's end) can add to both ends
/// in one loop, in vectors (omp simd safelen): an end that is both a lower end and, further on, an
/// upper end of the run is never in one vector twice, and takes its two terms in the bonds' order.
inline constexpr std::size_t simd_ends_apart = 8;

/// Whether a run's ends lie apart in vectors (simd_ends_apart).
inline bool ends_apart_in_vectors(const BondRun& run) {
  const auto distance = static_cast<std::int64_t>(run.j) - static_cast<std::int64_t>(run.i);
  return distance >= static_cast<std::int64_t>(std::min<std::size_t>(run.length, simd_ends_apart));
}

/// Groups the body's forward bonds into runs (after its bonds and slab length are made): every
/// forward bond belongs to exactly one run. A distributed run's window (pd/window.hpp) gives its
/// numbering: its runs are the whole run's, cut to the window, and none spans a jump of the
/// numbering.
inline void make_bond_runs(const Bonds& b, BodyInfo& body, const Numbering& numbering = {}) {
  body.runs.clear();
  body.slab_runs.clear();
  if (body.last <= body.first) return;
  // the slabs are the whole body's (BodyInfo::whole_first)
  auto slab = [&](std::size_t i) { return slab_of(body, numbering.whole(i)); };
  // and inside one block of the VES history (bonds.hpp), which holds max_run_length particles: the
  // whole body's blocks too (a window's history holds whole blocks, BodyInfo::origin)
  auto block = [&](std::size_t i) { return (numbering.whole(i) - body.whole_first) / max_run_length; };
  body.first_slab = slab(body.first);
  // Runs never cross a slab, so the slabs are made apart, in parallel. whole(i) ascends with i
  // (numbering.hpp), so each slab's particles are one range: [slab_first[q], slab_first[q + 1]).
  const std::size_t slabs = slab(body.last - 1) + 1 - body.first_slab;
  std::vector<std::size_t> slab_first(slabs + 1, body.last);
  for (std::size_t i = body.last; i-- > body.first;) slab_first[slab(i) - body.first_slab] = i;
  for (std::size_t q = slabs; q-- > 0;) slab_first[q] = std::min(slab_first[q], slab_first[q + 1]);
  std::vector<std::vector<BondRun>> runs_of(slabs);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(dynamic, 1)
  for (std::size_t q = 0; q < slabs; ++q) {
    std::vector<BondRun>& runs = runs_of[q];
    std::vector<std::int64_t> open(body.family_count, -1);  // per family offset: the run that may grow
    for (std::size_t i = slab_first[q]; i < slab_first[q + 1]; ++i)
      for (auto k = first_forward_bond(b, i); k < b.offset[i + 1]; ++k) {
        const auto position = static_cast<std::uint32_t>(k - b.offset[i]);
        const auto family = b.family[static_cast<std::size_t>(k)];
        const auto j = b.neighbor[static_cast<std::size_t>(k)];
        auto& o = open[family - body.first_family];
        if (o >= 0) {
          BondRun& r = runs[static_cast<std::size_t>(o)];
          if (static_cast<std::size_t>(r.i) + r.length == i && r.j + r.length == j && block(static_cast<std::size_t>(r.i)) == block(i) &&
              numbering.whole(static_cast<std::size_t>(r.i)) + r.length == numbering.whole(i) &&
              numbering.whole(static_cast<std::size_t>(r.j)) + r.length == numbering.whole(static_cast<std::size_t>(j))) {
            if (r.position != position) r.position = BondRun::varies;
            ++r.length;
            continue;
          }
        }
        o = static_cast<std::int64_t>(runs.size());
        runs.push_back({static_cast<std::int32_t>(i), j, position, family, 1});
      }
    // inside the slab block by block, and in a block family by family, in particle order: a pass
    // then takes the VES history (bonds.hpp, by block and family offset) as one stream, and a
    // block's particles (a few kB) stay in the cache over its families. (The slab's runs are made
    // in the order one pass over the body made them, so the order is that of one sort of all.)
    std::stable_sort(runs.begin(), runs.end(), [&](const BondRun& a, const BondRun& c) {
      const auto ia = static_cast<std::size_t>(a.i), ic = static_cast<std::size_t>(c.i);
      if (block(ia) != block(ic)) return block(ia) < block(ic);
      if (a.family != c.family) return a.family < c.family;
      return ia < ic;
    });
  }
  // each slab's runs together, slab after slab
  body.slab_runs.assign(slabs + 1, 0);
  for (std::size_t q = 0; q < slabs; ++q) body.slab_runs[q + 1] = body.slab_runs[q] + runs_of[q].size();
  body.runs.resize(body.slab_runs[slabs]);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(dynamic, 1)
  for (std::size_t q = 0; q < slabs; ++q)
    std::copy(runs_of[q].begin(), runs_of[q].end(), body.runs.begin() + static_cast<std::ptrdiff_t>(body.slab_runs[q]));
}

/// Which bonds of each row are intact, for the runs' masks (mask_run): per particle of the body,
/// whether its row is whole (every bond intact: the bonds' states are 1 or less for a broken bond, 2
/// for a failed interface bond, so their AND is 1 only when all are 1; a run of whole rows needs no
/// look at its bonds' states), and for the rows that are not, a bit per family offset of the body
/// (where it has at most 64 x max_row_words = 512: a horizon of 3 spacings has 122 in 3D with
/// LAMMPS's partial volumes, 250 with the default's), set where that bond is intact.
/// Made from the states only where they changed (whole_rows); after a pass that broke bonds, those
/// of the bonds it broke made again (refresh_rows) for the force pass and the VES sums (ves.hpp).
inline constexpr std::size_t max_row_words = 8;
struct RowStates {
  std::uint8_t* whole = nullptr;
  // offsets 64 w to 64 w + 63 of particle i at intact[w stride + i] (a run's rows one word after the
  // next); null: the body has more offsets
  std::uint64_t* intact = nullptr;
  std::size_t stride = 0, words = 0;
  std::size_t first_family = 0;
  std::size_t family_count = 0;
  std::uint64_t version = 0;  // the version of the bond states the rows are (BondStates::version)
  explicit operator bool() const { return whole != nullptr; }
};

/// Bit t of bits (bit t & 63 of bits[t / 64]) set where state[t] is bond_intact, t < count <= 64 x
/// max_row_words. The states are 0, 1 or 2, so bit 0 of a state says intact; eight states at a
/// time, their bits 0 gathered into one byte by a multiply (the eight partial products land on
/// distinct bits of the top byte), without the branch per bond that a row's random breaks mispredict.
inline void intact_bits(const std::uint8_t* state, std::size_t count, std::uint64_t* bits) {
  static_assert(bond_intact == 1 && bond_broken == 0 && bond_interface_failed == 2);
  constexpr std::uint64_t low_bits = 0x0101010101010101ull, gather = 0x0102040810204080ull;
  std::size_t t = 0;
  for (; t + 8 <= count; t += 8) {
    std::uint64_t u;
    std::memcpy(&u, state + t, sizeof u);
    bits[t >> 6] |= ((u & low_bits) * gather >> 56) << (t & 63);
  }
  for (; t < count; ++t) bits[t >> 6] |= std::uint64_t{state[t] & 1u} << (t & 63);
}

/// The AND of row i's states: bond_intact exactly when every bond of the row is (RowStates).
inline std::uint8_t row_whole(const Bonds& b, std::size_t i) {
  std::uint8_t all = bond_intact;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) all &= b.intact[static_cast<std::size_t>(k)];
  return all;
}

/// Row i of rows from its bonds' states.
inline void make_row_state(const Bonds& b, const RowStates& rows, std::size_t i) {
  const std::uint8_t* const state = b.intact.data();
  const std::int64_t first = b.offset[i], last = b.offset[i + 1];
  const std::uint8_t all = row_whole(b, i);
  rows.whole[i] = all;
  if (!rows.intact || all == bond_intact) return;
  std::uint64_t word[max_row_words] = {};
  if (static_cast<std::size_t>(last - first) == rows.family_count) {
    // a whole family: its rows' families ascend, so the bond's place is its offset
    intact_bits(state + first, rows.family_count, word);
  } else {
    for (auto k = first; k < last; ++k)
      if (state[k] == bond_intact) {
        const std::size_t f = b.family[static_cast<std::size_t>(k)] - rows.first_family;
        word[f >> 6] |= std::uint64_t{1} << (f & 63);
      }
  }
  for (std::size_t w = 0; w < rows.words; ++w) rows.intact[w * rows.stride + i] = word[w];
}

/// The rows of the body's particles, kept with the bonds (Bonds::kept_rows, indexed by particle, so
/// the rows of every body of the model stay valid together) and made again, in parallel, only where
/// the states changed since they were made (BondStates::version): a step that breaks nothing reads
/// no bond's state (8.4 MB a step on the 41^3 bench cube, on every step of PMB, LPS and VES).
inline RowStates whole_rows(const Bonds& b, const BodyInfo& body) {
  Bonds::KeptRows& kept = b.kept_rows;
  const std::size_t stride = b.offset.size();
  const std::size_t words = (body.family_count + 63) / 64;
  const bool bits = words <= max_row_words;
  if (kept.whole.size() != stride) kept.whole.resize(stride), kept.made.clear();
  if (bits && kept.intact.size() < words * stride) kept.intact.resize(words * stride);  // never shrinks: another body's rows may be in use
  const RowStates rows{kept.whole.data(), bits ? kept.intact.data() : nullptr, stride, bits ? words : 0, body.first_family, body.family_count,
                       b.intact.version()};
  const auto same = [&](const Bonds::KeptRows::Made& r) { return r.first == body.first && r.last == body.last; };
  const auto made = std::find_if(kept.made.begin(), kept.made.end(), same);
  if (made != kept.made.end() && made->version == b.intact.version()) return rows;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) make_row_state(b, rows, i);
  std::erase_if(kept.made, [&](const Bonds::KeptRows::Made& r) { return r.first < body.last && body.first < r.last; });
  kept.made.push_back({body.first, body.last, b.intact.version(), rows.words});
  return rows;
}

/// The intact and broken bonds of row i (intact | broken << 32, as hf/fluid_network.hpp
/// count_bond_states counts them) from the rows r kept at the states' version now (whole_rows),
/// where every state is intact or broken (no interface law): 17 bytes a particle read, where its
/// states are a byte a bond (a thesis-size step's counts read 509 MB). False where r does not hold
/// the row's bits.
inline bool kept_row_count(const Bonds& b, const Bonds::KeptRows::Made& r, std::size_t i, std::uint64_t& count) {
  const Bonds::KeptRows& kept = b.kept_rows;
  const auto length = static_cast<std::uint64_t>(b.offset[i + 1] - b.offset[i]);
  if (kept.whole[i] == bond_intact) {
    count = length;
    return true;
  }
  const std::size_t stride = b.offset.size();
  if (r.words == 0 || kept.intact.size() < r.words * stride) return false;
  std::uint64_t intact = 0;
  for (std::size_t w = 0; w < r.words; ++w) intact += static_cast<std::uint64_t>(std::popcount(kept.intact[w * stride + i]));
  count = intact | (length - intact) << 32;
  return true;
}

/// Makes the rows of both ends of the bonds `broken` ((i, k) of a row) again, after a pass broke
/// them (a few rows, where whole_rows reads every bond's state): the body's rows, current before the
/// pass, are then those of the states as the pass left them, `broken` being all it changed.
inline void refresh_rows(const Bonds& b, const BodyInfo& body, const RowStates& rows,
                         const std::vector<std::pair<std::size_t, std::int64_t>>& broken) {
  if (broken.empty()) return;
  // both ends marked, then the body's marked rows made again, by the team (where a sorted list of
  // the ends was made on one thread: a million at the thesis size)
  static thread_local std::vector<std::uint8_t> marks;  // all 0 between calls; the calling thread's, the team's through the pointer
  marks.resize(b.offset.size(), 0);
  std::uint8_t* const marked = marks.data();
#pragma omp parallel for if(rift::parallel::worth_a_team(broken.size())) schedule(static)
  for (std::size_t q = 0; q < broken.size(); ++q) {
    std::atomic_ref<std::uint8_t>(marked[broken[q].first]).store(1, std::memory_order_relaxed);
    std::atomic_ref<std::uint8_t>(marked[static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(broken[q].second)])])
        .store(1, std::memory_order_relaxed);
  }
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i)
    if (marked[i]) make_row_state(b, rows, i), marked[i] = 0;
  for (auto& r : b.kept_rows.made)
    if (r.first == body.first && r.last == body.last && r.version == rows.version) r.version = b.intact.version();
}

/// The intact bonds of row i (its whole length, or the bits of its intact offsets).
inline std::int32_t intact_bond_count(const Bonds& b, const RowStates& rows, std::size_t i) {
  const auto length = static_cast<std::int32_t>(b.offset[i + 1] - b.offset[i]);
  if (rows.whole[i] == bond_intact) return length;
  if (rows.intact) {
    std::int32_t count = 0;
    for (std::size_t w = 0; w < rows.words; ++w) count += std::popcount(rows.intact[w * rows.stride + i]);
    return count;
  }
  std::int32_t count = 0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) count += b.intact[static_cast<std::size_t>(k)] == bond_intact;
  return count;
}

/// Whether the rows [i, i + length) are whole (whole_rows).
inline bool whole_run(const std::uint8_t* __restrict whole, std::size_t length) {
  std::uint8_t all = 1;
  for (std::size_t t = 0; t < length; ++t) all &= whole[t];
  return all != 0;
}

/// The index of bond t of the run in its row.
inline std::int64_t run_bond(const Bonds& b, const BondRun& run, std::size_t t) {
  const std::size_t i = static_cast<std::size_t>(run.i) + t;
  if (run.position != BondRun::varies) return b.offset[i] + run.position;
  const auto first = b.neighbor.begin() + b.offset[i], last = b.neighbor.begin() + b.offset[i + 1];
  return std::lower_bound(first, last, static_cast<std::int32_t>(run.j + static_cast<std::int32_t>(t))) - b.neighbor.begin();
}

/// Whether bond t of a run is intact: from the rows' states where they hold the bits of its row (a
/// whole row, or the bit of the run's offset), else from its own state (found in its row: a search
/// where the run's place in its rows varies, at a body's surfaces, which short runs mostly are).
inline bool run_bond_intact(const Bonds& b, const BondRun& run, const RowStates& rows, std::size_t t) {
  const std::size_t i = static_cast<std::size_t>(run.i) + t;
  if (rows.whole[i] == bond_intact) return true;
  if (rows.intact) {
    const std::size_t f = run.family - rows.first_family;
    return (rows.intact[(f >> 6) * rows.stride + i] >> (f & 63) & 1u) != 0;
  }
  return b.intact[static_cast<std::size_t>(run_bond(b, run, t))] == bond_intact;
}

/// Whether any of the flags (1.0 or 0.0) is set; read as bits, so that the loop is vector code (a
/// loop that compares the doubles is not).
[[gnu::always_inline]] inline bool any_set(const double* __restrict flags, std::size_t length) {
  std::uint64_t bits = 0;
  for (std::size_t t = 0; t < length; ++t) {
    std::uint64_t u;
    std::memcpy(&u, flags + t, sizeof u);
    bits |= u;
  }
  return bits != 0;
}

/// Where a masked run's kernel finds which of its bonds are intact (mask_run): the bits of the
/// rows' intact offsets, one word per bond of the run at the run's family offset's bit, with the
/// rows' whole flags; or, where the rows hold no bits, `alive` made by the caller from the states.
struct RunMask {
  const std::uint64_t* words = nullptr;
  const std::uint8_t* whole = nullptr;
  unsigned bit = 0;
  const double* alive = nullptr;
};

/// Whether the run has a row that is not whole (RowStates); then `mask` says where its intact bonds
/// are read from: the bits of the rows' intact offsets, one row after the next; each row's own states
/// (and where the rows do not share the bonds' place, its neighbours, to find it) would take a cache
/// line per bond, in the damaged rows around the thesis-size perforation a fifth of the bond passes.
/// Where the rows hold no bits, alive[t] is made here from the states (1 intact, 0 not).
inline bool run_mask(const Bonds& b, const BondRun& run, const RowStates& rows, double* alive, RunMask& mask) {
  const std::uint8_t* const whole = rows.whole + run.i;
  if (whole_run(whole, run.length)) return false;
  if (rows.intact) {
    const std::size_t f = run.family - rows.first_family;
    mask = {rows.intact + (f >> 6) * rows.stride + static_cast<std::size_t>(run.i), whole, static_cast<unsigned>(f & 63), nullptr};
    return true;
  }
  for (std::size_t t = 0; t < run.length; ++t) alive[t] = b.intact[static_cast<std::size_t>(run_bond(b, run, t))] == bond_intact ? 1.0 : 0.0;
  mask = {nullptr, nullptr, 0, alive};
  return true;
}

/// The mask of a run (run_mask) as the kernels' Masked form reads it: alive[t] 1 for an intact bond
/// and 0 for another, made from the bits into `buffer` (in the calling kernel's clone, so in its
/// vectors, without a branch: a whole row has every bit), or the caller's. Returns whether any bond
/// is intact (none: the run adds nothing).
[[gnu::always_inline]] inline bool alive_from_mask(const RunMask& mask, std::size_t length, double* __restrict buffer, const double*& alive) {
  if (!mask.words) {
    alive = mask.alive;
    return any_set(mask.alive, length);
  }
  const std::uint64_t* __restrict const words = mask.words;
  const std::uint8_t* __restrict const whole = mask.whole;
  const unsigned bit = mask.bit;
  std::uint32_t any = 0;
  for (std::size_t t = 0; t < length; ++t) {
    const std::uint32_t on = (static_cast<std::uint32_t>(words[t] >> bit) | whole[t]) & 1u;
    any |= on;
    buffer[t] = static_cast<double>(static_cast<std::int32_t>(on));
  }
  alive = buffer;
  return any != 0;
}

/// Whether the VES force kernel takes only the spans of a masked run that hold an intact bond
/// (RunSpans, lps_runs.hpp): on, but for tests, which compare with every bond taken.
inline bool& skip_broken_spans() {
  static bool skip = true;
  return skip;
}

/// A masked run's bonds [0, length) cut at `first` and then every `width` bonds, the consecutive
/// pieces that hold an intact bond merged, and so those that hold none: span c is [at[c], at[c + 1]),
/// live[c] whether it holds an intact bond. A kernel may take the live spans alone: a broken bond adds
/// nothing (and keeps its VES history), so a dead span's bonds need neither their arithmetic nor their
/// memory (in a shattered block most runs that are not all broken have such spans). Only the VES
/// force kernel does, for its history: in the dilatation kernel, whose memory is the particles',
/// the spans gained nothing.
struct RunSpans {
  static constexpr std::size_t most = max_run_length / 8 + 2;  // width at least 8
  std::size_t count = 0;
  std::size_t at[most + 1];
  bool live[most];
};
[[gnu::always_inline]] inline void cut_run_spans(const double* __restrict alive, std::size_t length, std::size_t first, std::size_t width,
                                                 RunSpans& spans) {
  spans.count = 0;
  spans.at[0] = 0;
  for (std::size_t s = 0, e = first < length ? first : length; s < length; s = e, e = e + width < length ? e + width : length) {
    const bool live = any_set(alive + s, e - s);
    if (spans.count == 0 || spans.live[spans.count - 1] != live) spans.live[spans.count++] = live;
    spans.at[spans.count] = e;
  }
}

/// Whether the run has a row that is not whole (run_mask); then alive[t] is 1 for its intact bonds
/// and 0 for the others, for the passes whose kernels take alive[] made (PMB, the energy sums).
inline bool mask_run(const Bonds& b, const BondRun& run, const RowStates& rows, double* alive) {
  RunMask mask;
  if (!run_mask(b, run, rows, alive, mask)) return false;
  const double* made = nullptr;
  alive_from_mask(mask, run.length, alive, made);
  return true;
}

/// Bond t of a run as a row takes it: its ends i and j and its deformed vector y_j - y_i from the
/// per-component positions x (positions_by_component); its index in i's row is run_bond's.
template <int D>
struct RunEnds {
  std::size_t i, j;
  Vec<D> eta;
};
template <int D>
RunEnds<D> run_ends_at(const BondRun& run, std::size_t t, const std::array<double*, 3>& x) {
  RunEnds<D> bond{static_cast<std::size_t>(run.i) + t, static_cast<std::size_t>(run.j) + t, {}};
  for (int q = 0; q < D; ++q) bond.eta[q] = x[static_cast<std::size_t>(q)][bond.j] - x[static_cast<std::size_t>(q)][bond.i];
  return bond;
}

/// The deformed vector (ex, ey, ez; ez = 0 in 2D) of bond t of a run from its ends' per-component
/// positions (the lower ends' at a, the upper ends' at b); returns its squared length.
template <int D>
[[gnu::always_inline]] inline double run_bond_vector(const double* __restrict xa, const double* __restrict ya, const double* __restrict za,
                                                     const double* __restrict xb, const double* __restrict yb, const double* __restrict zb,
                                                     std::size_t t, double& ex, double& ey, double& ez) {
  ex = xb[t] - xa[t], ey = yb[t] - ya[t], ez = 0.0;
  double r2 = ex * ex + ey * ey;
  if constexpr (D == 3) {
    ez = zb[t] - za[t];
    r2 += ez * ez;
  }
  return r2;
}

/// The particles' positions one array per component (the runs read them contiguously): the calling
/// thread's buffers (pass_buffer position_x to position_z), which the team reads through the pointers.
template <int D>
std::array<double*, 3> positions_by_component(const std::vector<Vec<D>>& position, const BodyInfo& body) {
  std::array<double*, 3> x{};
  for (int q = 0; q < D; ++q) x[static_cast<std::size_t>(q)] = pass_buffer(position.size(), component(PassBuffer::position_x, q));
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j)
    for (int q = 0; q < D; ++q) x[static_cast<std::size_t>(q)][j] = position[j][q];
  return x;
}

/// Calls run(r) for every run of the body, slab by slab as for_each_row_by_slabs does (for_each_slab:
/// each even slab before its odd neighbours).
template <class Run>
void for_each_run_by_slabs(const BodyInfo& body, Run&& run) {
  if (body.slab_runs.size() < 2) return;
  for_each_slab(body.slab_runs.size() - 1, body.first_slab, rift::parallel::worth_a_team(body.last - body.first), [&](std::size_t slab) {
    for (std::size_t r = body.slab_runs[slab]; r < body.slab_runs[slab + 1]; ++r) run(body.runs[r]);
  });
}

/// What a run's pair forces add to its particles: f_i += g on the lower ends, f_j -= g on the upper
/// ones (called with f + i and f + j), and the smallest stretch of each end. Separate loops for the two
/// ends: a run's ends overlap where the offset moves along the line by less than the run.
[[gnu::always_inline]] inline void add_to_run_ends(double* __restrict f, const double* __restrict g, std::size_t length) {
  for (std::size_t t = 0; t < length; ++t) f[t] += g[t];
}
[[gnu::always_inline]] inline void subtract_from_run_ends(double* __restrict f, const double* __restrict g, std::size_t length) {
  for (std::size_t t = 0; t < length; ++t) f[t] -= g[t];
}
[[gnu::always_inline]] inline void lower_to_run_stretches(double* __restrict smallest, const double* __restrict s, std::size_t length) {
  for (std::size_t t = 0; t < length; ++t) smallest[t] = s[t] < smallest[t] ? s[t] : smallest[t];
}

/// Where a run kernel's pair forces go, bond t's g (per component, the force on the lower end;
/// the upper end takes -g) and its stretch s (`none`: adds nothing; Stretch: the kernel keeps the
/// ends' smallest stretches), for a run whose ends may share a vector: into buffers, which
/// add_pair_forces_to_run_ends and lower_to_run_stretches then add to the ends, loop after loop.
template <int D, bool Stretch>
struct PairForcesToBuffers {
  double *gx, *gy, *gz, *stretch;
  [[gnu::always_inline]] void operator()(std::size_t t, double x, double y, double z, double s) const {
    gx[t] = x, gy[t] = y;
    if constexpr (D == 3) gz[t] = z;
    if constexpr (Stretch) stretch[t] = s;
  }
};

/// The same straight to the ends (a run whose ends lie apart in vectors: ends_apart_in_vectors), so
/// that each end takes its terms in the bonds' order (the kernel's loop is omp simd
/// safelen(simd_ends_apart)).
template <int D, bool Stretch>
struct PairForcesToEnds {
  double *fxa, *fya, *fza, *fxb, *fyb, *fzb, *smallest_a = nullptr, *smallest_b = nullptr;
  template <class RunArguments>
  explicit PairForcesToEnds(const RunArguments& a) : fxa(a.fxa), fya(a.fya), fza(a.fza), fxb(a.fxb), fyb(a.fyb), fzb(a.fzb) {
    if constexpr (Stretch) smallest_a = a.smallest_a, smallest_b = a.smallest_b;
  }
  [[gnu::always_inline]] void operator()(std::size_t t, double x, double y, double z, double s) const {
    fxa[t] += x, fya[t] += y;
    fxb[t] -= x, fyb[t] -= y;
    if constexpr (D == 3) fza[t] += z, fzb[t] -= z;
    if constexpr (Stretch) {
      smallest_a[t] = s < smallest_a[t] ? s : smallest_a[t];
      smallest_b[t] = s < smallest_b[t] ? s : smallest_b[t];
    }
  }
};

/// What a run's pair forces g (per component) add to its ends: +g to the lower ends' forces, -g to
/// the upper ends' (the fxa ... fzb of a kernel's arguments `a`).
template <int D, class RunArguments>
[[gnu::always_inline]] inline void add_pair_forces_to_run_ends(const RunArguments& a, const double (&g)[3][max_run_length]) {
  add_to_run_ends(a.fxa, g[0], a.length);
  add_to_run_ends(a.fya, g[1], a.length);
  if constexpr (D == 3) add_to_run_ends(a.fza, g[2], a.length);
  subtract_from_run_ends(a.fxb, g[0], a.length);
  subtract_from_run_ends(a.fyb, g[1], a.length);
  if constexpr (D == 3) subtract_from_run_ends(a.fzb, g[2], a.length);
}

}  // namespace rift::pd
