#include "rift/pd/window.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>

#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/normal_stress_failure.hpp"

namespace rift::pd {

template <int D>
Partition partition_by_bonds(const Model<D>& m, int ranks, std::size_t reaches) {
  Partition p;
  const std::size_t n = m.size();
  const auto& offset = m.bonds.offset;
  const auto total = static_cast<double>(offset[n]) + static_cast<double>(n);  // a particle's fields weigh as one bond
  std::vector<std::size_t> cuts(static_cast<std::size_t>(ranks) + 1, n);  // rank r owns [cuts[r], cuts[r + 1])
  cuts[0] = 0;
  std::size_t i = 0;
  for (int r = 1; r < ranks; ++r) {
    const double share = total * r / ranks;
    while (i < n && static_cast<double>(offset[i]) + static_cast<double>(i) < share) ++i;
    while (i < n && m.continues_line(i)) ++i;  // at a lattice line's start: the exact sums' units stay whole
    cuts[static_cast<std::size_t>(r)] = std::max(i, cuts[static_cast<std::size_t>(r) - 1]);
  }
  for (std::size_t a = 0; a < n; ++a)
    for (auto k = offset[a]; k < offset[a + 1]; ++k) {
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[static_cast<std::size_t>(k)]);
      p.reach = std::max(p.reach, j > a ? j - a : a - j);
    }
  for (int r = 0; r < ranks; ++r) {
    const auto first = cuts[static_cast<std::size_t>(r)], last = cuts[static_cast<std::size_t>(r) + 1];
    const std::size_t around = reaches * p.reach;
    p.owned.push_back({{first, last}});
    p.window.push_back({{first == last ? first : first - std::min(first, around), first == last ? last : std::min(n, last + around)}});
  }
  return p;
}

namespace {

/// Whether [first, last) meets one of the ranges (ascending and apart).
bool meets_any(const std::vector<IndexRange>& ranges, std::size_t first, std::size_t last) {
  const auto r = std::upper_bound(ranges.begin(), ranges.end(), first, [](std::size_t x, const IndexRange& a) { return x < a.last; });
  return r != ranges.end() && r->first < last;
}

/// The ranges' union as ranges ascending and apart.
std::vector<IndexRange> joined(std::vector<IndexRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const IndexRange& a, const IndexRange& b) { return a.first < b.first; });
  std::vector<IndexRange> out;
  for (const IndexRange& r : ranges) {
    if (r.last <= r.first) continue;
    if (!out.empty() && r.first <= out.back().last) out.back().last = std::max(out.back().last, r.last);
    else out.push_back(r);
  }
  return out;
}

/// Cuts of `parts` parts of about equal weight along one axis: the values (a lattice coordinate)
/// with their weights, cut between distinct values; part p holds the values in [cut[p], cut[p + 1])
/// (cut[0] = -inf, cut[parts] = +inf). Fewer distinct values than parts leave parts empty.
std::vector<double> cuts_by_weight(std::vector<std::pair<double, double>> value_weight, int parts) {
  std::sort(value_weight.begin(), value_weight.end());
  double total = 0.0;
  for (const auto& [value, weight] : value_weight) total += weight;
  std::vector<double> cut(static_cast<std::size_t>(parts) + 1, std::numeric_limits<double>::infinity());
  cut[0] = -std::numeric_limits<double>::infinity();
  double before = 0.0;  // the weight of the values before the one at k
  int p = 1;
  for (std::size_t k = 0; k < value_weight.size() && p < parts; ++k) {
    const bool distinct = k == 0 || value_weight[k].first > value_weight[k - 1].first;
    if (distinct && k > 0 && before >= total * p / parts) cut[static_cast<std::size_t>(p++)] = value_weight[k].first;
    before += value_weight[k].second;
  }
  return cut;
}

/// The part of `cut` (cuts_by_weight) that holds `value`.
std::size_t part_of(const std::vector<double>& cut, double value) {
  return static_cast<std::size_t>(std::upper_bound(cut.begin() + 1, cut.end() - 1, value) - (cut.begin() + 1));
}

/// The VES history of the window's bodies (bonds.hpp, bond_slabs.hpp history_index): the whole
/// blocks of Bonds::history_block particles that hold its particles, laid out as in the whole run
/// from the window's first block on, one block after the other (each part's history_base counts
/// from its body's first block, so it may be negative), and the per-particle sums.
void window_viscous_history(const Bonds& b, const std::vector<BodyInfo>& bodies, std::vector<BodyInfo>& parts, const Numbering& window,
                            Bonds& c) {
  constexpr std::size_t block = Bonds::history_block;
  std::size_t slots = 0;
  for (std::size_t q = 0; q < parts.size(); ++q) {
    BodyInfo& part = parts[q];
    const BodyInfo& body = bodies[q];
    if (!law_traits(body.constants.model).bond_history || part.last <= part.first) continue;
    const std::size_t per_block = body.family_count / 2 * 2 * block;
    const auto index = [&](std::size_t i) { return static_cast<std::size_t>(static_cast<std::int64_t>(i) - part.origin); };
    const std::size_t first_block = index(part.first) / block, blocks = index(part.last - 1) / block + 1 - first_block;
    part.history_base = static_cast<std::int64_t>(slots) - static_cast<std::int64_t>(first_block * per_block);
    for (std::size_t k = 0; k < blocks; ++k) {
      // the whole body's block that holds block k here: that of its first particle in the window
      const std::size_t first_here = std::max(part.first, static_cast<std::size_t>(part.origin + static_cast<std::int64_t>((first_block + k) * block)));
      const std::size_t whole_block = (window.whole(first_here) - body.first) / block;
      const auto from = static_cast<std::size_t>(body.history_base) + whole_block * per_block;
      c.back_extension.insert(c.back_extension.end(), b.back_extension.begin() + static_cast<std::ptrdiff_t>(from),
                              b.back_extension.begin() + static_cast<std::ptrdiff_t>(from + per_block));
      // one pair slot per two history slots (bond_slabs.hpp pair_slot): the blocks' halves
      c.last_extension.insert(c.last_extension.end(), b.last_extension.begin() + static_cast<std::ptrdiff_t>(from / 2),
                              b.last_extension.begin() + static_cast<std::ptrdiff_t>((from + per_block) / 2));
    }
    slots += blocks * per_block;
  }
  c.history_dilatation = slice(b.history_dilatation, window);
  c.deviatoric_sum = slice(b.deviatoric_sum, window);
  c.back_sum = slice(b.back_sum, window);
  c.intact_weighted_volume = slice(b.intact_weighted_volume, window);
  c.summed_bonds = slice(b.summed_bonds, window);
}

/// Drops the runs (bond_runs.hpp) without an owned end (in the ranges `owned`): the bonds between
/// two ghosts are their owners' to compute (the ghosts' fields come from there). A run with one is
/// kept whole, in its place: cut shorter it could change from the vector form to the bond-by-bond
/// one, which adds a particle's two ends of one run in the other order.
void drop_runs_of_ghosts(BodyInfo& part, const std::vector<IndexRange>& owned) {
  if (part.runs.empty()) return;
  std::vector<BondRun> kept;
  std::vector<std::size_t> slab_runs(part.slab_runs.size(), 0);
  for (std::size_t q = 0; q + 1 < part.slab_runs.size(); ++q)
    for (std::size_t k = part.slab_runs[q]; k < part.slab_runs[q + 1]; ++k) {
      const BondRun& r = part.runs[k];
      const auto i = static_cast<std::size_t>(r.i), j = static_cast<std::size_t>(r.j);
      const bool owned_lower = meets_any(owned, i, i + r.length), owned_upper = meets_any(owned, j, j + r.length);
      if (!owned_lower && !owned_upper) continue;
      kept.push_back(r);
      ++slab_runs[q + 1];
    }
  for (std::size_t q = 0; q + 1 < slab_runs.size(); ++q) slab_runs[q + 1] += slab_runs[q];
  part.runs = std::move(kept);
  part.slab_runs = std::move(slab_runs);
}

/// The window's pressure bonds (hf/crack_pressure.hpp), each row cut to the fluid sites and the
/// neighbours inside the window (only ghosts' rows lose bonds); its fluid is hf/window_fluid.hpp's.
template <int D>
void window_pressure_bonds(const Model<D>& m, const Numbering& window, Model<D>& w) {
  const CrackBonds& from = m.crack_bonds;
  CrackBonds& to = w.crack_bonds;
  to.offset.assign(w.size() + 1, 0);
  if (from.neighbor.empty()) return;
  for_each_in(window, [&](std::size_t a, std::size_t i) {
    for (auto k = static_cast<std::size_t>(from.offset[i]); k < static_cast<std::size_t>(from.offset[i + 1]); ++k) {
      const std::int32_t j = from.neighbor[k];
      const std::size_t j_here = j < 0 ? Numbering::none : window.here(static_cast<std::size_t>(j));
      if (j >= 0 && j_here == Numbering::none) continue;
      to.neighbor.push_back(j < 0 ? j : static_cast<std::int32_t>(j_here));
      to.volume.push_back(from.volume[k]);
      to.source.push_back(from.source[k]);
      to.xi.push_back(from.xi[k]);
      to.fluid_weighted_volume.push_back(from.fluid_weighted_volume[k]);
      to.coefficient.push_back(from.coefficient[k]);
    }
    to.offset[a + 1] = static_cast<std::int64_t>(to.neighbor.size());
  });
}

/// The window's bonds across pre-existing fractures (interface_bonds.hpp): each row's entries whose
/// bond is in the window (only ghosts' rows lose entries), at their bonds' places in the window's
/// rows, with each entry's slip and mark and each particle's strain as the whole model has them.
template <int D>
void window_interface_bonds(const Model<D>& m, const Numbering& window, Model<D>& w) {
  const InterfaceBonds& from = m.interface_bonds;
  InterfaceBonds& to = w.interface_bonds;
  to.laws = from.laws;
  if (from.offset.empty()) return;
  const Bonds& b = m.bonds;
  const Bonds& c = w.bonds;
  const bool slips = from.slip.size() == from.slot.size(), marks = from.across_crack.size() == from.slot.size();
  const bool strains = !from.strain.empty() && from.strain.size() == from.particles.size();
  to.offset.assign(w.size() + 1, 0);
  for_each_in(window, [&](std::size_t a, std::size_t i) {
    for (auto q = static_cast<std::size_t>(from.offset[i]); q < static_cast<std::size_t>(from.offset[i + 1]); ++q) {
      const std::size_t j = window.here(static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(from.slot[q])]));
      if (j == Numbering::none) continue;
      const auto first = c.neighbor.begin() + c.offset[a], last = c.neighbor.begin() + c.offset[a + 1];
      to.slot.push_back(std::lower_bound(first, last, static_cast<std::int32_t>(j)) - c.neighbor.begin());
      to.interface.push_back(from.interface[q]);
      if (slips) to.slip.push_back(from.slip[q]);
      if (marks) to.across_crack.push_back(from.across_crack[q]);
    }
    to.offset[a + 1] = static_cast<std::int64_t>(to.slot.size());
    if (to.offset[a + 1] == to.offset[a]) return;
    to.particles.push_back(static_cast<std::int32_t>(a));
    if (strains) {
      const auto row = std::lower_bound(from.particles.begin(), from.particles.end(), static_cast<std::int32_t>(i)) - from.particles.begin();
      to.strain.push_back(from.strain[static_cast<std::size_t>(row)]);
    }
  });
}

}  // namespace

template <int D>
std::vector<IndexRange> with_whole_runs(const Model<D>& m, const std::vector<IndexRange>& owned, std::vector<IndexRange> window) {
  for (const BodyInfo& body : m.bodies)
    for (const BondRun& run : body.runs) {
      const auto i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
      if (!meets_any(owned, i, i + run.length) && !meets_any(owned, j, j + run.length)) continue;
      window.push_back({i, i + run.length}), window.push_back({j, j + run.length});
    }
  return joined(std::move(window));
}

template <int D>
Partition partition_into_pencils(const Model<D>& m, int across_y, int across_z, std::size_t reaches) {
  if constexpr (D == 2) {
    return partition_by_bonds<D>(m, across_y * across_z, reaches);
  } else {
    const std::size_t n = m.size();
    const auto& x = m.reference_position;
    const auto weight = [&](std::size_t i) { return static_cast<double>(m.bonds.offset[i + 1] - m.bonds.offset[i]) + 1.0; };
    // z first, then y within each layer of boxes (a particle's fields weigh as one bond)
    std::vector<std::pair<double, double>> along;
    for (std::size_t i = 0; i < n; ++i) along.emplace_back(x[i][2], weight(i));
    const std::vector<double> z_cut = cuts_by_weight(along, across_z);
    std::vector<std::vector<std::pair<double, double>>> along_y(static_cast<std::size_t>(across_z));
    for (std::size_t i = 0; i < n; ++i) along_y[part_of(z_cut, x[i][2])].emplace_back(x[i][1], weight(i));
    std::vector<std::vector<double>> y_cut;
    for (auto& v : along_y) y_cut.push_back(cuts_by_weight(std::move(v), across_y));
    const auto ranks = static_cast<std::size_t>(across_y * across_z);
    Partition p;
    p.owned.resize(ranks);
    // each rank's owned particles: one range per layer of each body (x is the fastest of the
    // numbering, y the next)
    std::vector<Vec<D>> low(ranks, Vec<D>{}), high(ranks, Vec<D>{});
    std::vector<std::uint8_t> owns_any(ranks, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t z = part_of(z_cut, x[i][2]);
      const std::size_t r = z * static_cast<std::size_t>(across_y) + part_of(y_cut[z], x[i][1]);
      auto& owned = p.owned[r];
      if (!owned.empty() && owned.back().last == i) ++owned.back().last;
      else owned.push_back({i, i + 1});
      if (!owns_any[r]) low[r] = high[r] = x[i], owns_any[r] = 1;
      for (int k = 0; k < D; ++k) low[r][k] = std::min(low[r][k], x[i][k]), high[r][k] = std::max(high[r][k], x[i][k]);
    }
    // each window: the particles within `reaches` of the longest bond of its owned box across y and
    // z (every neighbour of an owned particle among them), grown to hold whole runs
    double longest = 0.0;
    for (const auto& f : m.bonds.families) longest = std::max(longest, f.length);
    const double margin = static_cast<double>(reaches) * longest * (1.0 + 1e-12);
    const bool ves = std::any_of(m.bodies.begin(), m.bodies.end(), [](const BodyInfo& b) { return law_traits(b.constants.model).bond_history; });
    for (std::size_t r = 0; r < ranks; ++r) {
      std::vector<IndexRange> window;
      if (owns_any[r])
        for (std::size_t i = 0; i < n; ++i) {
          if (x[i][1] < low[r][1] - margin || x[i][1] > high[r][1] + margin || x[i][2] < low[r][2] - margin || x[i][2] > high[r][2] + margin)
            continue;
          if (!window.empty() && window.back().last == i) ++window.back().last;
          else window.push_back({i, i + 1});
        }
      window = with_whole_runs<D>(m, p.owned[r], std::move(window));
      // a VES window's ranges at whole blocks of each body's history (window_viscous_history)
      if (ves) {
        std::vector<IndexRange> blocks;
        for (const IndexRange& w : window)
          for (const BodyInfo& body : m.bodies) {
            const std::size_t first = std::max(w.first, body.first), last = std::min(w.last, body.last);
            if (first >= last) continue;
            constexpr std::size_t block = Bonds::history_block;
            blocks.push_back({body.first + (first - body.first) / block * block,
                              std::min(body.last, body.first + (last - body.first + block - 1) / block * block)});
          }
        window = joined(std::move(blocks));
      }
      p.window.push_back(std::move(window));
    }
    return p;
  }
}

template <int D>
std::array<int, 2> choose_pencils(const Model<D>& m, int ranks) {
  std::array<int, 2> best{1, ranks};  // slabs
  if constexpr (D == 3) {
    const std::size_t n = m.size();
    if (n == 0) return best;
    // the lattice's lines across y, layers across z and sites along x, and the horizon in spacings
    auto distinct = [&](int axis) {
      std::vector<double> v(n);
      for (std::size_t i = 0; i < n; ++i) v[i] = m.reference_position[i][axis];
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    };
    const std::vector<double> y = distinct(1), z = distinct(2);
    double spacing = std::numeric_limits<double>::max(), longest = 0.0;
    for (std::size_t k = 1; k < z.size(); ++k) spacing = std::min(spacing, z[k] - z[k - 1]);
    for (std::size_t k = 1; k < y.size(); ++k) spacing = std::min(spacing, y[k] - y[k - 1]);
    for (const auto& f : m.bonds.families) longest = std::max(longest, f.length);
    if (!(spacing < std::numeric_limits<double>::max())) return best;
    const double ny = static_cast<double>(y.size()), nz = static_cast<double>(z.size()), nx = static_cast<double>(n) / (ny * nz);
    const double h = longest / spacing;
    // a rank's ghosts: a cut across y adds two faces of (h + the lines a run of Bonds' pairs spans)
    // lines, one across z two faces of h layers (bond_runs.hpp: a run holds up to 256 pairs)
    auto ghosts = [&](int p, int q) {
      return (p > 1 ? 2.0 * (h + 256.0 / nx) * nx * nz / q : 0.0) + (q > 1 ? 2.0 * h * nx * ny / p : 0.0);
    };
    for (int p = 2; p <= ranks; ++p) {
      if (ranks % p != 0 || static_cast<double>(p) > ny || static_cast<double>(ranks / p) > nz) continue;
      if (ghosts(p, ranks / p) < ghosts(best[0], best[1])) best = {p, ranks / p};
    }
  }
  return best;
}

template <int D>
Model<D> window_of(const Model<D>& m, const Partition& p, int rank) {
  const auto r = static_cast<std::size_t>(rank);
  const Numbering window(p.window[r]);
  const std::size_t n = count_of(p.window[r]);
  Model<D> w;
  w.reference_position = slice(m.reference_position, window);
  w.position = slice(m.position, window);
  w.velocity = slice(m.velocity, window);
  w.force = slice(m.force, window);
  w.body_force = slice(m.body_force, window);
  w.volume = slice(m.volume, window);
  w.weighted_volume = slice(m.weighted_volume, window);
  w.dilatation = slice(m.dilatation, window);
  w.dilatation_coupling = slice(m.dilatation_coupling, window);
  w.stretch_limit = slice(m.stretch_limit, window);
  w.next_stretch_limit = slice(m.next_stretch_limit, window);
  w.damage = slice(m.damage, window);
  w.failure_strain = slice(m.failure_strain, window, stress_components<D>);
  w.body = slice(m.body, window);
  w.constrained = slice(m.constrained, window);
  w.coupling = m.coupling;
  w.stages = m.stages;
  w.dimension = m.dimension;
  w.thickness = m.thickness;
  w.time = m.time;
  w.owned_ranges = window.here_of(p.owned[r]);
  if (w.owned_ranges.empty()) w.owned_ranges = {{0, 0}};  // owns none (an empty range, not one rank's none)
  w.numbering = window;

  // rows of the window, each cut to the neighbours inside it (only ghosts' rows lose bonds: their
  // ranges are cut_rows); a row of factors (bonds.hpp) comes along once however many particles share it
  const Bonds& b = m.bonds;
  Bonds& c = w.bonds;
  c.families = b.families;
  c.offset.assign(n + 1, 0);
  c.factor_row.resize(n);
  std::map<std::pair<std::int64_t, std::uint32_t>, std::int64_t> factor_rows;  // (row, body) to its place here
  BondStates::Storage& states = c.intact.replace();
  for_each_in(window, [&](std::size_t a, std::size_t i) {
    const BodyInfo& body = m.bodies[m.body[i]];
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const std::size_t j = window.here(static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]));
      if (j == Numbering::none) continue;
      c.neighbor.push_back(static_cast<std::int32_t>(j));
      c.family.push_back(b.family[static_cast<std::size_t>(k)]);
      states.push_back(b.intact[static_cast<std::size_t>(k)]);
    }
    c.offset[a + 1] = c.size();
    if (c.offset[a + 1] - c.offset[a] != b.offset[i + 1] - b.offset[i]) {
      if (!w.cut_rows.empty() && w.cut_rows.back().last == a) ++w.cut_rows.back().last;
      else w.cut_rows.push_back({a, a + 1});
    }
    const auto first_family = static_cast<std::int64_t>(body.first_family), count = static_cast<std::int64_t>(body.family_count);
    auto [row, added] = factor_rows.try_emplace({b.factor_row[i], m.body[i]}, static_cast<std::int64_t>(c.factors.size()) - first_family);
    if (added) {
      const auto from = b.factors.begin() + (b.factor_row[i] + first_family);
      c.factors.insert(c.factors.end(), from, from + count);
    }
    c.factor_row[a] = row->second;
  });
  // the bodies: the part of each inside the window, its slabs the whole body's (BodyInfo::whole_first)
  // and its runs and VES history blocks counted from the whole body's first particle
  // (BodyInfo::origin: the window's ranges of several start at whole blocks, Partition)
  for (const BodyInfo& body : m.bodies) {
    BodyInfo part = body;
    part.first = window.first_from(body.first);
    part.last = window.first_from(body.last);
    part.whole_first = body.whole_first;
    const std::size_t first_whole = part.first < part.last ? window.whole(part.first) : body.first;
    part.origin = static_cast<std::int64_t>(part.first) - static_cast<std::int64_t>(first_whole - body.first);
    make_bond_runs(c, part, window);
    drop_runs_of_ghosts(part, w.owned_ranges);
    w.bodies.push_back(std::move(part));
  }
  if (!b.back_extension.empty()) window_viscous_history(b, m.bodies, w.bodies, window, c);
  window_pressure_bonds(m, window, w);
  window_interface_bonds(m, window, w);
  // every platen, on every rank (its sums gather all ranks' owned particles: platens.hpp), with the
  // particles of its face that are in the window
  for (const Platen& plate : m.platens) {
    Platen part{plate.axis, {}};
    for (const auto i : plate.particles)
      if (const std::size_t a = window.here(i); a != Numbering::none) part.particles.push_back(a);
    w.platens.push_back(std::move(part));
  }
  return w;
}

#define RIFT_INSTANTIATE(D)                                                      \
  template Partition partition_by_bonds<D>(const Model<D>&, int, std::size_t); \
  template Partition partition_into_pencils<D>(const Model<D>&, int, int, std::size_t); \
  template std::array<int, 2> choose_pencils<D>(const Model<D>&, int); \
  template Model<D> window_of<D>(const Model<D>&, const Partition&, int);                  \
  template std::vector<IndexRange> with_whole_runs<D>(const Model<D>&, const std::vector<IndexRange>&, std::vector<IndexRange>);
RIFT_INSTANTIATE(2)
RIFT_INSTANTIATE(3)
#undef RIFT_INSTANTIATE

}  // namespace rift::pd
