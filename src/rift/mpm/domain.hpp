// Domain decomposition of a material point run over the ranks of `mpirun -np N` (as Uintah and
// Karamelo decompose theirs): the grid's cells are cut into slabs along one axis, one per rank.
// A rank holds the material points inside its slab and the grid nodes they reach; a point in cell c
// reaches the nodes c - 1 .. c + 2 along an axis with every shape function here (linear, uGIMP,
// quadratic and cubic B-splines, shape_functions.hpp), so a rank owning the cells [a, b) holds the
// nodes a - 1 .. b + 1: its cells' nodes and one layer beyond each face.
//
// One step of a distributed run (Solver::step):
//   migration: points whose cell moved into a neighbour's slab go to that rank, with every member;
//   particle to grid: each rank scatters its points; the nodes two neighbours share then hold each
//     one's part, and they exchange and add them (the lower rank's part first, on both ranks, so
//     both hold the same sums): every node of a rank's grid then holds the whole run's sums;
//   the grid update and grid to particles are local to a node and to a point.
// The results equal the one-rank run's to round-off: the sums at the shared nodes add the same
// terms in another order.
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "rift/mpm/model.hpp"
#include "rift/parallel/communicator.hpp"

namespace rift::mpm {

/// The cut of the grid's cells along one axis into one slab per rank.
struct Slabs {
  /// A slab is at least this many cells thick, so that no node is reached from more than two ranks.
  static constexpr long min_cells = 4;
  int axis = 0;
  std::vector<long> first_cell;  // rank r owns the cells [first_cell[r], first_cell[r + 1]) along the axis
  /// The rank owning a cell (cells past either end of the grid: the first or last rank).
  int owner(long cell) const;
  /// The nodes along the axis that rank r holds: its cells' nodes and the ones its points reach.
  std::pair<long, long> node_layers(int r, long nodes) const;
};

/// Slabs across `axis` (-1: the axis with the most cells), each holding about the same work: a
/// material point weighs 1, or weight[p] where `weight` is given (a point near an explicit crack
/// weighs more: crack_work_weights); a SceneError (for `file`) when the grid has fewer than
/// Slabs::min_cells cells per rank along it.
template <int D>
Slabs cut_into_slabs(const Model<D>& whole, int ranks, const std::string& file, int axis = -1, const std::vector<double>* weight = nullptr);

template <int D>
class Domain {
 public:
  Domain(const parallel::Communicator& comm, Slabs slabs, const Model<D>& whole);
  /// This rank's part of the whole run's model: the points in its slab, in the whole run's order,
  /// and its layers of the grid.
  Model<D> part_of(const Model<D>& whole);
  /// The whole run's number of each of this rank's points.
  const std::vector<std::uint64_t>& id() const { return id_; }
  std::size_t whole_points() const { return whole_points_; }
  const Slabs& slabs() const { return slabs_; }
  const parallel::Communicator& communicator() const { return comm_; }

  /// Sends the points that left this rank's slab to the neighbour whose slab they entered, and takes
  /// in the neighbours' (each member of Particles); the points stay in the whole run's order. True
  /// when this rank's points changed. Every rank calls it at the same step.
  bool migrate(Model<D>& m);
  /// After a scatter: adds the neighbours' parts of the sums at the nodes this rank shares with
  /// them (mass and momentum; the force; the contact quantities).
  void sum_shared_nodes(Grid<D>& g, bool force, bool contact) const;

  /// Whether x lies in this rank's slab (its cell's owner is this rank).
  bool owns(const Grid<D>& g, const Vec<D>& x) const {
    const long c = cell_of(g, x);
    return c != -2 && slabs_.owner(c) == comm_.rank();
  }
  /// The nodes' sums and velocities of every rank's slab into the whole grid `whole` on rank 0 (null
  /// elsewhere), as one rank's grid after the same step.
  void gather_grid(Grid<D>& part, Grid<D>* whole) const;
  /// A per-point array (`width` entries per point) of every rank, on rank 0 in the whole run's
  /// order (empty elsewhere).
  template <class T>
  std::vector<T> gather(const std::vector<T>& local, std::size_t width = 1) const {
    const auto ids = comm_.gather(id_);
    const auto all = comm_.gather(local);
    if (!comm_.root()) return {};
    if (all.size() != ids.size() * width) throw std::logic_error("Domain::gather: an array that is not one per point");
    std::vector<T> whole(whole_points_ * width);
    for (std::size_t k = 0; k < ids.size(); ++k)
      for (std::size_t c = 0; c < width; ++c) whole[ids[k] * width + c] = all[k * width + c];
    return whole;
  }
  /// Every rank's points into `whole` on rank 0 (null elsewhere), for a checkpoint that holds the
  /// whole run; the grid is not gathered, as each step takes it anew from the points.
  void gather_points(Model<D>& part, Model<D>* whole) const;
  /// Points, step-loop time and the part of it in MPI calls (parallel::seconds_in_mpi) of every rank, on rank 0.
  std::string load_balance(const Model<D>& part, double loop_seconds, double in_mpi) const;

 private:
  /// Cell of a point along the cut axis.
  long cell_of(const Grid<D>& g, const Vec<D>& x) const;
  const parallel::Communicator& comm_;
  Slabs slabs_;
  long whole_nodes_ = 0;  // nodes of the whole grid along the axis
  std::size_t whole_points_ = 0;
  std::vector<std::uint64_t> id_;
};

}  // namespace rift::mpm
