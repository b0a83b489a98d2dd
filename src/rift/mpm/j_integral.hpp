// J-integral and stress intensity factors at an explicit-crack tip (Guo and Nairn 2006, CMES 14;
// seed 002, eqs. 7 and 10-22). Particle stresses, displacement gradients and energy densities are
// extrapolated to the grid per velocity field; J is integrated by the midpoint rule along a
// rectangular grid-line contour of n x n cells centred on the node nearest the tip, split where it
// crosses the crack so that each crack face uses its own field:
//   J_m = int_Gamma [(W + K) n_m - sigma_ij n_j du_i/dx_m] dGamma   (crack-tip axes, m = 1, 2),
// G = J_1 (growth straight ahead). K_I and K_II partition G by the crack opening (d_n) and sliding
// (d_t) displacements at the crack point next to the tip (stationary crack, eqs. 21-22):
//   K_I = d_n / sqrt(d_n^2 + d_t^2) sqrt(G E'),  K_II = d_t / sqrt(d_n^2 + d_t^2) sqrt(G E'),
// E' = E (plane stress) or E / (1 - nu^2) (plane strain). The area term of eq. 8 is not included.
#pragma once
#include "rift/mpm/crack.hpp"
#include "rift/mpm/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::mpm {

struct CrackTipParameters {
  double J1 = 0.0, J2 = 0.0;  // crack-tip axes: 1 along the crack growth direction, 2 normal
  double G = 0.0;
  double KI = 0.0, KII = 0.0;
  double opening = 0.0, sliding = 0.0;  // at the crack point next to the tip
  double angle = 0.0;                   // crack direction at the tip, radians from x
};

/// Parameters at the tip at the end of crack `c` (its last crack particle), contour of
/// `cells` x `cells` cells around the node nearest the tip.
CrackTipParameters crack_tip_parameters(const Model<2>& m, const CrackSet& cracks, std::size_t c, int cells,
                                        scene::PlaneCondition plane, double youngs_modulus, double poisson_ratio);

}  // namespace rift::mpm
