// The mass balance of a lumped compressible fluid injected into a cavity (a borehole and the cracks joined
// to it), one pressure for all of it. The fluid's volume at zero pressure, (V0 + V_s) (1 + p0 / K_f) + Q t
// less what escaped, fills the cavity V and the injection system's fixed V_s at
//   p = K_f (V_fluid / (V + V_s) - 1),
// and takes no tension (p >= 0: it cavitates). Once the cavity is open to the outer surface (vented) it
// keeps the fluid it has room for at zero pressure, and the rest escapes.
// V = V0 + cavity_volume_change (fluid_network.hpp), the work conjugate of the pressure's load, linear in
// the displacements and not bounded below (overlapping faces, fragments moved into a crack): the room is
// max(V, 0). Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <algorithm>

namespace rift::hf {

struct LumpedFluidState {
  double cavity_volume = 0.0;   // the cavity's room, V >= 0 (m^3), without the injection system's
  double escaped_volume = 0.0;  // the fluid that left through the outer surface, at zero pressure (m^3)
  double pressure = 0.0;        // Pa, >= 0
};

/// The lumped fluid's state from the cavity's volume change `change` (cavity_volume_change), its
/// reference volume V0, the injection system's volume V_s, the fluid's volume at zero pressure
/// `injected` ((V0 + V_s)(1 + p0 / K_f) + Q t), whether the cavity is vented and what had escaped
/// before.
inline LumpedFluidState lumped_fluid_state(double reference_volume, double change, double system_volume, double injected, bool vented,
                                           double escaped_before, double bulk_modulus) {
  LumpedFluidState s;
  s.cavity_volume = std::max(0.0, reference_volume + change);
  const double room = s.cavity_volume + system_volume;
  s.escaped_volume = vented ? std::max(escaped_before, injected - room) : escaped_before;
  // vented, the fluid left is at most the room (zero pressure); shut, a cavity with no room left
  // cannot hold the fluid it has, and no finite pressure says so: the measure is then past where it
  // means anything, and the fluid is taken at zero pressure rather than at an infinite one
  if (vented || room <= 0.0) return s;
  s.pressure = std::max(0.0, bulk_modulus * ((injected - s.escaped_volume) / room - 1.0));
  return s;
}

}  // namespace rift::hf
