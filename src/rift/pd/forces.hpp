// One evaluation of the peridynamic force density: bond forces of every body (model dispatched
// once per body, influence function as a template parameter), then contact.
#pragma once
#include <algorithm>

#include "rift/pd/contact.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// history_dt: the time the bonds' histories advance in this evaluation (VES: its back extensions;
/// EPS: its plastic extensions commit): the step of an explicit run; 0 holds them (initial forces,
/// dynamic relaxation, whose load steps commit_at_equilibrium).
template <int D>
void compute_forces(Model<D>& m, Contact<D>* contact, double history_dt = 0.0);

/// At the equilibrium of a load step of dynamic relaxation: the histories that commit there (EPS's
/// plastic extensions), from the forces of the positions reached. Nothing for the other laws.
template <int D>
void commit_at_equilibrium(Model<D>& m, Contact<D>* contact);

/// After a step: the s0 computed from this step's minimum stretch becomes current (alpha > 0).
template <int D>
void advance_stretch_limits(Model<D>& m) {
  for (const auto& body : m.bodies)
    if (body.constants.alpha > 0.0)
      std::copy(m.next_stretch_limit.begin() + body.first, m.next_stretch_limit.begin() + body.last,
                m.stretch_limit.begin() + body.first);
}

/// Particle damage: broken share of the bond volume (Silling and Askari 2005, eq. 25).
template <int D>
void update_damage(Model<D>& m);

/// Strain energy density of particle i (uses the current dilatation for LPS), its row's bonds one by
/// one.
template <int D>
double strain_energy_density(const Model<D>& m, std::size_t i);

/// The same of every particle into w (size m.size()), the bonds in runs (energy_runs.hpp).
template <int D>
void strain_energy_densities(const Model<D>& m, double* w);

struct EnergySummary {
  double kinetic = 0.0, strain = 0.0;
  std::int64_t broken_bonds = 0;  // bonds broken (each bond counted once)
  double broken_fraction = 0.0;
  // what they were counted from: the directed bonds not intact, of all directed bonds, in the rows
  // summed (a distributed run's ranks add theirs, run/distributed.hpp)
  double failed_directed = 0.0, directed = 0.0;
};
/// Kinetic and strain energy and the broken bonds of the owned particles (Model::owned) of every
/// rank, summed exactly (parallel/exact_sum.hpp: the one-rank run's bits). The strain energy visits every pair of bonds
/// again (strain_energy_densities); with `strain_energy` false it is left 0 unless a position is
/// not finite, which it then carries as NaN (runner's check_finite), and the sum costs one pass
/// over the particles and their bond states.
template <int D>
EnergySummary summarize(const Model<D>& m, bool strain_energy = true);

/// summarize and update_damage in one pass over the bond states (a history row's).
template <int D>
EnergySummary summarize_and_update_damage(Model<D>& m, bool strain_energy);

/// Directed bonds no longer intact (broken, and failed interface bonds): the owned particles' (a
/// distributed run's rank adds its owned rows).
template <int D>
std::size_t failed_bonds(const Model<D>& m);

/// Stable time step (Silling and Askari 2005, eq. 29): dt < sqrt(2 rho / sum_j V_j C_ij),
/// C_ij = c / |xi| of the PMB body with the same P-wave modulus; minimum over particles.
template <int D>
double stable_time_step(const Model<D>& m);

}  // namespace rift::pd
