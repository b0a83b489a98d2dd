// Prototype microelastic brittle (PMB) bond force (Silling and Askari 2005, eq. 15-16):
// f = c omega(|xi|) s V_j along the deformed bond, s = (|y| - |xi|) / |xi|; with the surface
// correction each end contributes half with its own influence factor: c (g_i + g_j)/2 omega s V_j. A bond breaks for good
// when s exceeds min(s0_i, s0_j); s0_i = s00 - alpha s_min,i (eq. 23, as LAMMPS peri/pmb).
#pragma once
#include <algorithm>
#include <limits>

#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Bond force density per unit V_j along the deformed bond, c omega s (g_i + g_j) / 2.
inline double pmb_bond_force(double micromodulus, double omega, double s, float correction, float mirror_correction) {
  return micromodulus * omega * s * (0.5f * (correction + mirror_correction));
}

template <int D, scene::Influence Omega>
void pmb_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double micromodulus = c.micromodulus, s00 = c.critical_stretch, alpha = c.alpha, horizon = c.horizon;
  const bool breakable = c.breakable;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const Vec<D> xi_pos = m.position[i];
    const double s0_i = m.stretch_limit[i];
    const std::int64_t row_i = b.factor_row[i];
    Vec<D> f{};
    double s_min = std::numeric_limits<double>::max();
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (b.intact[k] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const Vec<D> eta = m.position[j] - xi_pos;
      const double r = norm<D>(eta);
      const FamilyOffset& family = b.families[b.family[k]];
      const double xi = family.length;
      const double s = (r - xi) / xi;
      if (breakable && s > std::min(s0_i, m.stretch_limit[j])) {
        b.intact[k] = bond_broken;
        continue;
      }
      s_min = std::min(s_min, s);
      const float g_i = b.factors[static_cast<std::size_t>(row_i + b.family[k])].correction;
      const float g_j = b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)].correction;
      const double scalar = pmb_bond_force(micromodulus, influence(Omega, xi, horizon), s, g_i, g_j) * family.volume / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
    }
    m.force[i] = f;
    if (alpha > 0.0 && s_min < std::numeric_limits<double>::max()) m.next_stretch_limit[i] = s00 - alpha * s_min;
  }
}

/// Strain energy density W_i = (1/4) sum c g_i omega s^2 |xi| V_j (for output and histories).
template <int D>
double pmb_energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  double w = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] != bond_intact) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const double xi = b.length(k);
    const double s = (norm<D>(m.position[j] - m.position[i]) - xi) / xi;
    w += influence(c.influence, xi, c.horizon) * s * s * xi * b.volume(k) * b.correction(i, k);
  }
  return 0.25 * c.micromodulus * w;
}

}  // namespace rift::pd
