// A rank's share of a distributed peridynamic run. The particles are numbered body after body, each
// body's lattice x fastest, so a contiguous range of the numbering is a stack of lattice layers: the
// ranks own consecutive ranges (a processor grid of 1 x 1 x P along the lattice's slowest axis),
// balanced by bonds, or boxes of a 1 x P x Q grid (pencils along x), one range per layer each. A rank holds its owned range and, around it, every particle within the bonds'
// reach of it (ghosts): the window. Its bond passes take the whole run's runs and slabs cut to the
// window (BodyInfo::origin), so every sum of an owned particle is made in the same order as on one
// rank, and the run is bitwise the same on any number of ranks.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "rift/core/index_range.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

struct Partition {
  // each rank's owned particles and its window, as ranges of the whole run's numbering (ascending;
  // a slab's one each)
  std::vector<std::vector<IndexRange>> owned, window;
  std::size_t reach = 0;  // slabs: the farthest bond in the numbering, max |i - j|
};

/// Cuts the model's particles into `ranks` consecutive ranges of about equal bond counts, each cut
/// at a lattice line's start (Model::continues_line; a rank may own none where there are more
/// ranks than lines). Each window reaches `reaches` times the
/// bonds' reach past its owned range: one for the bond passes; a fluid whose cracks grow reads
/// further (hf/window_fluid.hpp fluid_ghost_reaches).
template <int D>
Partition partition_by_bonds(const Model<D>& m, int ranks, std::size_t reaches = 1);

/// Cuts the particles of a 3D model into a processor grid of 1 x `across_y` x `across_z` boxes,
/// pencils along x: across z by the lattice's layers into parts of about equal bond counts, then
/// each part across y by its lattice lines the same way (rank = z part * across_y + y part). A
/// rank's owned particles are one range of the numbering per layer of each body (x is its fastest
/// axis). Its window: the particles within `reaches` longest bonds of its owned box across y and z,
/// grown to hold whole bond runs (with_whole_runs) and, in a VES body, whole blocks of its history
/// (Bonds::history_block). A 2D model's 1 x P grid is partition_by_bonds' slabs.
template <int D>
Partition partition_into_pencils(const Model<D>& m, int across_y, int across_z, std::size_t reaches = 1);

/// The processor grid 1 x P x Q (P Q = ranks) whose ranks hold the fewest ghosts, estimated from
/// the lattice's lines across y, layers across z and the bonds' reach: {1, ranks} (slabs) unless a
/// cut across y holds fewer (a flat plate, many ranks on a cube). A 2D model's is {1, ranks}.
template <int D>
std::array<int, 2> choose_pencils(const Model<D>& m, int ranks);

/// `window` (ranges of the whole numbering, holding every neighbour of the `owned` particles) grown
/// to hold both ends of every pair of each of the whole model's bond runs (bond_runs.hpp) with an
/// owned end: a run cut by the window would add a particle's two terms of one run (it is the lower
/// end of one pair, the upper end of another) in another order, in the vector form or the pair by
/// pair one. The window's runs with an owned end are then the whole run's, in its order.
template <int D>
std::vector<IndexRange> with_whole_runs(const Model<D>& m, const std::vector<IndexRange>& owned, std::vector<IndexRange> window);

/// Rank r's window of the whole model: its fields, the rows of its particles (ghosts' rows cut to
/// the window), its bodies' runs made again over the window with the whole bodies' slabs; not its
/// fluid (hf/window_fluid.hpp).
template <int D>
Model<D> window_of(const Model<D>& m, const Partition& p, int rank);

/// The entries (`width` per particle) of the window's particles, range after range.
template <class T>
std::vector<T> slice(const std::vector<T>& v, const Numbering& window, std::size_t width = 1) {
  if (v.empty()) return {};
  std::vector<T> out;
  for (const auto& a : window.ranges())
    out.insert(out.end(), v.begin() + static_cast<std::ptrdiff_t>(a.whole * width), v.begin() + static_cast<std::ptrdiff_t>((a.whole + a.count) * width));
  return out;
}

/// f(a, i) for each particle of the window: a its number here, i the whole run's.
template <class F>
void for_each_in(const Numbering& window, F&& f) {
  for (const auto& r : window.ranges())
    for (std::size_t a = r.here; a < r.here + r.count; ++a) f(a, r.whole + (a - r.here));
}

}  // namespace rift::pd
