// J-integral and stress intensity factors at an explicit-crack tip (Guo and Nairn 2006, CMES 14;
// seed 002, eqs. 7, 8 and 10-22). Particle stresses, displacement gradients and energy densities are
// extrapolated to the grid per velocity field; J is integrated by the trapezoid rule along a
// rectangular grid-line contour Gamma of (2 cells) x (2 cells) cells centred on the node nearest the
// tip, split where it crosses the crack so that each crack face uses its own field (eq. 7):
//   J_m = int_Gamma [(W + K) n_m - sigma_ij n_j du_i/dx_m] dGamma   (crack-tip axes, m = 1, 2),
// plus, for dynamic problems, the area term over the region A inside Gamma (eq. 8), with the
// material points inside the contour as integration points:
//   J_m += int_A rho (a_i du_i/dx_m - v_i dv_i/dx_m) dA  ~  sum_p m_p (a_p . du/dx_m - v_p . dv/dx_m).
// G = J_1 (growth straight ahead, eq. 10). K_I and K_II partition G by the crack opening (d_n) and
// sliding (d_t) displacements at the crack point next to the tip (stationary crack, eqs. 21-22):
//   K_I = d_n / sqrt(d_n^2 + d_t^2) sqrt(G E'),  K_II = d_t / sqrt(d_n^2 + d_t^2) sqrt(G E'),
// E' = E (plane stress) or E / (1 - nu^2) (plane strain), taken from the cracked body's material.
#pragma once
#include <vector>

#include "rift/mpm/crack.hpp"
#include "rift/mpm/model.hpp"
#include "rift/mpm/solver.hpp"

namespace rift::mpm {

struct JContour {
  int cells = 2;          // the contour runs `cells` cells from the node nearest the tip
  bool area_term = true;  // eq. 8 (vanishes in static problems)
};

struct CrackTipParameters {
  double J1 = 0.0, J2 = 0.0;  // crack-tip axes: 1 along the crack growth direction, 2 normal
  double J1_area = 0.0;       // the area term's part of J1 (0 without it)
  double G = 0.0;
  double KI = 0.0, KII = 0.0;
  double opening = 0.0, sliding = 0.0;  // at the crack point next to the tip
  Vec<2> position{};                    // the tip
  double angle = 0.0;                   // crack growth direction at the tip, radians from x
  bool valid = false;                   // false: the contour misses the crack (tip too near an edge)
};

/// True when some material point lies within `radius` of x.
bool material_near(const Model<2>& m, const Vec<2>& x, double radius);

/// Crack tips inside material: those with a material point within one cell ahead of them. A crack
/// drawn from outside a body into it has one; a crack inside a body has two.
std::vector<CrackTip> interior_tips(const Model<2>& m, const CrackSet& cracks);

/// J, G, K_I, K_II at a crack tip after a solver step.
CrackTipParameters crack_tip_parameters(const Model<2>& m, const Solver<2>& solver, const CrackTip& tip, const JContour& contour);

}  // namespace rift::mpm
