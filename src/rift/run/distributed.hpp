// What a distributed peridynamic run (pd/window.hpp) gathers to one answer: the fields and states
// of the ranks' owned particles on rank 0 in the whole run's numbering (each rank owns ranges of it,
// in any order: slabs, pencils), which writes them as one rank would.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "rift/hf/crack_surface.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/normal_stress_failure.hpp"

namespace rift::run {

/// What each owned range holds (`entries_of(range, out)` appends a range's), gathered on rank 0 in
/// the whole run's order: each rank's blocks, one per range, placed by the whole-run number of the
/// range's first particle. Empty on the other ranks; a one-rank run's own.
template <int D, class T, class Entries>
std::vector<T> gather_in_whole_order(const parallel::Communicator& comm, const pd::Model<D>& m, Entries&& entries_of) {
  std::vector<std::uint64_t> heads;  // per range: its first particle's whole-run number, its entries
  std::vector<T> mine;
  for (const IndexRange& r : m.owned()) {
    if (r.first >= r.last) continue;
    const std::size_t before = mine.size();
    entries_of(r, mine);
    heads.push_back(m.numbering.whole(r.first)), heads.push_back(mine.size() - before);
  }
  if (!comm.distributed()) return mine;
  const auto all_heads = comm.gather(heads);
  const auto all = comm.gather(mine);
  if (!comm.root()) return {};
  std::vector<std::array<std::uint64_t, 3>> blocks;  // whole-run number, first entry, entries
  std::uint64_t at = 0;
  for (std::size_t q = 0; q + 1 < all_heads.size(); q += 2) blocks.push_back({all_heads[q], at, all_heads[q + 1]}), at += all_heads[q + 1];
  std::sort(blocks.begin(), blocks.end());
  std::vector<T> out;
  out.reserve(all.size());
  for (const auto& [whole, first, count] : blocks)
    out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(first), all.begin() + static_cast<std::ptrdiff_t>(first + count));
  return out;
}

/// The entries of the owned particles' rows in the whole run's order on rank 0: `width` per
/// particle, or with `offset` (a CSR's, one more than the particles) the entries [offset[i],
/// offset[i + 1]) of row i.
template <int D, class T, class Allocator>
std::vector<T> gather_rows(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<T, Allocator>& v, std::size_t width = 1,
                           const std::vector<std::int64_t>* offset = nullptr) {
  return gather_in_whole_order<D, T>(comm, m, [&](const IndexRange& r, std::vector<T>& out) {
    const auto first = offset ? static_cast<std::size_t>((*offset)[r.first]) : r.first * width;
    const auto last = offset ? static_cast<std::size_t>((*offset)[r.last]) : r.last * width;
    out.insert(out.end(), v.begin() + static_cast<std::ptrdiff_t>(first), v.begin() + static_cast<std::ptrdiff_t>(last));
  });
}

/// A per-particle field (`width` values each) of the owned particles, the whole run's on rank 0.
template <int D>
std::vector<double> gather_owned(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<double>& field,
                                 std::size_t width) {
  if (!comm.distributed()) return field;
  return gather_rows<D>(comm, m, field, width);
}

/// The owned particles' share of a per-particle array (`width` entries each), the whole run's on
/// rank 0, into `whole` there.
template <int D, class T>
void gather_into(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<T>& local, std::vector<T>* whole,
                 std::size_t width = 1) {
  if (local.empty()) return;
  auto all = gather_rows<D>(comm, m, local, width);
  if (whole) *whole = std::move(all);
}

/// The fluid's state (pd/fluid_network.hpp) gathered into the whole run's model on rank 0 (`whole`,
/// null on the other ranks): the sources' state (the same on every rank), the particles' labels,
/// marks and network load of the owned particles, and the crossing marks of their bonds (each owned
/// row is whole); the crack surface is made again there from those (hf/crack_surface.hpp: the same
/// patches and normals, whatever order they came in).
template <int D>
void gather_fluid(const parallel::Communicator& comm, const pd::Model<D>& m, pd::Model<D>* whole) {
  const pd::FluidNetwork& f = m.fluid_network;
  pd::FluidNetwork* g = whole ? &whole->fluid_network : nullptr;
  if (g) g->take_sources_state(f), g->relabel = f.relabel, g->load_from_scratch = f.load_from_scratch;
  gather_into<D>(comm, m, f.source, g ? &g->source : nullptr);
  gather_into<D>(comm, m, f.bond_counts, g ? &g->bond_counts : nullptr);
  gather_into<D>(comm, m, f.in_crack, g ? &g->in_crack : nullptr);
  gather_into<D>(comm, m, f.immersed, g ? &g->immersed : nullptr);
  gather_into<D>(comm, m, f.load_changed_mark, g ? &g->load_changed_mark : nullptr);
  if (g) g->list_load_changed_from_marks();
  // a window without pressure in its wet rock keeps none (hf/wet_rock.hpp): zeros
  if (comm.any(!f.pore_stretch.empty())) {
    std::vector<double> pore = f.pore_stretch;
    pore.resize(m.size(), 0.0);
    gather_into<D>(comm, m, pore, g ? &g->pore_stretch : nullptr);
  } else if (g) {
    g->pore_stretch.clear();
  }
  // a viscous fluid's (pd/viscous_fluid.hpp): its scalars the same on every rank, the fluid each
  // node holds and the pressure at each particle
  if (g) g->viscous = f.viscous;
  for (std::size_t s = 0; s < f.viscous.size(); ++s) {
    gather_into<D>(comm, m, f.viscous[s].stored, g ? &g->viscous[s].stored : nullptr);
    gather_into<D>(comm, m, f.viscous[s].trial, g ? &g->viscous[s].trial : nullptr);
  }
  gather_into<D>(comm, m, f.local_pressure, g ? &g->local_pressure : nullptr);
  gather_into<D>(comm, m, f.local_pore_pressure, g ? &g->local_pore_pressure : nullptr);
  // per source: the network load and its ends, where it has a network (the same on every rank)
  const std::size_t sources = f.has_network.size();
  if (g) g->network_load.assign(sources, {}), g->is_end.assign(sources, {}), g->network_ends.assign(sources, {});
  for (std::size_t s = 0; s < sources; ++s) {
    if (!f.has_network[s]) continue;
    const auto zeros_where_unsized = [&](const auto& v, std::size_t width) {
      return v.size() == m.size() * width ? v : std::remove_cvref_t<decltype(v)>(m.size() * width);
    };
    gather_into<D>(comm, m, zeros_where_unsized(f.network_load[s], D), g ? &g->network_load[s] : nullptr, D);
    gather_into<D>(comm, m, zeros_where_unsized(f.is_end[s], 1), g ? &g->is_end[s] : nullptr);
    gather_into<D>(comm, m, zeros_where_unsized(f.network_ends[s], 1), g ? &g->network_ends[s] : nullptr);
  }
  // lists of bonds (ascending) at the owned rows, sent as (row, place in the row) in the whole run's
  // numbering: the crossing marks, and the failed interface bonds each fluid fills
  const pd::Bonds& b = m.bonds;
  auto gather_bonds = [&](const std::vector<std::int64_t>& list, std::vector<std::int64_t>* into) {
    std::vector<std::int64_t> rows_and_places;
    for (const std::int64_t k : list) {
      const std::size_t i = b.row_of(k);
      if (!m.owns(i)) continue;
      rows_and_places.push_back(static_cast<std::int64_t>(m.numbering.whole(i))), rows_and_places.push_back(k - b.offset[i]);
    }
    const auto all = comm.gather(rows_and_places);
    if (!into) return;
    into->clear();
    for (std::size_t q = 0; q + 1 < all.size(); q += 2) into->push_back(whole->bonds.offset[static_cast<std::size_t>(all[q])] + all[q + 1]);
    std::sort(into->begin(), into->end());
  };
  gather_bonds(f.crossing_broken_whole(), g ? &g->crossing_broken : nullptr);
  if (g) g->crossing_recent.clear();
  if (g) g->open_interface_bonds.assign(f.open_interface_bonds.size(), {});
  for (std::size_t s = 0; s < f.open_interface_bonds.size(); ++s) gather_bonds(f.open_interface_bonds[s], g ? &g->open_interface_bonds[s] : nullptr);
  if (!g) return;
  // made as the run makes it after its first time (hf/crack_surface.hpp makes_patch)
  g->crack_surface = pd::CrackSurface{};
  g->crack_surface.made = f.crack_surface.made;
  if (g->crack_surface.made) hf::remake_crack_surface<D>(*whole);
}

/// The state of the bonds across interfaces (pd/interface_bonds.hpp) gathered into the whole run's
/// model on rank 0: each owned row's entries' slip and marks, and each owned interface particle's
/// strain (the owned rows, in order, are the whole run's rows one after the other).
template <int D>
void gather_interfaces(const parallel::Communicator& comm, const pd::Model<D>& m, pd::Model<D>* whole) {
  const pd::InterfaceBonds& ib = m.interface_bonds;
  pd::InterfaceBonds* g = whole ? &whole->interface_bonds : nullptr;
  if (ib.offset.empty()) return;
  auto entries = [&](const auto& v, auto* into) {
    auto all = gather_rows<D>(comm, m, v, 1, &ib.offset);
    if (into) *into = std::move(all);
  };
  entries(ib.slip, g ? &g->slip : nullptr);
  entries(ib.across_crack, g ? &g->across_crack : nullptr);
  // strain: per interface particle, where the law has run (on every rank alike)
  const auto& rows = ib.particles;
  const auto first_row_at = [&](std::size_t i) {
    return std::lower_bound(rows.begin(), rows.end(), static_cast<std::int32_t>(i)) - rows.begin();
  };
  if (comm.any(ib.strain.size() == rows.size() && !rows.empty())) {
    auto all = gather_in_whole_order<D, std::array<double, 9>>(comm, m, [&](const IndexRange& r, std::vector<std::array<double, 9>>& out) {
      out.insert(out.end(), ib.strain.begin() + first_row_at(r.first), ib.strain.begin() + first_row_at(r.last));
    });
    if (g) g->strain = std::move(all);
  }
}

/// A distributed run's state gathered into the whole run's model on rank 0 (`whole`, a model of the
/// same scene made there; null on the other ranks), which a checkpoint then holds as one rank's:
/// any number of ranks restarts from it. The state of what a distributed run takes: the
/// particles' fields, the bonds' states (each owned row is whole) and the VES history (each pair's
/// at its lower end, which owns it).
template <int D>
void gather_model(const parallel::Communicator& comm, const pd::Model<D>& m, pd::Model<D>* whole) {
  gather_into<D>(comm, m, m.position, whole ? &whole->position : nullptr);
  gather_into<D>(comm, m, m.velocity, whole ? &whole->velocity : nullptr);
  gather_into<D>(comm, m, m.force, whole ? &whole->force : nullptr);
  gather_into<D>(comm, m, m.body_force, whole ? &whole->body_force : nullptr);
  gather_into<D>(comm, m, m.dilatation, whole ? &whole->dilatation : nullptr);
  gather_into<D>(comm, m, m.dilatation_coupling, whole ? &whole->dilatation_coupling : nullptr);
  gather_into<D>(comm, m, m.stretch_limit, whole ? &whole->stretch_limit : nullptr);
  gather_into<D>(comm, m, m.next_stretch_limit, whole ? &whole->next_stretch_limit : nullptr);
  gather_into<D>(comm, m, m.damage, whole ? &whole->damage : nullptr);
  gather_into<D>(comm, m, m.failure_strain, whole ? &whole->failure_strain : nullptr, pd::stress_components<D>);
  const pd::Bonds& b = m.bonds;
  pd::Bonds* w = whole ? &whole->bonds : nullptr;
  {
    const auto all = gather_rows<D>(comm, m, b.intact.all(), 1, &b.offset);
    if (w) w->intact.replace().assign(all.begin(), all.end());
  }
  if (!b.back_extension.empty()) {
    gather_into<D>(comm, m, b.history_dilatation, w ? &w->history_dilatation : nullptr);
    gather_into<D>(comm, m, b.deviatoric_sum, w ? &w->deviatoric_sum : nullptr);
    gather_into<D>(comm, m, b.back_sum, w ? &w->back_sum : nullptr);
    gather_into<D>(comm, m, b.intact_weighted_volume, w ? &w->intact_weighted_volume : nullptr);
    gather_into<D>(comm, m, b.summed_bonds, w ? &w->summed_bonds : nullptr);
    // every owned particle's pairs as lower end: per forward offset, both directions and the pair's extension
    const std::vector<pd::LawTraits> laws = pd::body_laws(m.bodies);
    auto each_slot = [&laws](const pd::Model<D>& model, std::size_t from, std::size_t to, auto&& slot) {
      for (std::size_t i = from; i < to; ++i) {
        const pd::BodyInfo& body = model.bodies[model.body[i]];
        if (!laws[model.body[i]].bond_history) continue;
        for (std::size_t f = body.first_family + body.family_count / 2; f < body.first_family + body.family_count; ++f)
          slot(pd::history_index(body, i, f, 0));
      }
    };
    const auto all = gather_in_whole_order<D, float>(comm, m, [&](const IndexRange& r, std::vector<float>& mine) {
      each_slot(m, r.first, r.last, [&](std::size_t h) {
        mine.insert(mine.end(), {b.back_extension[h], b.back_extension[pd::mirror_history_slot(h)], b.last_extension[pd::pair_slot(h)]});
      });
    });
    if (w) {
      std::size_t at = 0;
      each_slot(*whole, 0, whole->size(), [&](std::size_t h) {
        w->back_extension[h] = all[at], w->back_extension[pd::mirror_history_slot(h)] = all[at + 1], w->last_extension[pd::pair_slot(h)] = all[at + 2];
        at += 3;
      });
    }
  }
  if (whole) whole->time = m.time;
  if (m.fluid_network.pressure_bonds) gather_fluid<D>(comm, m, whole);
  if (!m.interface_bonds.laws.empty()) gather_interfaces<D>(comm, m, whole);
}

/// The largest damage of the owned particles, over every rank.
template <int D>
double max_damage(const parallel::Communicator& comm, const pd::Model<D>& m) {
  double d = 0.0;
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i) d = std::max(d, m.damage[i]);
  return comm.max(d);
}

}  // namespace rift::run
