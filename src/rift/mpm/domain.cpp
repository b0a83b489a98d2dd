#include "rift/mpm/domain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "rift/core/error.hpp"
#include "rift/mpm/checkpoint_state.hpp"

namespace rift::mpm {

namespace {

using Parcel = parallel::Communicator::Parcel;

/// memcpy that takes no pointer when there is nothing to copy (an empty vector's may be null).
void copy_bytes(void* to, const void* from, std::size_t count) {
  if (count) std::memcpy(to, from, count);
}

template <class T>
void append(std::vector<std::byte>& out, const T& value) {
  const auto at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

template <class T>
T take(const std::vector<std::byte>& in, std::size_t& at) {
  T value;
  std::memcpy(static_cast<void*>(&value), in.data() + at, sizeof(T));  // Eigen's fixed-size matrices: their coefficients alone
  at += sizeof(T);
  return value;
}

/// Runs f(name, array) on every per-point array of Particles (the list checkpoint_state.hpp keeps).
template <int D, class F>
void each_member(F f, Particles<D>& p) {
  visit(f, p);
}

/// An array's elements as bytes, one column of a transfer of Particles between models.
template <class T>
std::vector<std::byte> column_of(const std::vector<T>& v) {
  std::vector<std::byte> bytes(v.size() * sizeof(T));
  copy_bytes(bytes.data(), static_cast<const void*>(v.data()), bytes.size());
  return bytes;
}

/// The columns (one per member, in each_member's order) into the members of `to`.
template <int D>
void place_columns(const std::vector<std::vector<std::byte>>& columns, Particles<D>& to) {
  std::size_t column = 0;
  each_member(
      [&](const char*, auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        const auto& bytes = columns[column++];
        v.resize(bytes.size() / sizeof(T));
        copy_bytes(static_cast<void*>(v.data()), bytes.data(), bytes.size());
      },
      to);
}

/// Runs f on every slot of the nodes of g whose index along `axis` (the whole grid's) lies in [lo, hi],
/// in the whole grid's order: two ranks visit the nodes they share in the same order.
template <int D, class F>
void each_slot_in_layers(const Grid<D>& g, int axis, long lo, long hi, F f) {
  std::array<long, 3> first{0, 0, 0}, last{g.nodes[0], g.nodes[1], g.nodes[2]};
  first[axis] = std::max(0L, lo - g.offset[axis]);
  last[axis] = std::min(g.nodes[axis], hi + 1 - g.offset[axis]);
  const auto fields = static_cast<std::size_t>(g.fields);
  for (long k = first[2]; k < last[2]; ++k)
    for (long j = first[1]; j < last[1]; ++j)
      for (long i = first[0]; i < last[0]; ++i) {
        const std::size_t node = g.index(i, j, k);
        for (std::size_t f_ = 0; f_ < fields; ++f_) f(node * fields + f_);
      }
}

/// The layer of cells along `axis` that holds x, as the floor of its grid coordinate (not clamped).
template <int D>
double layer_of(const Grid<D>& g, int axis, const Vec<D>& x) {
  return std::floor((x[axis] - g.origin[axis]) / g.cell_size);
}

/// The sums a scatter makes at grid slot n, one double at a time.
template <int D, class F>
void each_sum(Grid<D>& g, std::size_t n, bool force, bool contact, F f) {
  f(g.mass[n]);
  for (int a = 0; a < D; ++a) f(g.momentum[n][a]);
  if (force)
    for (int a = 0; a < D; ++a) f(g.force[n][a]);
  if (contact) {
    for (int a = 0; a < D; ++a) f(g.mass_gradient[n][a]);
    f(g.volume[n]);
    for (int a = 0; a < D; ++a) f(g.displacement[n][a]);
  }
}

}  // namespace

int Slabs::owner(long cell) const {
  const auto ranks = static_cast<long>(first_cell.size()) - 1;
  const auto it = std::upper_bound(first_cell.begin(), first_cell.end(), cell);
  return static_cast<int>(std::clamp(static_cast<long>(it - first_cell.begin()) - 1, 0L, ranks - 1));
}

std::pair<long, long> Slabs::node_layers(int r, long nodes) const {
  const auto q = static_cast<std::size_t>(r);
  return {std::max(0L, first_cell[q] - 1), std::min(nodes - 1, first_cell[q + 1] + 1)};
}

template <int D>
Slabs cut_into_slabs(const Model<D>& whole, int ranks, const std::string& file, int axis, const std::vector<double>* weight) {
  const auto& g = whole.grid;
  const char* names = "xyz";
  if (axis >= D)
    throw SceneError({file, 0, 0}, "--cut-along", fmt::format("a {}D scene has no {} axis; give x{}", D, names[axis], D == 3 ? ", y or z" : " or y"));
  Slabs slabs;
  slabs.axis = axis;
  if (axis < 0) {
    slabs.axis = D - 1;
    for (int a = D - 2; a >= 0; --a)
      if (g.nodes[a] > g.nodes[slabs.axis]) slabs.axis = a;
  }
  const long cells = g.nodes[slabs.axis] - 1;
  if (cells < Slabs::min_cells * ranks)
    throw SceneError({file, 0, 0}, "mpirun -np " + std::to_string(ranks),
                     fmt::format("the grid has {} cells along {} and a rank needs {} of them; run this scene on at most {} ranks{}", cells,
                                 names[slabs.axis], Slabs::min_cells, std::max(1L, cells / Slabs::min_cells),
                                 axis < 0 ? "" : " or cut it along another axis"));
  // the points' weight per layer of cells, then cuts where the running sum passes each rank's share
  std::vector<double> per_layer(static_cast<std::size_t>(cells), 0.0);
  const auto& position = whole.particles.position;
  double total = 0.0;
  for (std::size_t p = 0; p < position.size(); ++p) {
    const double u = layer_of<D>(g, slabs.axis, position[p]), w = weight ? (*weight)[p] : 1.0;
    per_layer[static_cast<std::size_t>(std::clamp(u, 0.0, double(cells - 1)))] += w;
    total += w;
  }
  slabs.first_cell.assign(static_cast<std::size_t>(ranks) + 1, cells);
  slabs.first_cell[0] = 0;
  double below = 0.0;
  long cell = 0;
  for (int r = 1; r < ranks; ++r) {
    const double share = total * r / ranks;
    while (cell < cells && below + per_layer[static_cast<std::size_t>(cell)] <= share) below += per_layer[static_cast<std::size_t>(cell++)];
    // every slab min_cells thick at least, and room for the slabs above
    const long first = std::clamp(cell, slabs.first_cell[static_cast<std::size_t>(r - 1)] + Slabs::min_cells,
                                  cells - Slabs::min_cells * (ranks - r));
    slabs.first_cell[static_cast<std::size_t>(r)] = first;
    for (; cell < first; ++cell) below += per_layer[static_cast<std::size_t>(cell)];
    for (; cell > first; --cell) below -= per_layer[static_cast<std::size_t>(cell - 1)];
  }
  return slabs;
}

template <int D>
Domain<D>::Domain(const parallel::Communicator& comm, Slabs slabs, const Model<D>& whole)
    : comm_(comm), slabs_(std::move(slabs)), whole_nodes_(whole.grid.nodes[slabs_.axis]), whole_points_(whole.particles.size()) {}

template <int D>
long Domain<D>::cell_of(const Grid<D>& g, const Vec<D>& x) const {
  const double u = layer_of<D>(g, slabs_.axis, x);
  // a point off the grid stays with its rank, whose stencil then reports it (stencil.hpp)
  return std::isfinite(u) ? static_cast<long>(std::clamp(u, -1.0, double(whole_nodes_))) : -2;
}

template <int D>
Model<D> Domain<D>::part_of(const Model<D>& whole) {
  Model<D> part;
  part.bodies = whole.bodies;
  part.shape = whole.shape;
  part.particle_half_width = whole.particle_half_width;
  part.thickness = whole.thickness;
  part.time = whole.time;
  // the grid: this rank's layers of nodes along the axis
  part.grid.origin = whole.grid.origin;
  part.grid.cell_size = whole.grid.cell_size;
  part.grid.fields = whole.grid.fields;
  part.grid.nodes = whole.grid.nodes;
  const auto [lo, hi] = slabs_.node_layers(comm_.rank(), whole_nodes_);
  part.grid.offset[slabs_.axis] = lo;
  part.grid.nodes[slabs_.axis] = hi - lo + 1;
  part.grid.resize();
  // the points in the slab, in the whole run's order
  id_.clear();
  for (std::size_t p = 0; p < whole.particles.size(); ++p) {
    const long c = cell_of(whole.grid, whole.particles.position[p]);
    if (slabs_.owner(c) == comm_.rank()) id_.push_back(p);
  }
  auto& from = const_cast<Particles<D>&>(whole.particles);  // each_member() takes its members by reference; only read here
  std::vector<std::vector<std::byte>> columns;
  each_member(
      [&](const char*, auto& v) {
        std::decay_t<decltype(v)> mine;
        mine.reserve(id_.size());
        for (auto p : id_) mine.push_back(v[p]);
        columns.push_back(column_of(mine));
      },
      from);
  place_columns(columns, part.particles);
  return part;
}

template <int D>
bool Domain<D>::migrate(Model<D>& m) {
  auto& ps = m.particles;
  const int me = comm_.rank();
  std::vector<Parcel> parcels;
  for (int q : {me - 1, me + 1})
    if (q >= 0 && q < comm_.size()) parcels.push_back({q, {}, {}});
  std::vector<std::uint8_t> leaves(ps.size(), 0);
  std::size_t left = 0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const long c = cell_of(m.grid, ps.position[p]);
    if (c == -2) continue;
    const int q = slabs_.owner(c);
    if (q == me) continue;
    auto parcel = std::find_if(parcels.begin(), parcels.end(), [&](const Parcel& k) { return k.peer == q; });
    if (parcel == parcels.end())
      throw PhysicsError(fmt::format("material point {} crossed a whole slab of {} cells in one step at t = {:g} s; the time step is too large "
                                     "for its speed",
                                     id_[p], Slabs::min_cells, m.time));
    append(parcel->send, id_[p]);
    each_member([&](const char*, auto& v) { append(parcel->send, v[p]); }, ps);
    leaves[p] = 1, ++left;
  }
  comm_.exchange(parcels);
  std::size_t arrived = 0;
  for (const auto& k : parcels) arrived += k.receive.size();
  if (left == 0 && arrived == 0) return false;
  // the points that stay, then the arrivals; then all in the whole run's order
  const std::size_t stay = ps.size() - left;
  std::size_t kept = 0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    if (leaves[p]) continue;
    if (kept != p) {
      id_[kept] = id_[p];
      each_member([&](const char*, auto& v) { v[kept] = v[p]; }, ps);
    }
    ++kept;
  }
  id_.resize(stay);
  each_member([&](const char*, auto& v) { v.resize(stay); }, ps);
  for (const auto& k : parcels) {
    std::size_t at = 0;
    while (at < k.receive.size()) {
      id_.push_back(take<std::uint64_t>(k.receive, at));
      each_member([&](const char*, auto& v) { v.push_back(take<typename std::decay_t<decltype(v)>::value_type>(k.receive, at)); }, ps);
    }
  }
  std::vector<std::size_t> order(id_.size());
  std::iota(order.begin(), order.end(), 0);
  // the staying points are in order already, and so are each neighbour's: a merge would do, a sort
  // of mostly ordered numbers is as quick here
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id_[a] < id_[b]; });
  auto permute = [&](auto& v) {
    std::decay_t<decltype(v)> sorted;
    sorted.reserve(v.size());
    for (auto p : order) sorted.push_back(v[p]);
    v = std::move(sorted);
  };
  permute(id_);
  each_member([&](const char*, auto& v) { permute(v); }, ps);
  return true;
}

template <int D>
void Domain<D>::sum_shared_nodes(Grid<D>& g, bool force, bool contact) const {
  const int me = comm_.rank();
  const auto mine = slabs_.node_layers(me, whole_nodes_);
  std::vector<Parcel> parcels;
  for (int q : {me - 1, me + 1}) {
    if (q < 0 || q >= comm_.size()) continue;
    const auto theirs = slabs_.node_layers(q, whole_nodes_);
    auto& k = parcels.emplace_back(Parcel{q, {}, {}});
    const long lo = std::max(mine.first, theirs.first), hi = std::min(mine.second, theirs.second);
    // the shared layers' slots times the sums of each (each_sum), in one allocation
    std::size_t slots = static_cast<std::size_t>(std::max(0L, hi - lo + 1)) * static_cast<std::size_t>(g.fields);
    for (int a = 0; a < D; ++a)
      if (a != slabs_.axis) slots *= static_cast<std::size_t>(g.nodes[a]);
    k.send.reserve(slots * static_cast<std::size_t>(1 + D + (force ? D : 0) + (contact ? 2 * D + 1 : 0)) * sizeof(double));
    each_slot_in_layers<D>(g, slabs_.axis, lo, hi, [&](std::size_t n) { each_sum<D>(g, n, force, contact, [&](double& v) { append(k.send, v); }); });
  }
  comm_.exchange(parcels);
  for (const auto& k : parcels) {
    const auto theirs = slabs_.node_layers(k.peer, whole_nodes_);
    std::size_t at = 0;
    // the lower rank's part first, on both ranks: both hold the same sums
    const bool lower = k.peer < me;
    each_slot_in_layers<D>(g, slabs_.axis, std::max(mine.first, theirs.first), std::min(mine.second, theirs.second), [&](std::size_t n) {
      each_sum<D>(g, n, force, contact, [&](double& v) {
        const double other = take<double>(k.receive, at);
        v = lower ? other + v : v + other;
      });
    });
  }
}

template <int D>
void Domain<D>::gather_points(Model<D>& part, Model<D>* whole) const {
  std::vector<std::vector<std::byte>> columns;
  each_member([&](const char*, auto& v) { columns.push_back(column_of(gather(v))); }, part.particles);
  if (!whole) return;
  place_columns(columns, whole->particles);
  whole->time = part.time;
}

template <int D>
void Domain<D>::gather_grid(Grid<D>& part, Grid<D>* whole) const {
  // each rank's own layers of nodes (its cells' lower nodes; the last rank's top layer too), whose
  // sums are whole there, in the whole grid's order
  auto own_layers = [&](int r) {
    const auto q = static_cast<std::size_t>(r);
    return std::pair<long, long>{slabs_.first_cell[q], r + 1 == comm_.size() ? whole_nodes_ - 1 : slabs_.first_cell[q + 1] - 1};
  };
  auto each_array = [](Grid<D>& g, auto f) {
    f(g.mass), f(g.momentum), f(g.force), f(g.velocity), f(g.velocity_start), f(g.mass_gradient), f(g.volume), f(g.displacement);
  };
  const auto [lo, hi] = own_layers(comm_.rank());
  std::vector<std::byte> mine;
  each_array(part, [&](auto& v) {
    if (!v.empty()) each_slot_in_layers<D>(part, slabs_.axis, lo, hi, [&](std::size_t n) { append(mine, v[n]); });
  });
  const auto all = comm_.gather(mine);
  if (!whole) return;
  std::size_t at = 0;
  for (int r = 0; r < comm_.size(); ++r) {
    const auto [first, last] = own_layers(r);
    each_array(*whole, [&](auto& v) {
      using T = typename std::decay_t<decltype(v)>::value_type;
      if (!v.empty()) each_slot_in_layers<D>(*whole, slabs_.axis, first, last, [&](std::size_t n) { v[n] = take<T>(all, at); });
    });
  }
}

template <int D>
std::string Domain<D>::load_balance(const Model<D>& part, double loop_seconds, double in_mpi) const {
  const auto all = comm_.gather(std::vector<double>{double(part.particles.size()), loop_seconds, in_mpi});
  static const char* axis[3] = {"x", "y", "z"};
  std::string out = fmt::format("load balance over {} ranks, slabs of cells along {} (material points, loop time, of it in MPI calls):",
                                comm_.size(), axis[slabs_.axis]);
  for (std::size_t r = 0; 3 * r < all.size(); ++r) out += fmt::format(" rank {}: {:.0f}, {:.2f} s, {:.2f} s;", r, all[3 * r], all[3 * r + 1], all[3 * r + 2]);
  out.pop_back();
  return out;
}

#define RIFT_INSTANTIATE(D)                                                            \
  template Slabs cut_into_slabs<D>(const Model<D>&, int, const std::string&, int, const std::vector<double>*);     \
  template class Domain<D>;
RIFT_INSTANTIATE(2)
RIFT_INSTANTIATE(3)
#undef RIFT_INSTANTIATE

}  // namespace rift::mpm
