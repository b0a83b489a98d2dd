// J-integral and stress intensity factors at an explicit-crack tip (Guo and Nairn 2006, CMES 14; seed 002,
// eqs. 7, 8, 10-22). Particle stresses, displacement gradients and energy densities are extrapolated to the
// grid per velocity field; J is integrated (trapezoid rule) on a rectangular grid-line contour Gamma 2 cells
// (or `cells`) from the tip, each crack face with its own field (eq. 7), plus the dynamic area term over A
// inside Gamma (eq. 8), the material points inside as integration points (crack-tip axes, m = 1, 2):
//   J_m = int_Gamma [(W + K) n_m - sigma_ij n_j du_i/dx_m] dGamma + int_A rho (a_i du_i/dx_m - v_i dv_i/dx_m) dA
// G = J_1 (growth straight ahead, eq. 10) = (K_I^2 + K_II^2) / E', E' = E (plane stress) or E / (1 - nu^2)
// (plane strain), with K_I : K_II = d_n : d_t, crack opening to sliding at the crack point next to the tip
// (stationary crack, eqs. 21-22), or by default the interaction integral's on the same contour (Yau, Wang
// and Corten 1980; dynamic: Rethore et al. 2005; auxiliary u~, sigma~, eps~: Williams fields of unit K_I or K_II):
//   I = int_Gamma [sigma_ij eps~_ij n_1 - sigma_ij n_j du~_i/dx_1 - sigma~_ij n_j du_i/dx_1] dGamma
//       + int_A rho a_i du~_i/dx_1 dA,   K = E' I / 2.
// Why, and what was measured: docs/decisions/method-notes.md.
#pragma once
#include <vector>

#include "rift/mpm/crack.hpp"
#include "rift/mpm/model.hpp"
#include "rift/mpm/solver.hpp"

namespace rift::mpm {

/// How K_I and K_II split G: the ratio of the interaction integrals, or of the crack opening and
/// sliding displacements at the crack point next to the tip (Guo and Nairn 2006).
using ModePartition = scene::Mpm::ModePartition;

struct JContour {
  int cells = 2;          // the contour reaches at least `cells` cells from the tip on every side
  bool area_term = true;  // eq. 8 (vanishes in static problems)
  ModePartition partition = ModePartition::interaction_integral;
};

/// The contour and partition of a scene's [mpm] table.
inline JContour contour_of(const scene::Mpm& s) { return {s.j_contour, s.j_area_term, s.mode_partition}; }

struct CrackTipParameters {
  double J1 = 0.0, J2 = 0.0;  // crack-tip axes: 1 along the crack growth direction, 2 normal
  double J1_area = 0.0;       // the area term's part of J1 (0 without it)
  double G = 0.0;
  double KI = 0.0, KII = 0.0;          // sqrt(E' G) split by the contour's partition
  double KI_cod = 0.0, KII_cod = 0.0;  // split by the opening/sliding displacements (eqs. 21-22)
  double KI_interaction = 0.0, KII_interaction = 0.0;  // the interaction integrals themselves
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
