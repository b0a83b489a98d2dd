// The bonds that cross a fluid-filled crack or its extension past the tip: those whose effective stretch
// the pore pressure shifts (wet_rock.hpp). The crack's surface is made of patches, one at the
// midpoint of each short broken bond of a network (nearest and diagonal neighbours, and the short bonds a
// pressurized pre-crack cut), each a plane whose normal is the largest eigenvector of the sum of n n^T over
// the short broken bonds within 1.5 spacings (sign-free: a zigzag crack reads as its mean plane). A bond
// crosses when its ends lie on opposite sides of a patch's plane and it pierces the plane within one spacing
// of the patch's point; bonds within a face or beside the crack carry the total stress. Only bonds broken
// across the crack or its extension, or from a borehole's wall, add patches; one beside it lets fluid in.
// Pure geometry in the reference configuration, asked only of the bonds the pore shift would break and of
// those that break. Growing networks add their new patches (extend_crack_surface), else the set is made
// again (remake_crack_surface); each patch keeps its sum of n n^T in whole numbers, so the surface does not
// depend on the order the patches came in. Why: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "rift/hf/pd_names.hpp"
#include "rift/parallel/sort.hpp"
#include "rift/parallel/team.hpp"

namespace rift::hf {

namespace detail {
// x the fastest: the cells of a row along x have consecutive keys
template <int D>
std::int64_t surface_cell_key(const std::array<std::int64_t, D>& c) {
  std::int64_t k = 0;
  for (int q = D - 1; q >= 0; --q) k = k * 2097152 + (c[q] + 1048576);
  return k;
}

/// Cell keys divided by this give the row along x the cell is in.
inline constexpr std::int64_t surface_row = 2097152;

/// Indexes the grid's entries by row along x (CrackSurface::row_keys): a search among the rows,
/// which stay in the cache, then among a row's entries, in place of one over the whole grid.
inline void index_surface_rows(CrackSurface& s) {
  s.row_keys.clear(), s.row_first.clear();
  for (std::size_t e = 0; e < s.cell_keys.size(); ++e)
    if (s.row_keys.empty() || s.cell_keys[e] / surface_row != s.row_keys.back())
      s.row_keys.push_back(s.cell_keys[e] / surface_row), s.row_first.push_back(e);
  s.row_first.push_back(s.cell_keys.size());
}

template <int D>
std::array<std::int64_t, D> surface_cell_of(const double* x, double cell) {
  std::array<std::int64_t, D> c{};
  for (int q = 0; q < D; ++q) c[q] = static_cast<std::int64_t>(std::floor(x[q] / cell));
  return c;
}

/// Calls f(patch) for every patch in the cells within `margin` of the box around a and b (x
/// fastest: one search per row of cells along x) until f returns true.
template <int D, class F>
void for_patches_near_segment(const CrackSurface& s, const double* a, const double* b, double margin, F&& f) {
  std::array<std::int64_t, D> lo{}, hi{};
  for (int q = 0; q < D; ++q) {
    lo[q] = static_cast<std::int64_t>(std::floor((std::min(a[q], b[q]) - margin) / s.cell));
    hi[q] = static_cast<std::int64_t>(std::floor((std::max(a[q], b[q]) + margin) / s.cell));
  }
  std::array<std::int64_t, D> at = lo;
  while (true) {
    at[0] = lo[0];
    const std::int64_t first = surface_cell_key<D>(at), last = first + (hi[0] - lo[0]);
    // the row's entries (surface_row), then the cells' among them
    const auto row = std::lower_bound(s.row_keys.begin(), s.row_keys.end(), first / surface_row);
    if (row != s.row_keys.end() && *row == first / surface_row) {
      const auto r = static_cast<std::size_t>(row - s.row_keys.begin());
      const auto end = s.cell_keys.begin() + s.row_first[r + 1];
      for (auto e = std::lower_bound(s.cell_keys.begin() + s.row_first[r], end, first); e != end && *e <= last; ++e)
        if (f(s.in_cell[static_cast<std::size_t>(e - s.cell_keys.begin())])) return;
    }
    int q = 1;
    for (; q < D; ++q) {
      if (++at[q] <= hi[q]) break;
      at[q] = lo[q];
    }
    if (q == D) break;
  }
}
}  // namespace detail

/// Whether the bond between reference positions a and b crosses the crack surface or its extension:
/// its ends on opposite sides of a patch's plane, which it pierces within `reach` of the patch's
/// point (at most the surface's own reach; by default that), among the patches `accept(p)` takes.
template <int D, class Accept>
bool pierces_crack_if(const CrackSurface& s, const Vec<D>& a, const Vec<D>& b, double reach, Accept accept) {
  if (s.empty()) return false;
  if (reach < 0.0 || reach > s.reach) reach = s.reach;
  // a patch it pierces within reach lies within reach of the bond
  bool crosses = false;
  detail::for_patches_near_segment<D>(s, a.data(), b.data(), reach, [&](std::uint32_t p) {
    if (!accept(p)) return false;
    const auto& plane = s.planes[p];
    double da = 0.0, db = 0.0;
    for (int q = 0; q < D; ++q) da += (a[q] - plane[static_cast<std::size_t>(q)]) * plane[static_cast<std::size_t>(3 + q)],
                                db += (b[q] - plane[static_cast<std::size_t>(q)]) * plane[static_cast<std::size_t>(3 + q)];
    if (!(da * db < 0.0)) return false;  // both ends on one side, or one on the plane
    const double t = da / (da - db);
    double r2 = 0.0;
    for (int q = 0; q < D; ++q) {
      const double e = a[q] + t * (b[q] - a[q]) - plane[static_cast<std::size_t>(q)];
      r2 += e * e;
    }
    crosses = r2 <= reach * reach;
    return crosses;
  });
  return crosses;
}

/// pierces_crack_if over every patch, within the surface's reach.
template <int D>
bool pierces_crack(const CrackSurface& s, const Vec<D>& a, const Vec<D>& b) {
  return pierces_crack_if<D>(s, a, b, -1.0, [](std::uint32_t) { return true; });
}

/// The network whose fluid fills entry k of row i: a broken bond between two particles the same
/// fluid reaches, or a failed interface bond that fluid fills where its faces are apart
/// (FluidNetwork::open_interface_bonds, made with the labels); -1: none.
inline int network_of_bond(const FluidNetwork& f, const Bonds& b, std::size_t i, std::int64_t k) {
  const auto state = b.intact[static_cast<std::size_t>(k)];
  if (state == bond_intact || f.source.empty()) return -1;
  const int s = f.source[i];
  if (s < 0 || f.source[static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)])] != s) return -1;
  if (state == bond_broken) return s;
  const auto& open = f.open_interface_bonds[static_cast<std::size_t>(s)];
  return std::binary_search(open.begin(), open.end(), k) ? s : -1;
}

namespace detail {

/// The bodies' largest lattice spacing.
template <int D>
double surface_spacing(const Model<D>& m) {
  double spacing = 0.0;
  for (const auto& body : m.bodies) spacing = std::max(spacing, body.constants.spacing);
  return spacing;
}

/// The longest bond that makes a patch (nearest and diagonal lattice neighbours).
template <int D>
double patch_bond_length(const Model<D>& m) {
  return 1.5 * surface_spacing<D>(m);
}

/// The unit direction of a patch's bond, from the patch's key.
template <int D>
std::array<double, 3> patch_direction(const Model<D>& m, std::int64_t key) {
  const bool cut = key < 0;
  const auto k = cut ? -1 - key : key;
  const std::array<double, 3>& xi = cut ? m.crack_bonds.xi[static_cast<std::size_t>(k)] : m.bonds.family_of(k).xi;
  const double length = cut ? m.crack_bonds.length(static_cast<std::size_t>(k)) : m.bonds.length(k);
  return {xi[0] / length, xi[1] / length, xi[2] / length};
}

/// A patch's point, its bond's midpoint, from the bond's lower end i.
template <int D>
std::array<double, 3> patch_point(const Model<D>& m, std::size_t i, std::int64_t key) {
  const bool cut = key < 0;
  const auto k = cut ? -1 - key : key;
  const std::array<double, 3>& xi = cut ? m.crack_bonds.xi[static_cast<std::size_t>(k)] : m.bonds.family_of(k).xi;
  std::array<double, 3> point{};
  for (int q = 0; q < D; ++q) point[static_cast<std::size_t>(q)] = m.reference_position[i][q] + 0.5 * xi[static_cast<std::size_t>(q)];
  return point;
}

/// Whether a particle is on a borehole's wall: a pressure bond to a fluid site as short as a
/// lattice neighbour.
template <int D>
bool on_borehole_wall(const Model<D>& m, std::size_t i, double short_bond) {
  const CrackBonds& w = m.crack_bonds;
  if (w.offset.size() != m.size() + 1) return false;
  for (auto q = w.offset[i]; q < w.offset[i + 1]; ++q)
    if (w.neighbor[static_cast<std::size_t>(q)] < 0 && w.length(static_cast<std::size_t>(q)) <= short_bond) return true;
  return false;
}

/// Whether the short network bond k = i-j (i < j) makes a patch: a bond (nearest and diagonal
/// neighbours) that broke across the crack or its extension, or from a borehole's wall; a bond
/// that broke beside the crack (a face's rock splitting) does not extend it. Before the surface is
/// first made, every short broken bond of a network is the crack's (a scene's initial state).
template <int D>
bool makes_patch(const Model<D>& m, std::size_t i, std::size_t j, std::int64_t k, double short_bond) {
  const FluidNetwork& f = m.fluid_network;
  if (!f.crack_surface.made || f.crossed_when_broken(k)) return true;
  return on_borehole_wall<D>(m, i, short_bond) || on_borehole_wall<D>(m, j, short_bond);
}

/// Whether bond entry k's bit is set in `bits`, read and set from any thread.
inline bool bit_set(const std::vector<std::uint64_t>& bits, std::int64_t k) {
  const auto word = std::atomic_ref<const std::uint64_t>(bits[static_cast<std::size_t>(k) >> 6]).load(std::memory_order_relaxed);
  return word >> (static_cast<std::size_t>(k) & 63) & 1;
}
inline void set_bit(std::vector<std::uint64_t>& bits, std::int64_t k) {
  std::atomic_ref<std::uint64_t>(bits[static_cast<std::size_t>(k) >> 6]).fetch_or(std::uint64_t{1} << (static_cast<std::size_t>(k) & 63),
                                                                                 std::memory_order_relaxed);
}

/// The patches of particle i's bonds, as (key, lower end): its network bonds that make one and the
/// short bonds a pre-crack cut where a fluid (its own or one that reached it) fills it; a pair's key
/// is its lower end's entry. With lower_only, the pairs whose lower end is i alone.
/// Whether a network bond makes a patch does not change once the surface is made (makes_patch), so
/// each entry is decided once (CrackSurface::decided, a bit per bond entry, each end its own) and
/// left alone after: the particles around a crack change again and again, and deciding their bonds
/// again took a search of the crossing bonds each (a fifth of the crack surface's time). A whole
/// family's short bonds sit at the same places in every row (short_places).
template <int D>
void patches_of_particle(const Model<D>& m, std::size_t i, double short_bond, bool lower_only,
                         std::vector<std::pair<std::int64_t, std::size_t>>& found, std::vector<std::uint64_t>& decided,
                         const std::vector<std::vector<std::uint32_t>>& short_places) {
  const FluidNetwork& f = m.fluid_network;
  const Bonds& b = m.bonds;
  const CrackBonds& w = m.crack_bonds;
  if (f.source[i] < 0) return;
  auto bond = [&](std::int64_t k) {
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    if ((lower_only && j < i) || bit_set(decided, k) || b.length(k) > short_bond || network_of_bond(f, b, i, k) < 0) return;
    const std::int64_t entry = j > i ? k : std::lower_bound(b.neighbor.begin() + b.offset[j], b.neighbor.begin() + b.offset[j + 1],
                                                            static_cast<std::int32_t>(i)) - b.neighbor.begin();
    if (makes_patch<D>(m, std::min(i, j), std::max(i, j), entry, short_bond)) found.emplace_back(entry, std::min(i, j));
    set_bit(decided, k);
  };
  const auto& body = m.bodies[m.body[i]];
  const auto& places = short_places[m.body[i]];
  if (static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]) == body.family_count && !places.empty()) {
    for (const std::uint32_t place : places) bond(b.offset[i] + place);
  } else {
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) bond(k);
  }
  if (w.offset.size() != m.size() + 1) return;
  for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
    const auto j = w.neighbor[static_cast<std::size_t>(k)];
    if (j < 0 || f.source[static_cast<std::size_t>(j)] != f.source[i] || w.length(static_cast<std::size_t>(k)) > short_bond) continue;
    if (static_cast<std::size_t>(j) > i) {
      found.emplace_back(-1 - k, i);
    } else if (!lower_only) {
      for (auto q = w.offset[static_cast<std::size_t>(j)]; q < w.offset[static_cast<std::size_t>(j) + 1]; ++q)
        if (w.neighbor[static_cast<std::size_t>(q)] == static_cast<std::int32_t>(i)) found.emplace_back(-1 - q, static_cast<std::size_t>(j));
    }
  }
}

/// The patches of the particles `particles` (patches_of_particle) not yet decided, sorted by key
/// and without repeats: the particles taken by the team, each thread's finds joined and sorted, so
/// the list does not depend on the threads (a bond both ends find is decided the same by either).
template <int D>
std::vector<std::pair<std::int64_t, std::size_t>> patches_of_particles(const Model<D>& m, const std::vector<std::size_t>& particles,
                                                                       double short_bond, bool lower_only, std::vector<std::uint64_t>& decided) {
  decided.resize((m.bonds.size() + 63) / 64, 0);
  // per body, the places in a whole family's row of the bonds no longer than short_bond (a row with
  // every offset lists them in the offsets' order)
  std::vector<std::vector<std::uint32_t>> short_places(m.bodies.size());
  for (std::size_t q = 0; q < m.bodies.size(); ++q)
    for (std::size_t a = 0; a < m.bodies[q].family_count; ++a)
      if (m.bonds.families[m.bodies[q].first_family + a].length <= short_bond) short_places[q].push_back(static_cast<std::uint32_t>(a));
  std::vector<std::pair<std::int64_t, std::size_t>> found;
#pragma omp parallel if(rift::parallel::worth_a_team(particles.size() * 16))
  {
    std::vector<std::pair<std::int64_t, std::size_t>> mine;
#pragma omp for schedule(dynamic, 256) nowait
    for (std::size_t q = 0; q < particles.size(); ++q) patches_of_particle<D>(m, particles[q], short_bond, lower_only, mine, decided, short_places);
#pragma omp critical(rift_found_patches)
    found.insert(found.end(), mine.begin(), mine.end());
  }
  rift::parallel::sort(found);
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

/// The grid of the patches' points, made from scratch.
template <int D>
void make_surface_grid(CrackSurface& s) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> entries(s.planes.size());
  for (std::size_t p = 0; p < s.planes.size(); ++p)
    entries[p] = {surface_cell_key<D>(surface_cell_of<D>(s.planes[p].data(), s.cell)), static_cast<std::uint32_t>(p)};
  std::sort(entries.begin(), entries.end());
  s.cell_keys.resize(entries.size()), s.in_cell.resize(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e) s.cell_keys[e] = entries[e].first, s.in_cell[e] = entries[e].second;
  index_surface_rows(s);
}

/// Adds the patches `found` (key and lower end, by key ascending, none of them on the surface yet)
/// at the end, their points into the grid and their keys into the sorted list (merges: the surface
/// is not sorted again).
template <int D>
void add_patches(const Model<D>& m, CrackSurface& s, const std::vector<std::pair<std::int64_t, std::size_t>>& found) {
  const std::size_t first = s.planes.size();
  std::vector<std::pair<std::int64_t, std::uint32_t>> entries(found.size());
  for (std::size_t q = 0; q < found.size(); ++q) {
    const auto point = patch_point<D>(m, found[q].second, found[q].first);
    s.patches.push_back(found[q].first);
    s.planes.push_back({point[0], point[1], point[2], 0.0, 0.0, 0.0});  // the normal comes later
    entries[q] = {surface_cell_key<D>(surface_cell_of<D>(point.data(), s.cell)), static_cast<std::uint32_t>(first + q)};
  }
  std::sort(entries.begin(), entries.end());
  std::vector<std::int64_t> cell_keys(s.cell_keys.size() + entries.size());
  std::vector<std::uint32_t> in_cell(cell_keys.size());
  // the grid's order: by cell, then by patch
  for (std::size_t a = 0, c = 0, e = 0; e < cell_keys.size(); ++e) {
    const bool old = c == entries.size() || (a < s.cell_keys.size() && std::pair(s.cell_keys[a], s.in_cell[a]) < entries[c]);
    cell_keys[e] = old ? s.cell_keys[a] : entries[c].first;
    in_cell[e] = old ? s.in_cell[a++] : entries[c++].second;
  }
  s.cell_keys = std::move(cell_keys), s.in_cell = std::move(in_cell);
  index_surface_rows(s);
  const std::size_t before = s.sorted_patches.size();
  for (const auto& [key, lower] : found) s.sorted_patches.push_back(key);
  std::inplace_merge(s.sorted_patches.begin(), s.sorted_patches.begin() + static_cast<std::ptrdiff_t>(before), s.sorted_patches.end());
}

/// The units of CrackSurface::moments: n n^T of a lattice bond (nearest or diagonal neighbour) is
/// in halves, so its entries times this are whole and their sums exact in any order.
/// 2^20: within 1.5 spacings of a patch lie at most 139 others on one lattice (their sum stays
/// below 2^28), and up to 2047 where a finer body meets the coarsest (its spacing sets the reach).
inline constexpr double moment_unit = 1048576.0;

/// n n^T of a patch's bond in moment_unit, rounded (exact for a lattice bond).
template <int D>
std::array<std::int32_t, 6> patch_moment(const Model<D>& m, std::int64_t key) {
  const auto n = patch_direction<D>(m, key);
  auto whole = [](double v) { return static_cast<std::int32_t>(std::llround(v * moment_unit)); };
  return {whole(n[0] * n[0]), whole(n[1] * n[1]), whole(n[2] * n[2]), whole(n[0] * n[1]), whole(n[1] * n[2]), whole(n[0] * n[2])};
}

/// Adds `sign` times moment `add` to patch p's, from any thread (whole numbers: the sum does not
/// depend on the order).
inline void add_moment(CrackSurface& s, std::size_t p, const std::array<std::int32_t, 6>& add, int sign) {
  for (std::size_t q = 0; q < 6; ++q) std::atomic_ref<std::int32_t>(s.moments[p][q]).fetch_add(sign * add[q], std::memory_order_relaxed);
}

/// Whether two points lie within `reach` of each other.
template <int D>
bool within_reach(const double* a, const double* c, double reach) {
  double r2 = 0.0;
  for (int q = 0; q < D; ++q) r2 += (a[q] - c[q]) * (a[q] - c[q]);
  return r2 <= reach * reach;
}

/// Patch p's normal: the principal direction (the largest eigenvector, sign-free) of its moment.
template <int D>
void make_normal(CrackSurface& s, std::size_t p) {
  const auto& mo = s.moments[p];
  Eigen::Matrix<double, D, D> sum;
  if constexpr (D == 2) {
    sum << mo[0], mo[3], mo[3], mo[1];
  } else {
    sum << mo[0], mo[3], mo[5], mo[3], mo[1], mo[4], mo[5], mo[4], mo[2];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eigen(sum);
  const auto v = eigen.eigenvectors().col(D - 1);  // the largest eigenvalue's
  for (int q = 0; q < 3; ++q) s.planes[p][static_cast<std::size_t>(3 + q)] = q < D ? v[q] : 0.0;
}

/// Takes the patches from `first` on (just added) into the moments, and makes the normals again
/// where a moment changed: each new patch's moment is the sum of n n^T of the patches within 1.5
/// spacings of it (itself included), and it adds its own to the older patches within that reach.
/// `turned`: older patches whose moment changed already (patches removed near them).
/// The moments are whole numbers (moment_unit), so a patch's normal is the same however and in
/// whatever order the patches came: the surface made from scratch.
template <int D>
void take_new_patches(const Model<D>& m, CrackSurface& s, std::size_t first, std::vector<std::uint32_t> turned, double short_bond) {
  const std::size_t count = s.planes.size();
  s.moments.resize(count);
  std::vector<std::array<std::int32_t, 6>> own(count - first);
  for (std::size_t p = first; p < count; ++p) own[p - first] = patch_moment<D>(m, s.patches[p]), s.moments[p] = {};
#pragma omp parallel if(rift::parallel::worth_a_team((count - first) * 64))
  {
    std::vector<std::uint32_t> mine;  // the older patches this thread's new ones reached
#pragma omp for schedule(dynamic, 64)
    for (std::size_t p = first; p < count; ++p) {
      std::array<std::int32_t, 6> sum{};
      const double* point = s.planes[p].data();
      for_patches_near_segment<D>(s, point, point, short_bond, [&](std::uint32_t o) {
        if (!within_reach<D>(s.planes[o].data(), point, short_bond)) return false;
        const auto moment = o >= first ? own[o - first] : patch_moment<D>(m, s.patches[o]);
        for (std::size_t q = 0; q < 6; ++q) sum[q] += moment[q];
        if (o < first) add_moment(s, o, own[p - first], 1), mine.push_back(o);
        return false;
      });
      s.moments[p] = sum;
    }
#pragma omp critical(rift_turned_patches)
    turned.insert(turned.end(), mine.begin(), mine.end());
  }
  std::sort(turned.begin(), turned.end());
  turned.erase(std::unique(turned.begin(), turned.end()), turned.end());
  for (std::size_t p = first; p < count; ++p) turned.push_back(static_cast<std::uint32_t>(p));
#pragma omp parallel for if(rift::parallel::worth_a_team(turned.size() * 16)) schedule(static)
  for (std::size_t t = 0; t < turned.size(); ++t) make_normal<D>(s, turned[t]);
}

}  // namespace detail

/// Makes the crack surface again from the networks as they are (call after the fluid's labels are
/// made from scratch): the patches that came are added, those gone are removed, and the normals
/// are made again around both.
template <int D>
void remake_crack_surface(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  CrackSurface& surface = f.crack_surface;
  const std::size_t n = m.size();
  const double spacing = detail::surface_spacing<D>(m), short_bond = detail::patch_bond_length<D>(m);
  std::vector<std::size_t> all(f.source.size() == n ? n : 0);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  // every bond decided again, by the rule as it stands now (makes_patch)
  surface.decided.assign((m.bonds.size() + 63) / 64, 0);
  auto found = detail::patches_of_particles<D>(m, all, short_bond, true, surface.decided);
  std::vector<std::int64_t> keys(found.size());
  for (std::size_t q = 0; q < found.size(); ++q) keys[q] = found[q].first;
  surface.made = true;
  surface.cell = surface.reach = (1.0 + 1e-9) * spacing;  // a lattice neighbour's crossing included
  std::vector<std::int64_t> added, removed;
  std::set_difference(keys.begin(), keys.end(), surface.sorted_patches.begin(), surface.sorted_patches.end(), std::back_inserter(added));
  std::set_difference(surface.sorted_patches.begin(), surface.sorted_patches.end(), keys.begin(), keys.end(), std::back_inserter(removed));
  std::vector<std::uint32_t> turned;  // the kept patches whose moment lost a removed patch's
  if (!removed.empty()) {
    // the removed patches' moments out of those within 1.5 spacings of them that stay
    std::vector<std::uint8_t> gone(surface.patches.size(), 0), turn(surface.patches.size(), 0);
    for (std::size_t p = 0; p < surface.patches.size(); ++p) gone[p] = std::binary_search(removed.begin(), removed.end(), surface.patches[p]);
    for (std::size_t p = 0; p < surface.patches.size(); ++p) {
      if (!gone[p]) continue;
      const auto moment = detail::patch_moment<D>(m, surface.patches[p]);
      const double* point = surface.planes[p].data();
      detail::for_patches_near_segment<D>(surface, point, point, short_bond, [&](std::uint32_t o) {
        if (!gone[o] && detail::within_reach<D>(surface.planes[o].data(), point, short_bond)) detail::add_moment(surface, o, moment, -1), turn[o] = 1;
        return false;
      });
    }
    CrackSurface kept;
    kept.made = true, kept.cell = surface.cell, kept.reach = surface.reach;
    kept.decided = std::move(surface.decided);
    for (std::size_t p = 0; p < surface.patches.size(); ++p) {
      if (gone[p]) continue;
      if (turn[p]) turned.push_back(static_cast<std::uint32_t>(kept.patches.size()));
      kept.patches.push_back(surface.patches[p]);
      kept.planes.push_back(surface.planes[p]);
      kept.moments.push_back(surface.moments[p]);
    }
    std::set_difference(surface.sorted_patches.begin(), surface.sorted_patches.end(), removed.begin(), removed.end(),
                        std::back_inserter(kept.sorted_patches));
    surface = std::move(kept);
    detail::make_surface_grid<D>(surface);
  }
  std::erase_if(found, [&](const auto& p) { return !std::binary_search(added.begin(), added.end(), p.first); });
  const std::size_t first = surface.planes.size();
  detail::add_patches<D>(m, surface, found);
  detail::take_new_patches<D>(m, surface, first, std::move(turned), short_bond);
}

/// Adds to the crack surface the patches of the bonds of `changed` (the particles whose bonds broke
/// or that the fluid reached since the last update) that joined a network, and makes the normals
/// again around them. While the networks only grow no patch goes, so this is the surface made from
/// scratch (remake_crack_surface).
template <int D>
void extend_crack_surface(Model<D>& m, const std::vector<std::size_t>& changed) {
  CrackSurface& surface = m.fluid_network.crack_surface;
  const double short_bond = detail::patch_bond_length<D>(m);
  auto found = detail::patches_of_particles<D>(m, changed, short_bond, false, surface.decided);
  std::erase_if(found, [&](const auto& p) { return std::binary_search(surface.sorted_patches.begin(), surface.sorted_patches.end(), p.first); });
  if (found.empty()) return;
  const std::size_t first = surface.planes.size();
  detail::add_patches<D>(m, surface, found);
  detail::take_new_patches<D>(m, surface, first, {}, short_bond);
}

/// Keeps the bonds just broken that crossed the crack (pairs (i, k): row i's entry k), both entries.
template <int D>
void record_crossing_breaks(Model<D>& m, const std::vector<std::pair<std::size_t, std::int64_t>>& crossed) {
  if (crossed.empty()) return;
  const Bonds& b = m.bonds;
  FluidNetwork& f = m.fluid_network;
  auto& kept = f.crossing_recent;
  const std::size_t before = kept.size();
  for (const auto& [i, k] : crossed) {
    const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
    const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
    kept.push_back(k);
    kept.push_back(std::lower_bound(first, last, static_cast<std::int32_t>(i)) - b.neighbor.begin());
  }
  std::sort(kept.begin() + static_cast<std::ptrdiff_t>(before), kept.end());
  std::inplace_merge(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(before), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  if (kept.size() > f.crossing_broken.size() / 32) f.settle_crossing_broken();
}

}  // namespace rift::hf
