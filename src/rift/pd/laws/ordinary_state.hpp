// The force state of the ordinary state-based laws (LPS, VES, EPS; Silling et al. 2007, eq. 88-92):
//   t_i<j> = b_ij p_i + a_i g_ij omega e_d,   p_i = kappa theta_i - a_i P_i / d,   a_i = A_dev / m_i,
// with b_ij the dilatation weight (surface_correction.hpp; without it d omega |xi| / m_i), g_ij the
// influence factor and e_d the deviatoric extension (VES, EPS: less lambda e_h). Written once: the
// row passes, the vector runs, the bond-pair stress and the network load all call these.
#pragma once

namespace rift::pd {

/// t_i<j> of one end of a bond: b_ij p_i + a_i g_ij omega e_d.
[[gnu::always_inline]] inline double force_state(double dilatation_weight, double pressure, double a, double correction, double omega,
                                                 double deviatoric) {
  return dilatation_weight * pressure + a * correction * omega * deviatoric;
}

/// b_ij of end i without the surface correction, LAMMPS's d omega |xi| / m_i, as its scale d / m_i:
/// the passes take omega |xi| per bond and this per particle (zero for a particle without a family).
template <int D>
double dilatation_scale(double weighted_volume) {
  return weighted_volume > 0.0 ? D / weighted_volume : 0.0;
}

/// p_i = kappa theta_i - a_i P_i / d.
template <int D>
double pressure_factor(double kappa, double theta, double a, double coupling) {
  return kappa * theta - a * coupling / D;
}

}  // namespace rift::pd
