#include "rift/pd/contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <omp.h>

#include "rift/core/error.hpp"
#include "rift/parallel/sort.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/ghost_fields.hpp"

namespace rift::pd {

template <int D>
Contact<D>::Contact(const scene::Contact& settings, const Model<D>& m) {
  enabled_ = settings.enabled;
  if (!enabled_) return;
  double min_spacing = 1e300;
  for (const auto& b : m.bodies) {
    const auto& c = b.constants;
    distance_.push_back(settings.distance * c.spacing);
    // micromodulus of the constant-influence PMB body with the same P-wave modulus
    const double kappa_equivalent = D == 3 ? 5.0 * c.p_wave_modulus() / 9.0 : 2.0 * c.p_wave_modulus() / 3.0;
    const double cc = pmb_micromodulus(D, kappa_equivalent, c.horizon, c.thickness, scene::Influence::constant);
    stiffness_.push_back(settings.stiffness * cc / c.horizon);
    max_distance_ = std::max(max_distance_, distance_.back());
    min_spacing = std::min(min_spacing, c.spacing);
  }
  skin_ = 0.5 * min_spacing;
  // s_f: half the smallest gap between a body's shortest bond and d (none: no gap, every row read)
  double gap = std::numeric_limits<double>::max();
  for (std::size_t q = 0; q < m.bodies.size(); ++q) {
    const auto& body = m.bodies[q];
    for (std::size_t f = body.first_family; f < body.first_family + body.family_count; ++f)
      gap = std::min(gap, m.bonds.families[f].length - distance_[q]);
  }
  family_skin_ = gap > 0.0 && gap < std::numeric_limits<double>::max() ? 0.5 * gap : 0.0;
  rebuild(m);
}

namespace {

/// Whether j is in i's family (bonded in the reference state, whatever the bond's state now).
inline bool in_family(const Bonds& b, std::size_t i, std::int32_t j) {
  const auto first = b.neighbor.begin() + b.offset[i], last = b.neighbor.begin() + b.offset[i + 1];
  return std::binary_search(first, last, j);
}

}  // namespace

template <int D>
void Contact<D>::rebuild(const Model<D>& m) {
  const std::size_t n = m.size();
  built_at_ = m.position;
  const double cell = max_distance_ + skin_;
  // a distributed run's particles beyond the window within reach of the owned ones
  // (contact_beyond_window.hpp): numbered n, n + 1, ... after the window's here
  const auto& comm = ranks_of(m);
  if (comm.distributed()) beyond_.gather(m, cell, comm);
  const std::size_t all = n + beyond_.size();
  auto position = [&](std::size_t i) -> const Vec<D>& { return i < n ? m.position[i] : beyond_.position[i - n]; };
  auto body = [&](std::size_t i) { return i < n ? m.body[i] : beyond_.body[i - n]; };
  // the particles sorted by cell (x fastest) on a grid over their bounding box, by the team (at the
  // thesis size, 4 million particles, a rebuild in the breaking regime comes every few dozen steps)
  const bool team = rift::parallel::worth_a_team(all);
  std::array<long, 3> low{0, 0, 0}, extent{1, 1, 1};
  std::vector<std::array<long, 3>> at(all);
  // a position past 2^40 cells from the origin (or not finite) has flown off under an unbounded
  // load: its cell number would overflow the grid's keys. Every rank stops alike (a PhysicsError).
  constexpr double farthest_cell = 1099511627776.0;  // 2^40
  std::size_t far_off = all;
#pragma omp parallel for if(team) schedule(static) reduction(min : far_off)
  for (std::size_t i = 0; i < all; ++i)
    for (int k = 0; k < D; ++k)
      if (!(std::abs(position(i)[k] / cell) < farthest_cell)) far_off = std::min(far_off, i);
  if (comm.any(far_off < all)) {
    std::string where = "on another rank";
    if (far_off < all) {
      where = "at (";
      for (int k = 0; k < D; ++k) where += fmt::format("{}{:.4g}", k ? ", " : "", position(far_off)[k]);
      where += ") m";
    }
    throw PhysicsError(fmt::format("a particle lies {}, beyond 2^40 contact cells ({:.3g} m) from the origin: it has flown off under an "
                                   "unbounded load or a time step above the stable limit",
                                   where, farthest_cell * cell));
  }
  if (all > 0) {
    long lx = std::numeric_limits<long>::max(), ly = lx, lz = D == 3 ? lx : 0;
    long hx = std::numeric_limits<long>::min(), hy = hx, hz = D == 3 ? hx : 0;
#pragma omp parallel for if(team) schedule(static) reduction(min : lx, ly, lz) reduction(max : hx, hy, hz)
    for (std::size_t i = 0; i < all; ++i) {
      for (int k = 0; k < D; ++k) at[i][k] = static_cast<long>(std::floor(position(i)[k] / cell));
      lx = std::min(lx, at[i][0]), hx = std::max(hx, at[i][0]), ly = std::min(ly, at[i][1]), hy = std::max(hy, at[i][1]);
      if constexpr (D == 3) lz = std::min(lz, at[i][2]), hz = std::max(hz, at[i][2]);
    }
    low = {lx, ly, lz};
    extent = {hx - lx + 1, hy - ly + 1, hz - lz + 1};
  }
  // (every rank alike: a rank's particles span no more cells than the whole run's)
  if (comm.any(double(extent[0]) * double(extent[1]) * double(extent[2]) > 4.6e18))
    throw PhysicsError(fmt::format("the particles span {} x {} x {} contact cells of {:.3g} m, more than 2^62 in all: fragments have flown "
                                   "off under an unbounded load or a time step above the stable limit",
                                   extent[0], extent[1], extent[2], cell));
  auto key = [&](const std::array<long, 3>& c) { return (c[2] - low[2]) * extent[1] * extent[0] + (c[1] - low[1]) * extent[0] + (c[0] - low[0]); };
  std::vector<std::pair<long, std::int32_t>> sorted(all);
  // Where the grid has not many more cells than particles, a counting sort by cell (Knuth, TAOCP
  // vol. 3, 5.2, algorithm D), whose table of where each cell's particles start then finds a row of
  // cells without a search; else (fragments flown far off) a sort and a binary search a row
  const auto cells = static_cast<std::size_t>(extent[0] * extent[1] * extent[2]);
  const bool counted = cells <= 2 * all + 1024;
  std::vector<std::uint32_t> cell_start(counted ? cells + 1 : 0, 0);
  if (counted) {
    for (std::size_t i = 0; i < all; ++i) ++cell_start[static_cast<std::size_t>(key(at[i])) + 1];
    for (std::size_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
    std::vector<std::uint32_t> next(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < all; ++i) {
      const long k = key(at[i]);
      sorted[next[static_cast<std::size_t>(k)]++] = {k, static_cast<std::int32_t>(i)};  // a cell's particles ascending: std::sort's order
    }
  } else {
#pragma omp parallel for if(team) schedule(static)
    for (std::size_t i = 0; i < all; ++i) sorted[i] = {key(at[i]), static_cast<std::int32_t>(i)};
    rift::parallel::sort(sorted);  // distinct elements: std::sort's order
  }
  // the particles of the cells [first, last] of a row, in sorted
  auto row_of_cells = [&](long first, long last) {
    if (counted)
      return std::pair{sorted.begin() + cell_start[static_cast<std::size_t>(first)], sorted.begin() + cell_start[static_cast<std::size_t>(last) + 1]};
    const auto from = std::lower_bound(sorted.begin(), sorted.end(), std::pair<long, std::int32_t>{first, 0});
    return std::pair{from, std::upper_bound(from, sorted.end(), std::pair<long, std::int32_t>{last, std::numeric_limits<std::int32_t>::max()})};
  };
  // per thread: the pairs within d + skin that no family holds (i < j, i of the window), then in rows
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> found(static_cast<std::size_t>(omp_get_max_threads()));
  const Bonds& b = m.bonds;
#pragma omp parallel if(rift::parallel::worth_a_team(n))
  {
    auto& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1024)
    for (std::size_t i = 0; i < n; ++i) {
      const long rz = D == 3 ? 1 : 0;
      for (long dz = -rz; dz <= rz; ++dz)
        for (long dy = -1; dy <= 1; ++dy) {
          const std::array<long, 3> c{std::max(at[i][0] - 1, low[0]), at[i][1] + dy, at[i][2] + dz};
          if (c[1] < low[1] || c[1] >= low[1] + extent[1] || c[2] < low[2] || c[2] >= low[2] + extent[2]) continue;
          // the cells of a row along x are one range of keys
          const long first = key(c), last = first + std::min(at[i][0] + 1, low[0] + extent[0] - 1) - c[0];
          const auto [from, to] = row_of_cells(first, last);
          for (auto it = from; it != to; ++it) {
            const auto j = static_cast<std::size_t>(it->second);
            if (j <= i) continue;
            const double d = 0.5 * (distance_[m.body[i]] + distance_[body(j)]) + skin_;
            const Vec<D> eta = position(j) - m.position[i];
            // a particle beyond the window is in no family of the window's owned particles (their
            // bonds lie in the window)
            if (dot<D>(eta, eta) < d * d && (j >= n || m.body[i] != m.body[j] || !in_family(b, i, static_cast<std::int32_t>(j))))
              mine.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
          }
        }
    }
  }
  // rows in the order of the whole run's numbers (one rank's: the window's own numbers)
  auto number = [&](std::int32_t j) {
    return j < static_cast<std::int32_t>(n) ? static_cast<std::int64_t>(m.numbering.whole(static_cast<std::size_t>(j))) : beyond_.number[static_cast<std::size_t>(j) - n];
  };
  struct Pair {
    std::int32_t row, neighbour;  // the neighbour's index here (n + k: beyond the window)
    std::int64_t number;          // the neighbour's whole-run number
  };
  std::vector<Pair> pairs;
  for (const auto& mine : found)
    for (const auto& [i, j] : mine) {
      pairs.push_back({i, j, number(j)});
      if (static_cast<std::size_t>(j) < n) pairs.push_back({j, i, number(i)});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& c) { return a.row != c.row ? a.row < c.row : a.number < c.number; });
  offset_.assign(n + 1, 0);
  for (const Pair& p : pairs) ++offset_[static_cast<std::size_t>(p.row) + 1];
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  pairs_.resize(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p) pairs_[p] = pairs[p].neighbour;
}

template <int D>
void Contact<D>::look_at_family_rows(const Model<D>& m) {
  const std::size_t n = m.size();
  const Bonds& b = m.bonds;
  family_looked_at_.resize(n);
  family_near_.resize(n);
  // on one rank, where the bodies hold every particle, each directed bond is a forward bond of a
  // body's runs (bond_runs.hpp) or its reverse: the runs read the positions a component at a time,
  // contiguous at both ends and in vectors, half the bonds, where the rows read every neighbour's
  // position (a sixteenth of a late step of the thesis-size example, looked at every 2-3 steps)
  std::size_t in_bodies = 0;
  for (const auto& body : m.bodies) in_bodies += body.last - body.first;
  const bool by_runs = !ranks_of(m).distributed() && in_bodies == n;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> u = m.displacement(i);
    for (int q = 0; q < D; ++q) family_looked_at_[i][q] = static_cast<float>(u[q]);
    NearBonds near;
    const auto length = b.offset[i + 1] - b.offset[i];
    if (length > 255) near.count = NearBonds::whole_row;
    if (!by_runs) {
      // bonds join particles of one body
      const double reach = distance_[m.body[i]] + family_skin_, reach2 = reach * reach;
      for (auto k = b.offset[i]; k < b.offset[i + 1] && near.count != NearBonds::whole_row; ++k) {
        const Vec<D> eta = m.position[static_cast<std::size_t>(b.neighbor[k])] - m.position[i];
        if (dot<D>(eta, eta) >= reach2) continue;  // a NaN position counts as near
        near.add(static_cast<std::uint8_t>(k - b.offset[i]));
      }
    }
    family_near_[i] = near;
  }
  if (by_runs) look_at_family_runs(m);
}

template <int D>
void Contact<D>::look_at_family_runs(const Model<D>& m) {
  const Bonds& b = m.bonds;
  NearBonds* const near = family_near_.data();
  for (std::size_t a = 0; a < m.bodies.size(); ++a) {
    const BodyInfo& body = m.bodies[a];
    if (body.runs.empty()) continue;
    const double reach = distance_[a] + family_skin_, reach2 = reach * reach;
    const std::array<double*, 3> x = positions_by_component<D>(m.position, body);
    // a run writes the rows of its two ends, in its slab and the next: the slabs' even-odd order
    // keeps the team's writes apart (bond_slabs.hpp for_each_slab)
    for_each_run_by_slabs(body, [&](const BondRun& run) {
      const std::size_t i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
      const double *xa = x[0] + i, *ya = x[1] + i, *xb = x[0] + j, *yb = x[1] + j, *za = nullptr, *zb = nullptr;
      if constexpr (D == 3) za = x[2] + i, zb = x[2] + j;
      double close[max_run_length];
      for (std::size_t t = 0; t < run.length; ++t) {
        double ex, ey, ez;
        // the squared length as the rows' dot<D> adds it; a NaN position counts as near
        close[t] = run_bond_vector<D>(xa, ya, za, xb, yb, zb, t, ex, ey, ez) >= reach2 ? 0.0 : 1.0;
      }
      if (!any_set(close, run.length)) return;
      for (std::size_t t = 0; t < run.length; ++t) {
        if (close[t] == 0.0) continue;
        const std::int64_t k = run_bond(b, run, t);
        near[i + t].add(static_cast<std::uint8_t>(k - b.offset[i + t]));
        near[j + t].add(static_cast<std::uint8_t>(reverse_bond(b, body, i + t, k) - b.offset[j + t]));
      }
    });
  }
}

template <int D>
void Contact<D>::add_forces(Model<D>& m) {
  if (!enabled_) return;
  double moved2 = 0.0, family_moved2 = 0.0;
  const std::size_t n = m.size();
  const bool family_rows = family_skin_ > 0.0 && family_near_.size() == n;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) reduction(max : moved2, family_moved2) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> d = m.position[i] - built_at_[i];
    moved2 = std::max(moved2, dot<D>(d, d));
    if (family_rows) {
      const Vec<D> u = m.displacement(i);
      double e2 = 0.0;
      for (int q = 0; q < D; ++q) e2 += (u[q] - family_looked_at_[i][q]) * (u[q] - family_looked_at_[i][q]);
      family_moved2 = std::max(family_moved2, e2);
    }
  }
  // a distributed run: every rank rebuilds when any particle has moved half the skin (the one
  // rank's test over the whole run), else refreshes the particles beyond its window
  const auto& comm = ranks_of(m);
  if (comm.distributed()) moved2 = comm.max(moved2);
  if (4.0 * moved2 > skin_ * skin_) rebuild(m);
  else if (comm.distributed()) beyond_.refresh(m, comm);
  // looked at again before a particle has moved s_f / 2: 0.45 leaves room for the float
  // displacements' rounding (a relative 6e-8 of displacements far below a spacing)
  if (family_skin_ > 0.0 && (!family_rows || !(family_moved2 <= 0.45 * 0.45 * family_skin_ * family_skin_))) look_at_family_rows(m);
  const NearBonds* const near = family_skin_ > 0.0 ? family_near_.data() : nullptr;
  const Bonds& b = m.bonds;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Vec<D> f{};
    bool any = false;
    auto pair = [&](std::size_t j) {
      const bool here = j < n;  // else beyond the window (contact_beyond_window.hpp)
      const auto body_j = here ? m.body[j] : beyond_.body[j - n];
      const double d = 0.5 * (distance_[m.body[i]] + distance_[body_j]);
      const Vec<D> eta = (here ? m.position[j] : beyond_.position[j - n]) - m.position[i];
      const double r2 = dot<D>(eta, eta);
      if (r2 >= d * d || r2 == 0.0) return;
      const double r = std::sqrt(r2);
      const double k = 0.5 * (stiffness_[m.body[i]] + stiffness_[body_j]);
      const double scalar = -k * (here ? m.volume[j] : beyond_.volume[j - n]) * (d - r) / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
      any = true;
    };
    // the broken bonds of i's family that may touch and the listed pairs, merged in the order of j
    // (rows of both are sorted by neighbour, the listed ones by the whole run's numbers); a failed
    // interface bond has its own contact (geomech/interface_contact.hpp)
    auto p = offset_[i];
    const auto listed_end = offset_[i + 1];
    auto listed_before = [&](std::int32_t q, std::int32_t j) {
      return q < static_cast<std::int32_t>(n) ? q < j : beyond_.number[static_cast<std::size_t>(q) - n] < static_cast<std::int64_t>(m.numbering.whole(static_cast<std::size_t>(j)));
    };
    auto family_pair = [&](std::int64_t k) {
      if (b.intact[static_cast<std::size_t>(k)] != bond_broken) return;
      const auto j = b.neighbor[static_cast<std::size_t>(k)];
      for (; p < listed_end && listed_before(pairs_[static_cast<std::size_t>(p)], j); ++p) pair(static_cast<std::size_t>(pairs_[static_cast<std::size_t>(p)]));
      pair(static_cast<std::size_t>(j));
    };
    if (near && near[i].count != NearBonds::whole_row) {
      for (std::uint8_t q = 0; q < near[i].count; ++q) family_pair(b.offset[i] + near[i].place[q]);
    } else {
      const std::uint8_t* const row = b.intact.data() + b.offset[i];
      const auto length = static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]);
      static_assert(bond_broken == 0);  // found by memchr: most rows have none
      for (auto at = static_cast<const std::uint8_t*>(std::memchr(row, 0, length)); at;
           at = static_cast<const std::uint8_t*>(std::memchr(at + 1, 0, length - static_cast<std::size_t>(at + 1 - row))))
        family_pair(b.offset[i] + (at - row));
    }
    for (; p < listed_end; ++p) pair(static_cast<std::size_t>(pairs_[static_cast<std::size_t>(p)]));
    if (any)
      for (int q = 0; q < D; ++q) m.force[i][q] += f[q];
  }
}

template class Contact<2>;
template class Contact<3>;

}  // namespace rift::pd
