// A rank's share of a distributed peridynamic run. The particles are numbered body after body, each
// body's lattice x fastest, so a contiguous range of the numbering is a stack of lattice layers: the
// ranks own consecutive ranges (a processor grid of 1 x 1 x P along the lattice's slowest axis),
// balanced by bonds. A rank holds its owned range and, around it, every particle within the bonds'
// reach of it (ghosts): the window. Its bond passes take the whole run's runs and slabs cut to the
// window (BodyInfo::origin), so every sum of an owned particle is made in the same order as on one
// rank, and the run is bitwise the same on any number of ranks.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::pd {

struct Partition {
  std::vector<std::size_t> owned;  // size ranks + 1: rank r owns [owned[r], owned[r + 1])
  std::vector<std::size_t> window_first, window_last;  // each rank's window [first, last)
  std::size_t reach = 0;  // the farthest bond in the numbering, max |i - j|
};

/// Cuts the model's particles into `ranks` consecutive ranges of about equal bond counts, at
/// multiples of `granularity` (a rank may own none where there are more ranks than particles).
/// Dynamic relaxation cuts at whole blocks of its sums (parallel::ordered_sum_block), whose damping
/// and residual are then the one-rank run's bits.
template <int D>
Partition partition_by_bonds(const Model<D>& m, int ranks, std::size_t granularity = 1);

/// What the distributed run cannot take yet, as a sentence; empty when the model can be
/// distributed (interfaces, and fluids whose cracks can grow, run on one rank for now).
template <int D>
std::string not_distributable(const Model<D>& m);

/// Rank r's window of the whole model: its fields, the rows of its particles (ghosts' rows cut to
/// the window), its bodies' runs made again over the window with the whole bodies' slabs.
template <int D>
Model<D> window_of(const Model<D>& m, const Partition& p, int rank);

}  // namespace rift::pd
