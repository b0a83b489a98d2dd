// Where a fluid-filled crack meets a pre-existing fracture (an interface): the junction. A failed interface
// bond is a frictional contact between its ends (geomech/interface_contact.hpp), the interface's faces pressing
// and sliding on each other. But a failed bond whose ends lie on the two faces of a crack the fluid fills,
// one that runs into the interface or through it, joins rock the fluid holds apart: its ends do not touch,
// and it carries no contact force, as a broken bond carries none. Such a bond crosses the crack's surface
// (hf/crack_surface.hpp: within half a spacing of a patch of broken rock or of a pre-crack, the crack
// itself and not its extension past the tip). The fluid's way is not changed: it enters a failed interface
// bond only where the interface's faces are apart (fluid_network.hpp carries_fluid); a bond across the
// near side's open crack that ends beyond a shut interface carries no contact force, but the fluid reaches
// its far end only through the interface. Why: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <cstdint>

#include "rift/hf/pd_names.hpp"
#include "rift/parallel/team.hpp"
#include "rift/hf/crack_surface.hpp"
#include "rift/pd/model.hpp"

namespace rift::hf {

/// Marks the failed interface bonds that cross the surface of a crack the fluid fills
/// (InterfaceBonds::across_crack). Call after the crack surface is made (hf/crack_surface.hpp).
template <int D>
void mark_bonds_across_crack(Model<D>& m) {
  InterfaceBonds& ib = m.interface_bonds;
  if (ib.empty()) return;
  ib.across_crack.resize(ib.slot.size(), 0);
  const CrackSurface& surface = m.fluid_network.crack_surface;
  const auto& rows = ib.particles;
  // the crack's patches of broken rock and of pre-cracks, not those of an open interface's own bonds
  auto of_rock = [&](std::uint32_t p) {
    const std::int64_t key = surface.patches[p];
    return key < 0 || m.bonds.intact[static_cast<std::size_t>(key)] != bond_interface_failed;
  };
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    const double reach = (0.5 + 1e-9) * m.constants_of(i).spacing;
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[k]);
      ib.across_crack[static_cast<std::size_t>(q)] =
          m.bonds.intact[k] == bond_interface_failed && pierces_crack_if<D>(surface, m.reference_position[i], m.reference_position[j], reach, of_rock);
    }
  }
}

}  // namespace rift::hf
