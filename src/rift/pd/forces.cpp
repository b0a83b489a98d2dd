#include "rift/pd/forces.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "rift/core/phase_times.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/pd/energy_runs.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/force_stages.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/normal_stress_failure.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

template <int D>
void compute_forces(Model<D>& m, Contact<D>* contact, double history_dt) {
  PhaseClock clock(Phase::bond_passes);
  const ForceStages<D>* stages = force_stages_of(m);
  if (stages) stages->before_bond_passes(m);  // bonds across pre-existing fractures, with the last stresses
  if (!m.failure_strain.empty()) {
    update_failure_strain<D>(m);  // what the first pass breaks on
    // a bond between two ranks reads both ends' strains: the ghosts' from their owners, whose
    // rows are whole (a ghost's row is cut to the window)
    m.refresh_ghosts(m.failure_strain, stress_components<D>);
  }
  // each state-based body's rows of bond states as its dilatation pass left them, for its force
  // pass (bond_runs.hpp RowStates: the states read once a step)
  std::vector<RowStates> rows(m.bodies.size());
  for (std::size_t a = 0; a < m.bodies.size(); ++a) {
    const auto& body = m.bodies[a];
    with_law(body.constants.model, [&]<class Law>() { Law::template first_pass<D>(m, body, history_dt, &rows[a]); });
  }
  // the second pass of the state-based models needs every dilatation of the step (bodies may
  // neighbour through contact only); a distributed run's ghosts take theirs, and P, from their
  // owners, who summed them over whole families (pd/window.hpp); PMB alone reads neither
  const bool state_based =
      std::any_of(m.bodies.begin(), m.bodies.end(), [](const auto& b) { return law_traits(b.constants.model).state_based; });
  if (m.ghosts && state_based) {
    m.refresh_ghosts(m.dilatation);
    m.refresh_ghosts(m.dilatation_coupling);
  }
  for (std::size_t a = 0; a < m.bodies.size(); ++a) {
    const auto& body = m.bodies[a];
    with_law(body.constants.model, [&]<class Law>() { Law::template second_pass<D>(m, body, history_dt, &rows[a]); });
  }
  if (history_dt > 0.0) m.bonds.back_extension_at_rest = false;  // the VES pass advanced the history
  if (stages) stages->after_bond_passes(m, history_dt > 0.0);  // failed bonds across pre-existing fractures
  if (contact) {
    PhaseClock contact_clock(Phase::contact);
    contact->add_forces(m);
  }
}

template <int D>
void commit_at_equilibrium(Model<D>& m, Contact<D>* contact) {
  const bool any =
      std::any_of(m.bodies.begin(), m.bodies.end(), [](const BodyInfo& b) { return law_traits(b.constants.model).commits_at_equilibrium; });
  if (!any) return;
  compute_forces<D>(m, contact);
  for (const auto& body : m.bodies) with_law(body.constants.model, [&]<class Law>() { Law::template commit<D>(m, body); });
}

namespace {

/// Damage of row i (Silling and Askari 2005, eq. 25); its broken (or failed) directed bonds into
/// `broken`. A whole row (the AND of its states, bond_runs.hpp) without a look at its bonds' volumes.
inline double row_damage(const Bonds& b, std::size_t i, double& broken) {
  if (row_whole(b, i) == bond_intact) return 0.0;
  double all = 0.0, intact = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    const double v = b.volume(k);
    all += v;
    if (b.intact[static_cast<std::size_t>(k)] == bond_intact) intact += v;
    else broken += 1.0;
  }
  return all > 0.0 ? 1.0 - intact / all : 0.0;
}

/// What row_damage_from_bits reads of a body: its rows (bond_runs.hpp whole_rows, current at the
/// states' version; no bits where its family has more offsets than they hold), the volume of each
/// of its family offsets, and their sum in the order of the offsets (a whole row's bond volume).
struct DamageRows {
  RowStates rows;
  const FamilyOffset* families = nullptr;  // the body's first
  double whole_family_volume = 0.0;
};

template <int D>
std::vector<DamageRows> damage_rows(const Model<D>& m) {
  std::vector<DamageRows> out(m.bodies.size());
  for (std::size_t a = 0; a < m.bodies.size(); ++a) {
    const BodyInfo& body = m.bodies[a];
    if (body.last <= body.first) continue;
    DamageRows& d = out[a];
    d.rows = whole_rows(m.bonds, body);
    d.families = m.bonds.families.data() + body.first_family;
    for (std::size_t f = 0; f < body.family_count; ++f) d.whole_family_volume += d.families[f].volume;
  }
  return out;
}

/// row_damage from the bits of the row's intact family offsets (d.rows): the same sums in the same
/// order, so the same bits (a row holds its bonds by ascending family offset, discretize.cpp, and
/// the intact volume adds the set bits' volumes from the lowest up), where row_damage reads every
/// state of a row twice and each bond's family. A row of the whole family has the body's sum of
/// volumes; a row at a surface sums its own.
inline double row_damage_from_bits(const Bonds& b, const DamageRows& d, std::size_t i, double& broken) {
  const RowStates& r = d.rows;
  if (r.whole[i] == bond_intact) return 0.0;
  const auto length = static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]);
  double all = d.whole_family_volume;
  if (length != r.family_count) {
    all = 0.0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) all += b.volume(k);
  }
  double intact = 0.0;
  std::size_t count = 0;
  for (std::size_t w = 0; w < r.words; ++w) {
    std::uint64_t bits = r.intact[w * r.stride + i];
    count += static_cast<std::size_t>(std::popcount(bits));
    for (; bits != 0; bits &= bits - 1) intact += d.families[64 * w + static_cast<std::size_t>(std::countr_zero(bits))].volume;
  }
  broken += static_cast<double>(length - count);  // whole numbers: as adding one per bond
  return all > 0.0 ? 1.0 - intact / all : 0.0;
}

}  // namespace

template <int D>
void update_damage(Model<D>& m) {
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double broken = 0.0;
    m.damage[i] = row_damage(m.bonds, i, broken);
  }
}

template <int D>
double strain_energy_density(const Model<D>& m, std::size_t i) {
  const auto& body = m.bodies[m.body[i]];
  return with_law(body.constants.model, [&]<class Law>() { return Law::template energy_density<D>(m, body, i); });
}

template <int D>
void strain_energy_densities(const Model<D>& m, double* w) {
  for (const auto& body : m.bodies)
    with_law(body.constants.model, [&]<class Law>() { Law::template energy_densities<D>(m, body, w); });
}

namespace {

/// summarize, and where `damage` is given each particle's damage into it (row_damage).
template <int D>
EnergySummary summarize_rows(const Model<D>& m, bool strain_energy, double* damage) {
  // W_i of every particle first, its bonds in runs (energy_runs.hpp)
  static thread_local std::vector<double> densities;  // the calling thread's; the team reads it through the pointer
  densities.resize(strain_energy ? m.size() : 0);
  double* const density = densities.data();
  if (strain_energy) strain_energy_densities<D>(m, density);
  // each body's rows of bond states, where they hold its bits (row_damage_from_bits)
  const std::vector<DamageRows> rows = damage_rows<D>(m);
  // over the owned particles of every rank, exact (the one-rank run's bits on any cut)
  const std::vector<IndexRange> owned = m.owned();
  auto sums = parallel::exact_sums<3>(ranks_of<D>(m), owned, line_of(m), [&](std::size_t i, std::array<double, 3>& acc) {
    const double rho = m.constants_of(i).density;
    acc[0] += 0.5 * rho * dot<D>(m.velocity[i], m.velocity[i]) * m.volume[i];
    if (strain_energy) {
      acc[1] += density[i] * m.volume[i];
    } else {
      for (int k = 0; k < D; ++k)
        if (!std::isfinite(m.position[i][k])) acc[1] = std::numeric_limits<double>::quiet_NaN();
    }
    const DamageRows& r = rows[m.body[i]];
    if (r.rows.intact) {
      const double d = row_damage_from_bits(m.bonds, r, i, acc[2]);
      if (damage) damage[i] = d;
    } else if (damage) {
      damage[i] = row_damage(m.bonds, i, acc[2]);
    } else {
      for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) acc[2] += m.bonds.intact[k] != bond_intact;
    }
  });
  EnergySummary s;
  s.kinetic = sums[0];
  s.strain = sums[1];
  s.failed_directed = sums[2];
  s.directed = 0.0;
  for (const IndexRange& r : owned) s.directed += static_cast<double>(m.bonds.offset[r.last] - m.bonds.offset[r.first]);
  s.directed = ranks_of<D>(m).sum(s.directed);  // whole numbers: exact in any order
  s.broken_bonds = static_cast<std::int64_t>(s.failed_directed) / 2;
  s.broken_fraction = s.directed > 0.0 ? s.failed_directed / s.directed : 0.0;
  return s;
}

}  // namespace

template <int D>
EnergySummary summarize(const Model<D>& m, bool strain_energy) {
  return summarize_rows<D>(m, strain_energy, nullptr);
}

template <int D>
EnergySummary summarize_and_update_damage(Model<D>& m, bool strain_energy) {
  return summarize_rows<D>(m, strain_energy, m.damage.data());
}

template <int D>
double stable_time_step(const Model<D>& m) {
  double dt = std::numeric_limits<double>::max();
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    double local = std::numeric_limits<double>::max();
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) reduction(min : local) schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) {
      double sum = 0.0;
      for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) {
        const double xi = m.bonds.length(k);
        sum += m.bonds.volume(k) * std::max(1.0f, m.bonds.correction(i, k)) * c.equivalent_micromodulus *
               influence(c.influence, xi, c.horizon) / xi;
      }
      if (sum > 0.0) local = std::min(local, std::sqrt(2.0 * c.density / sum));
    }
    dt = std::min(dt, local);
  }
  return dt;
}

template <int D>
std::size_t failed_bonds(const Model<D>& m) {
  std::size_t failed = 0;
  const auto& intact = m.bonds.intact;
  if (m.bonds.offset.size() != m.size() + 1) return 0;
  for (const IndexRange& r : m.owned()) {
    const auto first = static_cast<std::size_t>(m.bonds.offset[r.first]), last = static_cast<std::size_t>(m.bonds.offset[r.last]);
#pragma omp parallel for if(rift::parallel::worth_a_team(last - first)) schedule(static) reduction(+ : failed)
    for (std::size_t k = first; k < last; ++k) failed += intact[k] != bond_intact;
  }
  return failed;
}

#define RIFT_INSTANTIATE(D)                                               \
  template void compute_forces<D>(Model<D>&, Contact<D>*, double);        \
  template void commit_at_equilibrium<D>(Model<D>&, Contact<D>*);         \
  template void update_damage<D>(Model<D>&);                              \
  template double strain_energy_density<D>(const Model<D>&, std::size_t); \
  template void strain_energy_densities<D>(const Model<D>&, double*);     \
  template EnergySummary summarize<D>(const Model<D>&, bool);             \
  template EnergySummary summarize_and_update_damage<D>(Model<D>&, bool); \
  template std::size_t failed_bonds<D>(const Model<D>&);                  \
  template double stable_time_step<D>(const Model<D>&);
RIFT_INSTANTIATE(2)
RIFT_INSTANTIATE(3)
#undef RIFT_INSTANTIATE

}  // namespace rift::pd
