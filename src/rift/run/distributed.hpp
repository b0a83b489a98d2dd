// What a distributed peridynamic run (pd/window.hpp) reduces to one answer: the history's sums over
// the ranks' owned particles, and the fields gathered to rank 0 in the whole run's numbering (the
// ranks own consecutive ranges of it, in rank order), which writes them as one rank would.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "rift/parallel/communicator.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/normal_stress_failure.hpp"

namespace rift::run {

/// The whole run's energies and broken bonds from each rank's (pd::summarize).
inline pd::EnergySummary reduce(const parallel::Communicator& comm, pd::EnergySummary e) {
  if (!comm.distributed()) return e;
  double sums[4] = {e.kinetic, e.strain, e.failed_directed, e.directed};
  comm.sum(sums, 4);
  e.kinetic = sums[0], e.strain = sums[1], e.failed_directed = sums[2], e.directed = sums[3];
  e.broken_bonds = static_cast<std::int64_t>(e.failed_directed) / 2;
  e.broken_fraction = e.directed > 0.0 ? e.failed_directed / e.directed : 0.0;
  return e;
}

/// A per-particle field (`width` values each) of the owned particles, the whole run's on rank 0.
template <int D>
std::vector<double> gather_owned(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<double>& field,
                                 std::size_t width) {
  if (!comm.distributed()) return field;
  const auto first = static_cast<std::ptrdiff_t>(m.owned_begin * width), last = static_cast<std::ptrdiff_t>(m.owned_last() * width);
  return comm.gather(std::vector<double>(field.begin() + first, field.begin() + last));
}

/// The owned particles' share of a per-particle array (`width` entries each), the whole run's on
/// rank 0, into `whole` there.
template <int D, class T>
void gather_into(const parallel::Communicator& comm, const pd::Model<D>& m, const std::vector<T>& local, std::vector<T>* whole,
                 std::size_t width = 1) {
  if (local.empty()) return;
  const auto first = static_cast<std::ptrdiff_t>(m.owned_begin * width), last = static_cast<std::ptrdiff_t>(m.owned_last() * width);
  auto all = comm.gather(std::vector<T>(local.begin() + first, local.begin() + last));
  if (whole) *whole = std::move(all);
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
    const auto first = b.intact.begin() + b.offset[m.owned_begin], last = b.intact.begin() + b.offset[m.owned_last()];
    auto all = comm.gather(std::vector<std::uint8_t>(first, last));
    if (w) w->intact = std::move(all);
  }
  if (!b.back_extension.empty()) {
    gather_into<D>(comm, m, b.history_dilatation, w ? &w->history_dilatation : nullptr);
    gather_into<D>(comm, m, b.deviatoric_sum, w ? &w->deviatoric_sum : nullptr);
    gather_into<D>(comm, m, b.back_sum, w ? &w->back_sum : nullptr);
    gather_into<D>(comm, m, b.intact_weighted_volume, w ? &w->intact_weighted_volume : nullptr);
    gather_into<D>(comm, m, b.summed_bonds, w ? &w->summed_bonds : nullptr);
    // every owned particle's pairs as lower end: per forward offset, both directions and the pair's extension
    auto each_slot = [](const pd::Model<D>& model, std::size_t from, std::size_t to, auto&& slot) {
      for (std::size_t i = from; i < to; ++i) {
        const pd::BodyInfo& body = model.bodies[model.body[i]];
        if (body.constants.model != scene::ModelKind::ves) continue;
        for (std::size_t f = body.first_family + body.family_count / 2; f < body.first_family + body.family_count; ++f)
          slot(pd::history_index(body, i, f, 0));
      }
    };
    std::vector<float> mine;
    each_slot(m, m.owned_begin, m.owned_last(), [&](std::size_t h) {
      mine.insert(mine.end(), {b.back_extension[h], b.back_extension[pd::mirror_history_slot(h)], b.last_extension[pd::pair_slot(h)]});
    });
    const auto all = comm.gather(mine);
    if (w) {
      std::size_t at = 0;
      each_slot(*whole, 0, whole->size(), [&](std::size_t h) {
        w->back_extension[h] = all[at], w->back_extension[pd::mirror_history_slot(h)] = all[at + 1], w->last_extension[pd::pair_slot(h)] = all[at + 2];
        at += 3;
      });
    }
  }
  if (whole) {
    whole->time = m.time;
    // the fluid's sources, the same on every rank; the particles' labels are made again from the
    // bonds' states where the run continues (window.hpp window_pressure_bonds)
    whole->fluid_network.take_sources_state(m.fluid_network);
  }
}

/// The largest damage of the owned particles, over every rank.
template <int D>
double max_damage(const parallel::Communicator& comm, const pd::Model<D>& m) {
  double d = 0.0;
  for (std::size_t i = m.owned_begin; i < m.owned_last(); ++i) d = std::max(d, m.damage[i]);
  return comm.max(d);
}

}  // namespace rift::run
