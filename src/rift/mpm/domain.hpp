// Domain decomposition of a material point run over the ranks of `mpirun -np N` (as Uintah and Karamelo
// decompose theirs): the grid's cells are cut by a processor grid of P_x x P_y (x P_z) boxes, one per
// rank. A rank holds the material points inside its box and the grid nodes they reach: with every shape
// function here (linear, uGIMP, quadratic and cubic B-splines; shape_functions.hpp) a point in cell c
// reaches the nodes c - 1 .. c + 2 along an axis, so a rank owning the cells [a, b) holds a - 1 .. b + 1.
// One step (Solver::step): migration (points whose cell moved into a neighbour's box go to that rank,
// with every member); particle to grid, after which the nodes that ranks share (up to 2^D at a corner)
// exchange their parts and add them in the order of the ranks on every rank that holds the node, so every
// node of a rank's grid holds the whole run's sums; the grid update and grid to particles are local.
// The results equal the one-rank run's to round-off: the shared nodes add the same terms in another order.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "rift/mpm/model.hpp"
#include "rift/parallel/communicator.hpp"

namespace rift::mpm {

/// The cut of the grid's cells into one box per rank: along each axis a into ranks[a] ranges;
/// rank r sits at (r mod P_x, (r / P_x) mod P_y, r / (P_x P_y)) of the processor grid.
struct CellBoxes {
  /// A box is at least this many cells across along every cut axis, so that no node is reached from
  /// more than two ranks along it.
  static constexpr long min_cells = 4;
  std::array<int, 3> ranks{1, 1, 1};
  std::array<std::vector<long>, 3> first_cell;  // per axis: the range c owns [first_cell[a][c], first_cell[a][c + 1])
  int size() const { return ranks[0] * ranks[1] * ranks[2]; }
  std::array<int, 3> coordinates(int r) const { return {r % ranks[0], r / ranks[0] % ranks[1], r / (ranks[0] * ranks[1])}; }
  int rank_at(const std::array<int, 3>& c) const { return c[0] + ranks[0] * (c[1] + ranks[1] * c[2]); }
  /// The rank owning a cell (cells past either end of the grid: the first or last range).
  int owner(const std::array<long, 3>& cell) const;
  /// The nodes that rank r holds along each axis, [first, last]: its cells' nodes and the ones its
  /// points reach (`nodes`: the whole grid's per axis).
  std::array<std::pair<long, long>, 3> node_box(int r, const std::array<long, 3>& nodes) const;
  /// The nodes whose sums rank r gathers for the whole grid (its cells' lower nodes; along an axis
  /// the last range's top node too): every node is one rank's.
  std::array<std::pair<long, long>, 3> own_nodes(int r, const std::array<long, 3>& nodes) const;
  /// "boxes of cells, 2 x 2", or "slabs of cells along x" where one axis alone is cut.
  std::string describe(int dimension) const;
};

/// The boxes of `ranks` ranks, each holding about the same work along each cut axis: a material
/// point weighs 1, or weight[p] where `weight` is given (a point near an explicit crack weighs more:
/// crack_work_weights). `grid` (P_x, P_y, P_z; empty: chosen here) sets the processor grid; `axis`
/// (>= 0) cuts that axis alone. Chosen: the grid whose cuts cross the fewest nodes (the least
/// exchanged), every box CellBoxes::min_cells cells across. A SceneError (for `file`) where no grid of
/// `ranks` boxes gives that.
template <int D>
CellBoxes cut_into_boxes(const Model<D>& whole, int ranks, const std::string& file, int axis = -1, const std::vector<int>& grid = {},
                         const std::vector<double>* weight = nullptr);

template <int D>
class Domain {
 public:
  Domain(const parallel::Communicator& comm, CellBoxes boxes, const Model<D>& whole);
  /// This rank's part of the whole run's model: the points in its box, in the whole run's order,
  /// and its box of the grid's nodes.
  Model<D> part_of(const Model<D>& whole);
  /// The whole run's number of each of this rank's points.
  const std::vector<std::uint64_t>& id() const { return id_; }
  std::size_t whole_points() const { return whole_points_; }
  const CellBoxes& boxes() const { return boxes_; }
  const parallel::Communicator& communicator() const { return comm_; }

  /// Sends the points that left this rank's box to the neighbour whose box they entered, and takes
  /// in the neighbours' (each member of Particles); the points stay in the whole run's order. True
  /// when this rank's points changed. Every rank calls it at the same step.
  bool migrate(Model<D>& m);
  /// After a scatter: adds the neighbours' parts of the sums at the nodes this rank shares with
  /// them (the mass, which MUSL's remap leaves as it was; the momentum; the force; the contact
  /// quantities).
  void sum_shared_nodes(Grid<D>& g, bool mass, bool force, bool contact) const;

  /// Whether x lies in this rank's box (its cell's owner is this rank).
  bool owns(const Grid<D>& g, const Vec<D>& x) const {
    const auto c = cell_of(g, x);
    return c && boxes_.owner(*c) == comm_.rank();
  }
  /// The nodes' sums and velocities of every rank's box into the whole grid `whole` on rank 0 (null
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
  /// The cell of a point (none where its position is not finite: it stays with its rank, whose
  /// stencil then reports it, stencil.hpp).
  std::optional<std::array<long, 3>> cell_of(const Grid<D>& g, const Vec<D>& x) const;
  /// The ranks whose boxes touch this one's (up to 3^D - 1), ascending.
  const std::vector<int>& neighbours() const { return neighbours_; }
  const parallel::Communicator& comm_;
  CellBoxes boxes_;
  std::vector<int> neighbours_;
  std::array<long, 3> whole_nodes_{1, 1, 1};  // nodes of the whole grid per axis
  std::size_t whole_points_ = 0;
  std::vector<std::uint64_t> id_;
};

}  // namespace rift::mpm
