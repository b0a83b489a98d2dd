// An injected fluid that flows along its cracks: lubrication flow by the cubic law (network_flow.hpp) in
// place of the lumped fluid's one pressure, a viscosity-dominated hydraulic fracture (Adachi and Detournay
// 2002; Detournay 2004). Nodes: the borehole (with its wall's particles and a notch's faces) and every other
// particle the fluid reaches; a node holds half the volume of each flow bond it ends, the borehole's node
// also the borehole's and the injection system's. The bonds' volumes are scaled to sum to the work
// conjugate of the fluid's load (fluid_network.hpp): rock and fluid relax as one conservative system.
// Each node's fluid, as the volume it takes at zero pressure, M = V (1 + p / K_f), obeys, backward Euler,
//   V_a (1 + p_a / K_f) - M_a^n = dt (sum_b C_ab (p_b - p_a) + Q delta_a0),
// V and C from the current positions, solved at every relaxation iteration; large C: the lumped fluid.
// p >= 0 (cavitation: the fluid lag, Garagash and Detournay 2000); after breakthrough the outer surface's
// nodes hold p = 0. The rock is loaded by p_i g_s,i (network_load.hpp). Every rank solves the whole network.
// Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "rift/hf/fluid_network.hpp"
#include "rift/hf/network_flow.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/pd/ghost_fields.hpp"

namespace rift::hf {

/// A node with no room left (every bond of it shut, or the network's whole volume gone) cannot keep
/// the fluid it held: the faces squeeze it out into the open neighbour of largest volume, or
/// into the borehole's node where no neighbour is open. What every node holds is conserved.
/// `bonds` join nodes (FlowBond::i, j are node numbers).
inline void squeeze_out_closed_nodes(const std::vector<FlowBond>& bonds, const std::vector<double>& volume, std::vector<double>& held) {
  std::vector<std::int64_t> outlet(volume.size(), -1);
  for (const auto& b : bonds) {
    const std::size_t a = b.i, c = b.j;
    if (volume[c] > 0.0 && (outlet[a] < 0 || volume[c] > volume[static_cast<std::size_t>(outlet[a])])) outlet[a] = static_cast<std::int64_t>(c);
    if (volume[a] > 0.0 && (outlet[c] < 0 || volume[a] > volume[static_cast<std::size_t>(outlet[c])])) outlet[c] = static_cast<std::int64_t>(a);
  }
  for (std::size_t a = 1; a < volume.size(); ++a) {
    if (volume[a] > 0.0 || held[a] == 0.0) continue;
    held[outlet[a] >= 0 ? static_cast<std::size_t>(outlet[a]) : 0] += held[a];
    held[a] = 0.0;
  }
}

/// The flow bonds between particles as bonds between their nodes (node: per particle, its node's
/// number).
inline std::vector<FlowBond> nodes_joined(const std::vector<std::int64_t>& node, std::vector<FlowBond> bonds) {
  for (auto& b : bonds) b.i = static_cast<std::size_t>(node[b.i]), b.j = static_cast<std::size_t>(node[b.j]);
  return bonds;
}

/// Source s's viscous fluid at time t (call after update_fluid_network and update_network_load):
/// solves its nodes' pressures, writes them to m.fluid_network.local_pressure and the fluid each
/// node holds to its trial state, and returns the pressure in the borehole. A call at a later time
/// than the last first stores the last call's state as the end of the previous load step.
template <int D>
double viscous_fluid_pressure(Model<D>& m, std::size_t s, double t, double injection_rate, double bulk_modulus, double initial_pressure,
                              double system_volume = 0.0) {
  FluidNetwork& f = m.fluid_network;
  ViscousFluid& v = f.viscous[s];
  const std::size_t n = m.size();
  if (!v.started) {  // the borehole and the injection system hold (V0 + V_s) (1 + p0 / K_f) at t = 0
    v.started = true;
    v.stored_time = v.trial_time = 0.0;
    v.stored_inlet = v.trial_inlet = (f.reference_volume[s] + system_volume) * (1.0 + initial_pressure / bulk_modulus);
  }
  if (v.stored.size() != n) v.stored.assign(n, 0.0), v.trial.assign(n, 0.0);
  if (t > v.trial_time) {  // a new load step: the last state is the previous one's end
    v.stored_inlet = v.trial_inlet;
    v.stored = v.trial;
    v.stored_time = v.trial_time;
    v.trial_time = t;
  }
  const double dt = std::max(t - v.stored_time, 1e-12);
  if (f.local_pressure.size() != n) f.local_pressure.assign(n, 0.0);

  // the nodes: 0 the borehole with its wall and its notches, then every other particle the fluid
  // reaches, ascending by whole-run number (the one-rank numbering on any number of ranks), the
  // ghosts with their owners' numbers.
  const auto& ranks = ranks_of<D>(m);
  const CrackBonds& w = m.crack_bonds;
  std::vector<std::size_t> wet;
  std::vector<std::uint8_t> wall(n, 0), notch(f.dry.size(), 0);
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i) {
      if (f.source[i] != static_cast<int>(s) || (!f.immersed.empty() && f.immersed[i])) continue;
      wet.push_back(i);
      for (auto k = w.offset[i]; k < w.offset[i + 1] && !wall[i]; ++k)
        wall[i] = w.neighbor[static_cast<std::size_t>(k)] < 0 && w.source[static_cast<std::size_t>(k)] == s;
    }
  // a dry pre-crack that a wall particle's bonds cross starts in the borehole: a notch, whose faces
  // share its pressure (a pre-crack closed at first carries no flow, and the fluid would never enter)
  for (const std::size_t i : wet)
    if (wall[i] && f.enters_dry_cracks(static_cast<int>(s)))
      for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k)
        if (w.neighbor[static_cast<std::size_t>(k)] >= 0 && f.dry[w.source[static_cast<std::size_t>(k)]]) notch[w.source[static_cast<std::size_t>(k)]] = 1;
  set_on_any_rank(ranks, notch);
  std::vector<std::int64_t> node(n, -1);
  std::vector<std::size_t> owned_nodes;  // the particles of this rank's nodes other than the borehole's
  for (const std::size_t i : wet) {
    bool in_borehole = wall[i];
    for (auto k = w.offset[i]; k < w.offset[i + 1] && !in_borehole; ++k)
      in_borehole = w.neighbor[static_cast<std::size_t>(k)] >= 0 && notch[w.source[static_cast<std::size_t>(k)]];
    if (in_borehole) node[i] = 0;
    else owned_nodes.push_back(i);
  }
  // every rank's nodes by their particles' whole-run numbers, in rank order; a node's number is 1 +
  // its particle's place among them all, ascending (any cut of the particles among the ranks)
  std::vector<std::uint64_t> mine;
  for (const std::size_t i : owned_nodes) mine.push_back(m.numbering.whole(i));
  const std::vector<std::uint64_t> all_nodes = ranks.all_gather(mine);
  std::vector<std::uint64_t> ascending = all_nodes;
  std::sort(ascending.begin(), ascending.end());
  const std::size_t nodes = 1 + ascending.size();
  const auto node_of = [&](std::uint64_t whole) {
    return static_cast<std::int64_t>(1 + (std::lower_bound(ascending.begin(), ascending.end(), whole) - ascending.begin()));
  };
  for (const std::size_t i : owned_nodes) node[i] = node_of(m.numbering.whole(i));
  refresh_ghost_values<D>(m, node);
  // the flow bonds, each at its lower end's row (an owned row), between nodes: the whole network's
  // on every rank, in the one-rank order (by row, each row's as listed)
  std::vector<FlowBond> bonds;
  {
    std::vector<FlowBond> found = flow_bonds<D>(
        m, v.viscosity, wet, [&](std::size_t i, std::int64_t k, std::size_t j) { return node[j] >= 0 && carries_fluid<D>(m, k, i, j); },
        [&](std::size_t, std::int64_t k, std::size_t j) {
          return node[j] >= 0 && f.dry[w.source[static_cast<std::size_t>(k)]] && f.enters_dry_cracks(static_cast<int>(s));
        });
    std::vector<std::uint64_t> rows;
    for (const FlowBond& b : found) rows.push_back(m.numbering.whole(b.i));
    const std::vector<std::uint64_t> all_rows = ranks.all_gather(rows);
    const std::vector<FlowBond> all_bonds = ranks.all_gather(nodes_joined(node, std::move(found)));
    std::vector<std::size_t> order(all_bonds.size());
    for (std::size_t q = 0; q < order.size(); ++q) order[q] = q;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return all_rows[a] < all_rows[c]; });
    for (const std::size_t q : order) bonds.push_back(all_bonds[q]);
  }
  std::vector<double> volume(nodes, 0.0);
  const double borehole_change = cavity_volume_change<D>(m, static_cast<int>(s), true);
  // the borehole's room is no less than nothing (its measure is linear in the displacements, as the
  // lumped fluid's, lumped_fluid.hpp)
  volume[0] = std::max(0.0, f.reference_volume[s] + borehole_change) + system_volume;
  // the bonds' volumes, scaled to the work conjugate of the network's load (see the top)
  double opened = 0.0;
  for (const auto& b : bonds) opened += b.volume;
  const double network_volume = cavity_volume_change<D>(m, static_cast<int>(s)) - borehole_change;
  const double scale = opened > 0.0 ? std::max(0.0, network_volume / opened) : 0.0;
  std::vector<FlowBond> links;
  for (const auto& b : bonds) {
    volume[b.i] += 0.5 * scale * b.volume;
    volume[b.j] += 0.5 * scale * b.volume;
    if (b.i != b.j && b.conductance > 0.0) links.push_back({b.i, b.j, b.opening, b.conductance, 0.0});
  }
  // what each node held at the last load step's end, and whether it is on the outer surface
  std::vector<double> held(1, v.stored_inlet);
  std::vector<std::uint8_t> outer(1, 0);
  {
    std::vector<double> owned_held;
    std::vector<std::uint8_t> owned_outer;
    for (const std::size_t i : owned_nodes) {
      owned_held.push_back(v.stored[i]);
      owned_outer.push_back(f.outer_surface.size() == n && f.outer_surface[i]);
    }
    const auto all_held = ranks.all_gather(owned_held);
    const auto all_outer = ranks.all_gather(owned_outer);
    held.resize(nodes), outer.resize(nodes);
    for (std::size_t e = 0; e < all_nodes.size(); ++e) {
      const auto a = static_cast<std::size_t>(node_of(all_nodes[e]));
      held[a] = all_held[e], outer[a] = all_outer[e];
    }
  }
  // held at zero pressure: the nodes on the outer surface once the fluid breaks through
  std::vector<std::uint8_t> fixed(nodes, 0);
  if (s < f.vented.size() && f.vented[s]) fixed = outer;
  std::vector<double> storage(nodes), source(nodes), zero(nodes, 0.0);
  squeeze_out_closed_nodes(bonds, volume, held);
  for (std::size_t a = 0; a < nodes; ++a) {
    storage[a] = volume[a] / (bulk_modulus * dt);
    source[a] = (held[a] - volume[a]) / dt + (a == 0 ? injection_rate : 0.0);
  }
  // cavitation: the fluid takes no tension. A node whose pressure would fall below zero is held at
  // zero and only partly filled (the fluid lag behind a tip that opens faster than the fluid
  // follows), until what flows in fills it (an active set, a few solves).
  std::vector<std::uint8_t> cavitated(nodes, 0), held_at_zero(fixed);
  std::vector<double> p, inflow(nodes);
  for (int pass = 0; pass < 30; ++pass) {
    for (std::size_t a = 0; a < nodes; ++a) held_at_zero[a] = fixed[a] || cavitated[a];
    p = solve_network_pressure(links, storage, zero, source, held_at_zero, zero);
    std::fill(inflow.begin(), inflow.end(), 0.0);
    for (const auto& l : links) inflow[l.i] += l.conductance * (p[l.j] - p[l.i]), inflow[l.j] += l.conductance * (p[l.i] - p[l.j]);
    inflow[0] += injection_rate;  // the pump
    bool changed = false;
    for (std::size_t a = 0; a < nodes; ++a) {
      if (fixed[a]) continue;
      if (!cavitated[a] && p[a] < 0.0) cavitated[a] = 1, changed = true;
      else if (cavitated[a] && held[a] + dt * inflow[a] > volume[a]) cavitated[a] = 0, changed = true;
    }
    if (!changed) break;
  }
  // what each node holds: a wet node V (1 + p / K_f), a cavitated one what it held and what flowed in
  auto holds = [&](std::size_t a) {
    if (!cavitated[a]) return volume[a] * (1.0 + p[a] / bulk_modulus);
    return std::clamp(held[a] + dt * inflow[a], 0.0, volume[a]);
  };
  // the fluid each node holds now, and the pressure at each particle (the owned ones; the ghosts
  // take their owners')
  v.trial_inlet = holds(0);
  std::fill(v.trial.begin(), v.trial.end(), 0.0);
  for (const std::size_t i : owned_nodes) v.trial[i] = holds(static_cast<std::size_t>(node[i]));
  for (const std::size_t i : wet) f.local_pressure[i] = p[static_cast<std::size_t>(node[i])];
  // a particle the network loads that the fluid does not reach: the mean of its family's wet particles
  if (s < f.network_load.size() && !f.network_load[s].empty()) {
    const auto& g = f.network_load[s];
    const Bonds& b = m.bonds;
    for (const IndexRange& owned : m.owned())
      for (std::size_t i = owned.first; i < owned.last; ++i) {
        if (node[i] >= 0) continue;
        bool loaded = false;
        for (int q = 0; q < D; ++q) loaded = loaded || g[i * D + static_cast<std::size_t>(q)] != 0.0;
        if (!loaded) continue;
        double sum = 0.0;
        int count = 0;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
          const auto j = static_cast<std::size_t>(b.neighbor[k]);
          if (node[j] >= 0) sum += p[static_cast<std::size_t>(node[j])], ++count;
        }
        f.local_pressure[i] = count > 0 ? sum / count : p[0];
      }
  }
  m.refresh_ghosts(f.local_pressure);
  if (s < f.cavity_volume.size()) {
    double total = 0.0;
    for (double x : volume) total += x;
    f.cavity_volume[s] = total - system_volume;
  }
  return p[0];
}

}  // namespace rift::hf
