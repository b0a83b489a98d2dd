// Critical stretch from the fracture energy G0. G0 is the work to separate a body across a plane
// per unit of new crack area (Silling and Askari 2005, eq. 24 for PMB). The work is computed for
// the continuum model itself by rigid separation of two half-spaces: bonds crossing the plane break
// when their stretch reaches s0, and every quantity scales with s0^2, so G0 = Gamma s0^2. For PMB
// Gamma has a closed form; for LPS (where the dilatation couples the bonds of a family) Gamma is
// evaluated by quadrature over the height above the plane, the bond length and direction, and the
// opening. Both are checked against each other and against the discrete work in the tests.
#pragma once
#include "rift/pd/material_constants.hpp"

namespace rift::pd {

/// Gamma = G0 / s0^2 by quadrature of the rigid-separation work (any dimension and influence): of a
/// state-based law (the LPS energy) or, where not `state_based`, of the PMB.
double separation_work_per_stretch2(const MaterialConstants& mc, bool state_based);
/// Closed form for PMB: 3D  G0 = (pi c s0^2 / 2) int omega r^4 dr ; 2D  G0 = c t s0^2 int omega r^3 dr.
double pmb_separation_work_per_stretch2(const MaterialConstants& mc);
/// s0 such that the work to separate the body equals G0 (the law's Gamma, laws/registry.hpp).
double critical_stretch_from_fracture_energy(const MaterialConstants& mc, double fracture_energy);

}  // namespace rift::pd
