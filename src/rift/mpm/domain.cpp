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

using NodeBox = std::array<std::pair<long, long>, 3>;  // per axis [first, last] in the whole grid's numbering

/// The box of nodes both boxes hold (empty along an axis where first > last).
NodeBox common(const NodeBox& a, const NodeBox& b) {
  NodeBox c;
  for (int k = 0; k < 3; ++k) c[k] = {std::max(a[k].first, b[k].first), std::min(a[k].second, b[k].second)};
  return c;
}

bool empty(const NodeBox& box) {
  return box[0].first > box[0].second || box[1].first > box[1].second || box[2].first > box[2].second;
}

/// Runs f on every slot of the nodes of g inside `box` (the whole grid's numbering), in the whole
/// grid's order: the ranks visit the nodes they share in the same order.
template <int D, class F>
void each_slot_in_box(const Grid<D>& g, const NodeBox& box, F f) {
  std::array<long, 3> first{}, last{};
  for (int a = 0; a < 3; ++a) {
    first[a] = std::max(0L, box[a].first - g.offset[a]);
    last[a] = std::min(g.nodes[a], box[a].second + 1 - g.offset[a]);
  }
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
void each_sum(Grid<D>& g, std::size_t n, bool mass, bool force, bool contact, F f) {
  if (mass) f(g.mass[n]);
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

int CellBoxes::owner(const std::array<long, 3>& cell) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const auto& cuts = first_cell[static_cast<std::size_t>(a)];
    const auto it = std::upper_bound(cuts.begin(), cuts.end(), cell[static_cast<std::size_t>(a)]);
    c[static_cast<std::size_t>(a)] = static_cast<int>(std::clamp(static_cast<long>(it - cuts.begin()) - 1, 0L, static_cast<long>(ranks[static_cast<std::size_t>(a)]) - 1));
  }
  return rank_at(c);
}

NodeBox CellBoxes::node_box(int r, const std::array<long, 3>& nodes) const {
  const auto c = coordinates(r);
  NodeBox box;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto q = static_cast<std::size_t>(c[a]);
    box[a] = {std::max(0L, first_cell[a][q] - 1), std::min(nodes[a] - 1, first_cell[a][q + 1] + 1)};
  }
  return box;
}

NodeBox CellBoxes::own_nodes(int r, const std::array<long, 3>& nodes) const {
  const auto c = coordinates(r);
  NodeBox box;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto q = static_cast<std::size_t>(c[a]);
    box[a] = {first_cell[a][q], c[a] + 1 == ranks[a] ? nodes[a] - 1 : first_cell[a][q + 1] - 1};
  }
  return box;
}

std::string CellBoxes::describe(int dimension) const {
  static const char* names = "xyz";
  int cut = 0, axis = 0;
  for (int a = 0; a < dimension; ++a)
    if (ranks[static_cast<std::size_t>(a)] > 1) ++cut, axis = a;
  if (cut <= 1) return fmt::format("slabs of cells along {}", names[axis]);
  return dimension == 3 ? fmt::format("boxes of cells, {} x {} x {}", ranks[0], ranks[1], ranks[2])
                        : fmt::format("boxes of cells, {} x {}", ranks[0], ranks[1]);
}

namespace {

/// The cuts of `cells` layers into `parts` ranges of about equal weight, each min_cells at least.
std::vector<long> cut_layers(const std::vector<double>& per_layer, int parts) {
  const auto cells = static_cast<long>(per_layer.size());
  const double total = std::accumulate(per_layer.begin(), per_layer.end(), 0.0);
  std::vector<long> first(static_cast<std::size_t>(parts) + 1, cells);
  first[0] = 0;
  double below = 0.0;
  long cell = 0;
  for (int r = 1; r < parts; ++r) {
    const double share = total * r / parts;
    while (cell < cells && below + per_layer[static_cast<std::size_t>(cell)] <= share) below += per_layer[static_cast<std::size_t>(cell++)];
    // every range min_cells thick at least, and room for the ranges above
    const long at = std::clamp(cell, first[static_cast<std::size_t>(r - 1)] + CellBoxes::min_cells, cells - CellBoxes::min_cells * (parts - r));
    first[static_cast<std::size_t>(r)] = at;
    for (; cell < at; ++cell) below += per_layer[static_cast<std::size_t>(cell)];
    for (; cell > at; --cell) below -= per_layer[static_cast<std::size_t>(cell - 1)];
  }
  return first;
}

}  // namespace

template <int D>
CellBoxes cut_into_boxes(const Model<D>& whole, int ranks, const std::string& file, int axis, const std::vector<int>& grid,
                         const std::vector<double>* weight) {
  const auto& g = whole.grid;
  const char* names = "xyz";
  if (axis >= D)
    throw SceneError({file, 0, 0}, "--cut-along", fmt::format("a {}D scene has no {} axis; give x{}", D, names[axis], D == 3 ? ", y or z" : " or y"));
  std::array<long, 3> cells{1, 1, 1};
  for (int a = 0; a < D; ++a) cells[static_cast<std::size_t>(a)] = g.nodes[a] - 1;
  auto fits = [&](const std::array<int, 3>& p) {
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] > 1 && cells[a] < CellBoxes::min_cells * p[a]) return false;
    return true;
  };
  CellBoxes boxes;
  if (!grid.empty()) {
    if (static_cast<int>(grid.size()) != D)
      throw SceneError({file, 0, 0}, "--processor-grid", fmt::format("a {}D scene's processor grid has {} numbers (as {})", D, D, D == 3 ? "2x2x1" : "2x2"));
    long product = 1;
    for (int a = 0; a < D; ++a) boxes.ranks[static_cast<std::size_t>(a)] = grid[static_cast<std::size_t>(a)], product *= grid[static_cast<std::size_t>(a)];
    if (product != ranks)
      throw SceneError({file, 0, 0}, "--processor-grid", fmt::format("a grid of {} boxes for {} ranks; its numbers' product must be the ranks' number", product, ranks));
    if (!fits(boxes.ranks))
      throw SceneError({file, 0, 0}, "--processor-grid",
                       fmt::format("the grid has {} x {}{} cells and a box needs {} along each cut axis", cells[0], cells[1],
                                   D == 3 ? fmt::format(" x {}", cells[2]) : "", CellBoxes::min_cells));
  } else {
    // the cut axis (given, or else the one with the most cells) for the message of a grid too thin
    int longest = axis;
    if (longest < 0) {
      longest = D - 1;
      for (int a = D - 2; a >= 0; --a)
        if (g.nodes[a] > g.nodes[longest]) longest = a;
    }
    bool found = false;
    double least = 0.0;
    // every P_x x P_y x P_z = ranks (one axis alone where `axis` is given): the fewest nodes on cuts
    for (int px = 1; px <= ranks; ++px)
      for (int py = 1; py <= ranks / px; ++py) {
        if (ranks % (px * py) != 0) continue;
        const std::array<int, 3> p{px, py, ranks / (px * py)};
        if ((D == 2 && p[2] != 1) || !fits(p)) continue;
        if (axis >= 0 && p[static_cast<std::size_t>(axis)] != ranks) continue;
        double crossed = 0.0;  // nodes on the cuts: (P_a - 1) planes of the other axes' nodes
        for (std::size_t a = 0; a < 3; ++a) crossed += (p[a] - 1) * double(g.nodes[(a + 1) % 3]) * double(g.nodes[(a + 2) % 3]);
        if (!found || crossed < least) found = true, least = crossed, boxes.ranks = p;
      }
    if (!found)
      throw SceneError({file, 0, 0}, "mpirun -np " + std::to_string(ranks),
                       fmt::format("the grid has {} cells along {} and a rank needs {} of them; run this scene on at most {} ranks{}",
                                   cells[static_cast<std::size_t>(longest)], names[longest], CellBoxes::min_cells,
                                   std::max(1L, cells[static_cast<std::size_t>(longest)] / CellBoxes::min_cells),
                                   axis < 0 ? "" : " or cut it along another axis"));
  }
  // along each axis the points' weight per layer of cells, cut where the running sum passes each
  // range's share
  const auto& position = whole.particles.position;
  for (std::size_t a = 0; a < 3; ++a) {
    std::vector<double> per_layer(static_cast<std::size_t>(cells[a]), 0.0);
    if (static_cast<int>(a) < D)
      for (std::size_t p = 0; p < position.size(); ++p) {
        const double u = layer_of<D>(g, static_cast<int>(a), position[p]), w = weight ? (*weight)[p] : 1.0;
        per_layer[static_cast<std::size_t>(std::clamp(u, 0.0, double(cells[a] - 1)))] += w;
      }
    boxes.first_cell[a] = cut_layers(per_layer, boxes.ranks[a]);
  }
  return boxes;
}

template <int D>
Domain<D>::Domain(const parallel::Communicator& comm, CellBoxes boxes, const Model<D>& whole)
    : comm_(comm), boxes_(std::move(boxes)), whole_nodes_(whole.grid.nodes), whole_points_(whole.particles.size()) {
  const auto me = boxes_.coordinates(comm_.rank());
  for (int r = 0; r < comm_.size(); ++r) {
    const auto c = boxes_.coordinates(r);
    bool touches = r != comm_.rank();
    for (std::size_t a = 0; a < 3; ++a) touches = touches && std::abs(c[a] - me[a]) <= 1;
    if (touches) neighbours_.push_back(r);
  }
}

template <int D>
std::optional<std::array<long, 3>> Domain<D>::cell_of(const Grid<D>& g, const Vec<D>& x) const {
  std::array<long, 3> c{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    const double u = layer_of<D>(g, a, x);
    if (!std::isfinite(u)) return std::nullopt;
    c[static_cast<std::size_t>(a)] = static_cast<long>(std::clamp(u, -1.0, double(whole_nodes_[static_cast<std::size_t>(a)])));
  }
  return c;
}

template <int D>
Model<D> Domain<D>::part_of(const Model<D>& whole) {
  Model<D> part;
  part.bodies = whole.bodies;
  part.shape = whole.shape;
  part.particle_half_width = whole.particle_half_width;
  part.thickness = whole.thickness;
  part.time = whole.time;
  // the grid: this rank's box of nodes
  part.grid.origin = whole.grid.origin;
  part.grid.cell_size = whole.grid.cell_size;
  part.grid.fields = whole.grid.fields;
  part.grid.nodes = whole.grid.nodes;
  const auto box = boxes_.node_box(comm_.rank(), whole_nodes_);
  for (std::size_t a = 0; a < 3; ++a) {
    part.grid.offset[a] = box[a].first;
    part.grid.nodes[a] = box[a].second - box[a].first + 1;
  }
  part.grid.resize();
  // the points in the box, in the whole run's order
  id_.clear();
  for (std::size_t p = 0; p < whole.particles.size(); ++p) {
    const auto c = cell_of(whole.grid, whole.particles.position[p]);
    if (c && boxes_.owner(*c) == comm_.rank()) id_.push_back(p);
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
  for (int q : neighbours()) parcels.push_back({q, {}, {}});
  std::vector<std::uint8_t> leaves(ps.size(), 0);
  std::size_t left = 0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto c = cell_of(m.grid, ps.position[p]);
    if (!c) continue;
    const int q = boxes_.owner(*c);
    if (q == me) continue;
    auto parcel = std::find_if(parcels.begin(), parcels.end(), [&](const Parcel& k) { return k.peer == q; });
    if (parcel == parcels.end())
      throw PhysicsError(fmt::format("material point {} crossed a whole box of {} cells in one step at t = {:g} s; the time step is too large "
                                     "for its speed",
                                     id_[p], CellBoxes::min_cells, m.time));
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
void Domain<D>::sum_shared_nodes(Grid<D>& g, bool mass, bool force, bool contact) const {
  const int me = comm_.rank();
  const auto mine = boxes_.node_box(me, whole_nodes_);
  std::vector<Parcel> parcels;  // in the order of the ranks (neighbours() ascends)
  std::vector<NodeBox> shared;
  const std::size_t per_slot = static_cast<std::size_t>((mass ? 1 : 0) + D + (force ? D : 0) + (contact ? 2 * D + 1 : 0));
  for (int q : neighbours()) {
    auto& k = parcels.emplace_back(Parcel{q, {}, {}});
    const NodeBox box = shared.emplace_back(common(mine, boxes_.node_box(q, whole_nodes_)));
    if (empty(box)) continue;
    // the shared nodes' slots times the sums of each (each_sum), in one allocation
    std::size_t slots = static_cast<std::size_t>(g.fields);
    for (std::size_t a = 0; a < 3; ++a) slots *= static_cast<std::size_t>(box[a].second - box[a].first + 1);
    k.send.reserve(slots * per_slot * sizeof(double));
    each_slot_in_box<D>(g, box, [&](std::size_t n) { each_sum<D>(g, n, mass, force, contact, [&](double& v) { append(k.send, v); }); });
  }
  comm_.exchange(parcels);
  // every holder of a node adds its holders' parts in the order of the ranks, so all hold the same
  // sums: the lower ranks' parts first (into `lower`, a row per slot that a lower rank shares), then
  // this rank's, then the higher ranks'
  static thread_local std::vector<double> lower;
  static thread_local std::vector<std::int32_t> row;  // per slot of the grid: its row in `lower`; -1: none (between calls too)
  static thread_local std::vector<std::size_t> touched;
  row.resize(g.size() * static_cast<std::size_t>(g.fields), -1);
  lower.clear(), touched.clear();
  for (std::size_t p = 0; p < parcels.size(); ++p) {
    if (parcels[p].peer > me || empty(shared[p])) continue;
    std::size_t at = 0;
    each_slot_in_box<D>(g, shared[p], [&](std::size_t n) {
      if (row[n] < 0) {
        row[n] = static_cast<std::int32_t>(touched.size());
        touched.push_back(n);
        for (std::size_t t = 0; t < per_slot; ++t) lower.push_back(take<double>(parcels[p].receive, at));
      } else {
        double* const sum = &lower[static_cast<std::size_t>(row[n]) * per_slot];
        for (std::size_t t = 0; t < per_slot; ++t) sum[t] += take<double>(parcels[p].receive, at);
      }
    });
  }
  for (const std::size_t n : touched) {
    std::size_t t = 0;
    const double* const sum = &lower[static_cast<std::size_t>(row[n]) * per_slot];
    each_sum<D>(g, n, mass, force, contact, [&](double& v) { v = sum[t++] + v; });
    row[n] = -1;
  }
  for (std::size_t p = 0; p < parcels.size(); ++p) {
    if (parcels[p].peer < me || empty(shared[p])) continue;
    std::size_t at = 0;
    each_slot_in_box<D>(g, shared[p], [&](std::size_t n) { each_sum<D>(g, n, mass, force, contact, [&](double& v) { v += take<double>(parcels[p].receive, at); }); });
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
  // each rank's own nodes (CellBoxes::own_nodes), whose sums are whole there, in the whole grid's order
  auto each_array = [](Grid<D>& g, auto f) {
    f(g.mass), f(g.momentum), f(g.force), f(g.velocity), f(g.velocity_start), f(g.mass_gradient), f(g.volume), f(g.displacement);
  };
  const NodeBox own = boxes_.own_nodes(comm_.rank(), whole_nodes_);
  std::vector<std::byte> mine;
  each_array(part, [&](auto& v) {
    if (!v.empty()) each_slot_in_box<D>(part, own, [&](std::size_t n) { append(mine, v[n]); });
  });
  const auto all = comm_.gather(mine);
  if (!whole) return;
  std::size_t at = 0;
  for (int r = 0; r < comm_.size(); ++r) {
    const NodeBox theirs = boxes_.own_nodes(r, whole_nodes_);
    each_array(*whole, [&](auto& v) {
      using T = typename std::decay_t<decltype(v)>::value_type;
      if (!v.empty()) each_slot_in_box<D>(*whole, theirs, [&](std::size_t n) { v[n] = take<T>(all, at); });
    });
  }
}

template <int D>
std::string Domain<D>::load_balance(const Model<D>& part, double loop_seconds, double in_mpi) const {
  const auto all = comm_.gather(std::vector<double>{double(part.particles.size()), loop_seconds, in_mpi});
  std::string out = fmt::format("load balance over {} ranks, {} (material points, loop time, of it in MPI calls):", comm_.size(),
                                boxes_.describe(D));
  for (std::size_t r = 0; 3 * r < all.size(); ++r) out += fmt::format(" rank {}: {:.0f}, {:.2f} s, {:.2f} s;", r, all[3 * r], all[3 * r + 1], all[3 * r + 2]);
  out.pop_back();
  return out;
}

#define RIFT_INSTANTIATE(D)                                                            \
  template CellBoxes cut_into_boxes<D>(const Model<D>&, int, const std::string&, int, const std::vector<int>&, const std::vector<double>*); \
  template class Domain<D>;
RIFT_INSTANTIATE(2)
RIFT_INSTANTIATE(3)
#undef RIFT_INSTANTIATE

}  // namespace rift::mpm
