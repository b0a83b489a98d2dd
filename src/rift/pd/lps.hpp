// Linear peridynamic solid (LPS), ordinary state-based (Silling et al. 2007, eq. 88-92; 2D: Le,
// Chan and Schwartz 2014). Strain energy density of particle i, with sigma_i its influence function
// and b_ij its dilatation weights (see surface_correction.hpp; without correction sigma = omega and
// b_ij = d omega |xi| / m_i, which is exactly LAMMPS peri/lps):
//   theta_i = sum_j b_ij e_ij V_j,   e = |y| - |xi|,
//   W_i = kappa/2 theta_i^2 + (A_dev / 2 m_i) sum_j sigma_ij (e_ij - theta_i |xi|/d)^2 V_j,
// A_dev = 15 G (3D) or 8 G (2D), m_i = sum sigma_ij |xi|^2 V_j. Its derivative is the force state
//   t_i<j> = b_ij (kappa theta_i - a_i P_i / d) + a_i sigma_ij (e_ij - theta_i |xi| / d),  a_i = A_dev / m_i,
//   P_i = sum_j sigma_ij (e_ij - theta_i |xi|/d) |xi| V_j  (zero without correction),
// and the force density is f_i = sum_j (t_i<j> + t_j<i>) V_j along the deformed bond. Two passes:
// dilatation (and P), then forces. Uncorrected in 3D: t = (3K - 5G) theta omega |xi| / m + 15 G omega e / m.
#pragma once
#include <algorithm>
#include <limits>

#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// The force state t_i<j> = b_ij p_i + a_i sigma_ij e_dev of one end of a bond, p_i = kappa theta_i -
/// a_i P_i / d its pressure-like factor, e_dev its deviatoric extension (VES: less lambda e_b).
inline double force_state(float dilatation_weight, double pressure, double a, float correction, double omega, double deviatoric) {
  return dilatation_weight * pressure + a * correction * omega * deviatoric;
}

/// p_i = kappa theta_i - a_i P_i / d.
template <int D>
double pressure_factor(double kappa, double theta, double a, double coupling) {
  return kappa * theta - a * coupling / D;
}

template <int D, scene::Influence Omega>
void lps_dilatation(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double horizon = c.horizon, s00 = c.critical_stretch, alpha = c.alpha;
  const bool breakable = c.breakable;
#pragma omp parallel for schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const Vec<D> xi_pos = m.position[i];
    const double s0_i = m.stretch_limit[i];
    double theta = 0.0, q = 0.0;
    double s_min = std::numeric_limits<double>::max();
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!b.intact[k]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const double r = norm<D>(m.position[j] - xi_pos);
      const double xi = b.length[k];
      const double e = r - xi;
      if (breakable && e > xi * std::min(s0_i, m.stretch_limit[j])) {
        b.intact[k] = 0;  // the mirror bond in row j is broken by the same test
        continue;
      }
      s_min = std::min(s_min, e / xi);
      theta += b.dilatation_weight[k] * e * b.volume[k];
      q += b.correction[k] * influence(Omega, xi, horizon) * xi * e * b.volume[k];
    }
    m.dilatation[i] = theta;
    m.dilatation_coupling[i] = q - theta * m.weighted_volume[i] / D;
    if (alpha > 0.0 && s_min < std::numeric_limits<double>::max()) m.next_stretch_limit[i] = s00 - alpha * s_min;
  }
}

template <int D, scene::Influence Omega>
void lps_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double horizon = c.horizon, kappa = c.kappa, a_dev = c.lps_deviatoric_coefficient();
#pragma omp parallel for schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const Vec<D> xi_pos = m.position[i];
    const double a_i = a_dev / m.weighted_volume[i];
    const double theta_i = m.dilatation[i];
    const double pressure_i = pressure_factor<D>(kappa, theta_i, a_i, m.dilatation_coupling[i]);
    Vec<D> f{};
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!b.intact[k]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const Vec<D> eta = m.position[j] - xi_pos;
      const double r = norm<D>(eta);
      const double xi = b.length[k];
      const double e = r - xi;
      const double omega = influence(Omega, xi, horizon);
      const double a_j = a_dev / m.weighted_volume[j];
      const double theta_j = m.dilatation[j];
      const double pressure_j = pressure_factor<D>(kappa, theta_j, a_j, m.dilatation_coupling[j]);
      const double t_i = force_state(b.dilatation_weight[k], pressure_i, a_i, b.correction[k], omega, e - theta_i * xi / D);
      const double t_j = force_state(b.mirror_dilatation_weight[k], pressure_j, a_j, b.mirror_correction[k], omega, e - theta_j * xi / D);
      const double scalar = (t_i + t_j) * b.volume[k] / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
    }
    m.force[i] = f;
  }
}

/// W_i (uses the current dilatation).
template <int D>
double lps_energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double theta = m.dilatation[i];
  double dev = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (!b.intact[k]) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const double xi = b.length[k];
    const double ed = norm<D>(m.position[j] - m.position[i]) - xi - theta * xi / D;
    dev += b.correction[k] * influence(c.influence, xi, c.horizon) * ed * ed * b.volume[k];
  }
  return 0.5 * c.kappa * theta * theta + 0.5 * c.lps_deviatoric_coefficient() / m.weighted_volume[i] * dev;
}

}  // namespace rift::pd
