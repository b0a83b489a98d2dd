// The load of a fluid on the rock around the cracks it has filled: the discrete unjacketed test.
// A solid whose cracks all hold fluid at p, and whose outer boundary carries -p too, is compressed
// uniformly by -p I with no effective stress (Biot coefficient 1: the unjacketed compression test;
// Detournay and Cheng 1993, section 2.2). Terzaghi's split of a pressurized crack into a dry crack under
// the effective stress and that uniform state (effective_stretch.hpp) holds in the discrete model
// only if the fluid's forces keep the uniform compression in equilibrium there. The force flux of
// -p I across each broken bond (the cut bonds of crack_pressure.hpp) does so in the continuum limit
// only: with a horizon of 3 spacings the uniform state is left with a residual of 60% of the face
// load in the row at a tip, and a pressurized tip starts at 1.02-1.10 K_Ic where a dry one starts
// at 0.97-1.06. So the fluid of source s loads particle i by p_s g_s,i, with g defined by the model
// itself:
//   g_s,i = (F_i(eps) - F_i^s(eps)) / (eps d kappa_i),
// F(eps) the internal force density with every particle moved by a uniform expansion x = (1 + eps) X
// and the bonds as they are, F^s the same with the broken bonds of s's network held intact. Every model
// is linear in a uniform expansion (e = eps |xi|, y / |y| = xi / |xi|), so g does not depend on eps,
// and the uniform strain -p / (d kappa) is an equilibrium of the network with its load: a grown tip
// under pressure starts at the dry tip's K (tests/test_crack_tip_initiation.cpp). Over a flat crack
// in the LPS g puts the traction p on each face (the lattice's virial is exact for a uniform strain;
// tests/test_crack_pressure.cpp); it differs from the flux only where the families are not whole. The viscoelastic model loads with its
// instantaneous (LPS) response. The pre-crack's cut bonds and a borehole's wall keep the force flux
// (crack_pressure.hpp); the cavity volume is the work conjugate of both (fluid_network.hpp).
// F and F^s differ only within reach of the network's bonds: on their ends, whose dilatation (and P)
// change, and on those ends' neighbours. So g is evaluated bond by bond on those particles alone
// (the dilatations on their neighbours too), the rest of the body untouched: the thesis-size block
// (4 million particles) took two passes over all its 494 million directed bonds whenever a crack grew.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <vector>

#include "rift/pd/fluid_network.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/pmb.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

namespace detail {

/// Adds to `set` (marked in `in`) the neighbours of its particles, through bonds of any state.
inline void add_neighbours(const Bonds& b, std::vector<std::size_t>& set, std::vector<std::uint8_t>& in) {
  const std::size_t before = set.size();
  for (std::size_t q = 0; q < before; ++q)
    for (auto k = b.offset[set[q]]; k < b.offset[set[q] + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (!in[j]) in[j] = 1, set.push_back(j);
    }
}

/// The internal force density of the particles `near` (no bond breaking; the VES by its LPS
/// response) under the uniform expansion y = (1 + eps) X, twice: with the bonds as they are (intact)
/// and with the network's broken bonds held intact as well (in_network(k)); returns the first less
/// the second. The formulas of pmb.hpp and lps.hpp bond by bond, both evaluations in one pass over
/// the bonds (each summed in the order it would be alone). `state` are the particles whose
/// dilatation the forces read (near and their neighbours); slot maps a particle to its place there.
template <int D, class InNetwork>
std::vector<Vec<D>> expansion_force_difference(const Model<D>& m, double eps, const std::vector<std::size_t>& near,
                                               const std::vector<std::size_t>& state, const std::vector<std::int32_t>& slot,
                                               InNetwork in_network) {
  const Bonds& b = m.bonds;
  auto bond = [&](std::size_t i, std::int64_t k, Vec<D>& eta) {  // e = |y| - |xi|, eta = y_j - y_i
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    for (int q = 0; q < D; ++q) eta[q] = (1.0 + eps) * m.reference_position[j][q] - (1.0 + eps) * m.reference_position[i][q];
    return norm<D>(eta) - b.length(k);
  };
  // alive in the cracked (0) and in the whole (1) evaluation
  auto alive = [&](std::int64_t k, bool& cracked, bool& whole) {
    cracked = b.intact[static_cast<std::size_t>(k)] == bond_intact;
    whole = cracked || in_network(k);
    return whole;
  };
  // theta_i and P_i = q_i - theta_i m_i / d (lps.hpp lps_dilatation) of the state-based particles
  std::vector<std::array<double, 2>> theta(state.size(), {0.0, 0.0}), coupling(state.size(), {0.0, 0.0});
#pragma omp parallel for if(rift::parallel::worth_a_team(state.size())) schedule(static)
  for (std::size_t s = 0; s < state.size(); ++s) {
    const std::size_t i = state[s];
    const auto& c = m.constants_of(i);
    if (c.model == scene::ModelKind::pmb) continue;
    double th[2] = {0.0, 0.0}, q[2] = {0.0, 0.0};
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      bool in[2];
      if (!alive(k, in[0], in[1])) continue;
      Vec<D> eta;
      const double xi = b.length(k), ev = bond(i, k, eta) * b.volume(k);
      const double w = influence(c.influence, xi, c.horizon) * xi * ev;
      const BondFactors& g = b.factors_of(i, k);
      for (int v = 0; v < 2; ++v)
        if (in[v]) {
          th[v] += c.surface_correction ? g.dilatation_weight * ev : w;
          q[v] += c.surface_correction ? g.correction * w : w;
        }
    }
    for (int v = 0; v < 2; ++v) {
      if (!c.surface_correction) th[v] *= dilatation_scale<D>(m.weighted_volume[i]);
      theta[s][static_cast<std::size_t>(v)] = th[v], coupling[s][static_cast<std::size_t>(v)] = q[v] - th[v] * m.weighted_volume[i] / D;
    }
  }
  std::vector<Vec<D>> difference(near.size(), Vec<D>{});
#pragma omp parallel for if(rift::parallel::worth_a_team(near.size())) schedule(static)
  for (std::size_t s = 0; s < near.size(); ++s) {
    const std::size_t i = near[s];
    const auto& c = m.constants_of(i);
    const double a_dev = c.lps_deviatoric_coefficient();
    // p, a and b of one end (lps.hpp force_state) in evaluation v
    auto end = [&](std::size_t p, std::size_t v, double& pressure, double& a) {
      const auto t = static_cast<std::size_t>(slot[p]);
      a = m.weighted_volume[p] > 0.0 ? a_dev / m.weighted_volume[p] : 0.0;
      pressure = pressure_factor<D>(c.kappa, theta[t][v], a, coupling[t][v]);
    };
    Vec<D> force[2] = {Vec<D>{}, Vec<D>{}};
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      bool in[2];
      if (!alive(k, in[0], in[1])) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      Vec<D> eta;
      const double xi = b.length(k), e = bond(i, k, eta), r = e + xi;
      const double omega = influence(c.influence, xi, c.horizon);
      for (std::size_t v = 0; v < 2; ++v) {
        if (!in[v]) continue;
        double pair;
        if (c.model == scene::ModelKind::pmb) {
          pair = pmb_bond_force(c.micromodulus, omega, e / xi, b.correction(i, k), b.mirror_correction(j, k));
        } else {
          double p_i, a_i, p_j, a_j;
          end(i, v, p_i, a_i);
          end(j, v, p_j, a_j);
          const BondFactors &g_i = b.factors_of(i, k), &g_j = b.mirror_factors_of(j, k);
          const double b_i = c.surface_correction ? double(g_i.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[i]);
          const double b_j = c.surface_correction ? double(g_j.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[j]);
          pair = force_state(b_i, p_i, a_i, g_i.correction, omega, e - theta[static_cast<std::size_t>(slot[i])][v] * (xi / D)) +
                 force_state(b_j, p_j, a_j, g_j.correction, omega, e - theta[static_cast<std::size_t>(slot[j])][v] * (xi / D));
        }
        const double scale = pair * b.volume(k) / r;
        for (int q = 0; q < D; ++q) force[v][q] += scale * eta[q];
      }
    }
    for (int q = 0; q < D; ++q) difference[s][q] = force[0][q] - force[1][q];
  }
  return difference;
}

}  // namespace detail

/// Per particle: its intact and its broken bonds, counted (bond states never heal, so any change of
/// state among its bonds changes these).
inline std::vector<std::uint64_t> bond_state_signatures(const Bonds& b, std::size_t n) {
  std::vector<std::uint64_t> signature(n);
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t intact = 0, broken = 0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto state = b.intact[static_cast<std::size_t>(k)];
      intact += state == bond_intact, broken += state == bond_broken;
    }
    signature[i] = intact | broken << 32;
  }
  return signature;
}

/// Makes g_s for every source whose network changed since the last call (call after
/// update_fluid_network). Reads the model, changes nothing of its state.
/// Incremental: g_i reads the bonds of i and of its neighbours (their dilatations), so it changes
/// only where a bond of i or of a neighbour changed state or joined or left the network since the
/// last call; g is evaluated again on those particles alone, with the same formulas in the same
/// order, so it equals g made from scratch bit for bit (tests/test_network_load.cpp).
template <int D>
void update_network_load(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  if (f.network_bonds == f.loaded_bonds) return;
  constexpr double expansion = 1e-6;
  const Bonds& b = m.bonds;
  const std::size_t n = m.size();
  // the particles whose bonds changed state since the last call (all of them the first time)
  auto signature = bond_state_signatures(b, n);
  const bool first = f.loaded_signature.size() != n;
  std::vector<std::uint8_t> state_changed(n, first ? 1 : 0);
  if (!first)
    for (std::size_t i = 0; i < n; ++i) state_changed[i] = signature[i] != f.loaded_signature[i];
  f.loaded_signature = std::move(signature);
  f.loaded_bonds.resize(f.network_bonds.size());
  f.network_load.resize(f.network_bonds.size());
  auto end_of = [&](std::int64_t k) {  // the particle whose row holds entry k
    return static_cast<std::size_t>(std::upper_bound(b.offset.begin(), b.offset.end(), k) - b.offset.begin() - 1);
  };
  std::vector<std::uint8_t> in(n, 0);
  for (std::size_t s = 0; s < f.network_bonds.size(); ++s) {
    const auto& bonds = f.network_bonds[s];  // both directions of each, ascending
    auto& g = f.network_load[s];
    if (bonds.empty()) {
      g.clear();
      f.loaded_bonds[s].clear();
      continue;
    }
    if (g.empty()) g.assign(n * D, 0.0), f.loaded_bonds[s].clear();
    // the particles whose g may change: the ends of the bonds that joined or left the network, those
    // whose bonds changed state, and the neighbours of both (near); and those whose dilatation they read
    std::vector<std::int64_t> joined_or_left;
    std::set_symmetric_difference(bonds.begin(), bonds.end(), f.loaded_bonds[s].begin(), f.loaded_bonds[s].end(),
                                  std::back_inserter(joined_or_left));
    f.loaded_bonds[s] = bonds;
    std::vector<std::size_t> near;
    std::fill(in.begin(), in.end(), 0);
    for (const std::int64_t k : joined_or_left) {
      const auto i = end_of(k);
      if (!in[i]) in[i] = 1, near.push_back(i);
    }
    for (std::size_t i = 0; i < n; ++i)
      if (state_changed[i] && !in[i]) in[i] = 1, near.push_back(i);
    if (near.empty()) continue;
    detail::add_neighbours(b, near, in);
    std::vector<std::size_t> state = near;
    detail::add_neighbours(b, state, in);
    std::vector<std::int32_t> slot(n, -1);
    for (std::size_t q = 0; q < state.size(); ++q) slot[state[q]] = static_cast<std::int32_t>(q);
    const auto difference = detail::expansion_force_difference<D>(
        m, expansion, near, state, slot, [&](std::int64_t k) { return std::binary_search(bonds.begin(), bonds.end(), k); });
    for (std::size_t q = 0; q < near.size(); ++q) {
      const std::size_t i = near[q];
      const double scale = 1.0 / (expansion * D * m.constants_of(i).kappa);
      for (int r = 0; r < D; ++r) g[i * D + static_cast<std::size_t>(r)] = difference[q][r] * scale;
    }
  }
}

}  // namespace rift::pd
