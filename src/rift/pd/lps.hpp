// Linear peridynamic solid (LPS), ordinary state-based (Silling et al. 2007, eq. 88-92; 2D: Le,
// Chan and Schwartz 2014). Two passes over the bonds: the dilatation
//   theta_i = (d / m_i) sum G_theta omega |xi| e V_j,
// then the force state. With the surface-correction factors G_theta, G_d the strain energy is
//   W_i = kappa/2 theta_i^2 + alpha_i/2 sum G_d omega (e - theta_i |xi|/d)^2 V_j,  alpha_i = A_dev / m_i,
// and the scalar force state is its derivative
//   t_i = (d/m_i) G_theta omega |xi| (kappa theta_i - alpha_i P_i / d) + alpha_i G_d omega (e - theta_i |xi| / d),
//   P_i = sum G_d omega (e - theta_i |xi|/d) |xi| V_j.
// Without correction (G = 1, P = 0) this is exactly LAMMPS peri/lps:
//   t = (3K - 5G) theta omega |xi| / m + 15 G omega e / m   (3D).
#pragma once
#include <algorithm>
#include <limits>

#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

template <int D, scene::Influence Omega>
void lps_dilatation(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double horizon = c.horizon, s00 = c.critical_stretch, alpha = c.alpha;
  const bool breakable = c.breakable;
  const bool corrected = !m.dilatation_correction.empty();
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
        b.intact[k] = 0;
        continue;
      }
      s_min = std::min(s_min, e / xi);
      const double w = influence(Omega, xi, horizon) * xi * e * b.volume[k];
      theta += corrected ? w * m.dilatation_correction[k] : w;
      q += w * b.correction[k];
    }
    theta *= D / m.weighted_volume[i];
    m.dilatation[i] = theta;
    m.dilatation_coupling[i] = corrected ? q - theta * m.deviatoric_weighted_volume[i] / D : 0.0;
    if (alpha > 0.0 && s_min < std::numeric_limits<double>::max()) m.next_stretch_limit[i] = s00 - alpha * s_min;
  }
}

template <int D, scene::Influence Omega>
void lps_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double horizon = c.horizon, kappa = c.kappa, a_dev = c.lps_deviatoric_coefficient();
  const bool corrected = !m.dilatation_correction.empty();
#pragma omp parallel for schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const Vec<D> xi_pos = m.position[i];
    const double inv_m_i = 1.0 / m.weighted_volume[i];
    const double theta_i = m.dilatation[i], p_i = m.dilatation_coupling[i];
    Vec<D> f{};
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!b.intact[k]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const Vec<D> eta = m.position[j] - xi_pos;
      const double r = norm<D>(eta);
      const double xi = b.length[k];
      const double e = r - xi;
      const double omega = influence(Omega, xi, horizon);
      const double g_theta = corrected ? m.dilatation_correction[k] : 1.0f;
      const double g_dev = b.correction[k];
      const double inv_m_j = 1.0 / m.weighted_volume[j];
      const double theta_j = m.dilatation[j], p_j = m.dilatation_coupling[j];
      // t_i<xi> + t_j<-xi>
      const double t_i = D * inv_m_i * g_theta * omega * xi * (kappa * theta_i - a_dev * inv_m_i * p_i / D) +
                         a_dev * inv_m_i * g_dev * omega * (e - theta_i * xi / D);
      const double t_j = D * inv_m_j * g_theta * omega * xi * (kappa * theta_j - a_dev * inv_m_j * p_j / D) +
                         a_dev * inv_m_j * g_dev * omega * (e - theta_j * xi / D);
      const double scalar = (t_i + t_j) * b.volume[k] / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
    }
    m.force[i] = f;
  }
}

/// W_i = kappa/2 theta_i^2 + alpha_i/2 sum G_d omega (e^d)^2 V_j (uses the current dilatation).
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
