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
#pragma once
#include <cstdint>
#include <vector>

#include "rift/pd/fluid_network.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/pmb.hpp"

namespace rift::pd {

namespace detail {
/// The internal force density of every particle, no bond breaking (the VES by its LPS response).
template <int D>
void elastic_forces(Model<D>& m) {
  using I = scene::Influence;
  const HeldBreaking<D> held(m);
  for (const auto& body : m.bodies) {
    const bool constant = body.constants.influence == I::constant;
    if (body.constants.model == scene::ModelKind::pmb) {
      if (constant) pmb_forces<D, I::constant>(m, body);
      else pmb_forces<D, I::inverse_distance>(m, body);
    } else {
      if (constant) lps_dilatation<D, I::constant>(m, body), state_based_forces<D, I::constant, false>(m, body);
      else lps_dilatation<D, I::inverse_distance>(m, body), state_based_forces<D, I::inverse_distance, false>(m, body);
    }
  }
}
}  // namespace detail

/// Makes g_s for every source whose network changed since the last call (call after
/// update_fluid_network). Leaves the particles' state as it found it.
template <int D>
void update_network_load(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  if (f.network_bonds == f.loaded_bonds) return;
  f.loaded_bonds = f.network_bonds;
  f.network_load.assign(f.network_bonds.size(), {});
  bool any = false;
  for (const auto& bonds : f.network_bonds) any = any || !bonds.empty();
  if (!any) return;
  // what the passes overwrite
  const auto position = m.position, force = m.force;
  const auto dilatation = m.dilatation, coupling = m.dilatation_coupling, next_limit = m.next_stretch_limit;
  constexpr double expansion = 1e-6;
  const std::size_t n = m.size();
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < D; ++q) m.position[i][q] = (1.0 + expansion) * m.reference_position[i][q];
  detail::elastic_forces<D>(m);
  const auto cracked = m.force;
  for (std::size_t s = 0; s < f.network_bonds.size(); ++s) {
    const auto& bonds = f.network_bonds[s];
    if (bonds.empty()) continue;
    std::vector<std::uint8_t> state(bonds.size());
    for (std::size_t q = 0; q < bonds.size(); ++q) {
      state[q] = m.bonds.intact[static_cast<std::size_t>(bonds[q])];
      m.bonds.intact[static_cast<std::size_t>(bonds[q])] = bond_intact;
    }
    detail::elastic_forces<D>(m);
    for (std::size_t q = 0; q < bonds.size(); ++q) m.bonds.intact[static_cast<std::size_t>(bonds[q])] = state[q];
    auto& g = f.network_load[s];
    g.assign(n * D, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double scale = 1.0 / (expansion * D * m.constants_of(i).kappa);
      for (int q = 0; q < D; ++q) g[i * D + static_cast<std::size_t>(q)] = (cracked[i][q] - m.force[i][q]) * scale;
    }
  }
  m.position = position;
  m.force = force;
  m.dilatation = dilatation;
  m.dilatation_coupling = coupling;
  m.next_stretch_limit = next_limit;
}

}  // namespace rift::pd
