// The plastic part of the elastic-plastic state-based law (EPS; Mitchell 2011, "A nonlocal, ordinary,
// state-based plasticity model for peridynamics", SAND2011-3166; laws/eps.hpp). Each direction of
// every bond keeps its plastic deviatoric extension e_p (bonds.hpp back_extension, the VES history's
// slots). The trial deviatoric force state of particle i is t_d = a_i sigma_ij (e_d - e_p), a_i =
// A_dev / m_i; where ||t_d||^2 / 2 = sum_j t_d^2 V_j / 2 passes psi_0 (YieldShear) the state returns to the yield
// surface, t_d -> beta_i t_d with beta_i = sqrt(2 psi_0) / ||t_d|| (Mitchell's return map), and
// e_p -> e_p + (1 - beta_i)(e_d - e_p), which keeps t_d = a sigma (e_d - e_p) for any influence
// function (Mitchell's e_p + lambda t_d where omega = 1). beta of both ends enters the pair force, so
// the pair keeps Newton's third law.
#pragma once
#include <cmath>
#include <vector>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/material_constants.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// psi_0 of particle i: ||t_d||^2 / 2 of its family under a homogeneous pure shear tau = sigma_Y /
/// sqrt(3) (von Mises), the orientations of the shear averaged: with its bonds' factors,
/// ||t_d||^2 = a_i^2 |dev eps|^2 sum_j (g omega |xi|)^2 V_j (2/15 in 3D, 1/4 in 2D), |dev eps|^2 =
/// gamma^2 / 2, every bond of the row counted (broken ones too: damage does not move the yield
/// surface). A particle a surface cuts then yields under the homogeneous deformation that yields the
/// bulk, as its surface correction makes it carry the bulk's stress. On the continuum's whole
/// family, 3D and omega = 1: 25 sigma_Y^2 / (8 pi delta^5), Mitchell's.
struct YieldShear {
  double factor = 0.0;  // |dev eps|^2 (2/15 or 1/4) / 2 at the yield shear: psi_0 = factor a^2 sum (g omega |xi|)^2 V
  template <int D>
  static YieldShear of(const MaterialConstants& c) {
    const double gamma = c.yield_stress / (std::sqrt(3.0) * c.shear_modulus);
    return {0.5 * (0.5 * gamma * gamma) * (D == 3 ? 2.0 / 15.0 : 0.25)};
  }
};

/// beta_i of every owned particle of the body (1 where the trial state lies inside the yield
/// surface), from the current positions and dilatations and the stored plastic extensions.
template <int D, scene::Influence Omega>
void plastic_yield_scales(const Model<D>& m, const BodyInfo& body, std::vector<double>& beta) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double a_dev = c.lps_deviatoric_coefficient(), shear = YieldShear::of<D>(c).factor;
  for (const IndexRange& r : m.owned()) {
    const std::size_t first = std::max(r.first, body.first), last = std::min(r.last, body.last);
#pragma omp parallel for if(rift::parallel::worth_a_team(last > first ? last - first : 0)) schedule(static)
    for (std::size_t i = first; i < last; ++i) {
      beta[i] = 1.0;
      if (!(m.weighted_volume[i] > 0.0)) continue;
      const double a = a_dev / m.weighted_volume[i], theta = m.dilatation[i];
      double norm2 = 0.0, family = 0.0;
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const double xi = b.length(k), weight = a * b.correction(i, k) * influence(Omega, xi, c.horizon);
        family += weight * weight * xi * xi * b.volume(k);
        if (b.intact[static_cast<std::size_t>(k)] != bond_intact) continue;
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        const double e = norm<D>(m.position[j] - m.position[i]) - xi;
        const double t = weight * (e - theta * (xi / D) - b.back_extension[history_slot(b, body, i, k)]);
        norm2 += t * t * b.volume(k);
      }
      const double psi0 = shear * family;
      if (0.5 * norm2 > psi0) beta[i] = std::sqrt(2.0 * psi0 / norm2);
    }
  }
}

/// e_p of each direction i -> j of every intact bond of the body's particles (the window's ghosts
/// too, with their owners' beta: both ranks of a pair keep its history alike) after the return map.
template <int D>
void commit_plastic_extension(Model<D>& m, const BodyInfo& body, const std::vector<double>& beta) {
  Bonds& b = m.bonds;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    if (beta[i] == 1.0) continue;
    const double theta = m.dilatation[i], share = 1.0 - beta[i];
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (b.intact[static_cast<std::size_t>(k)] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const double xi = b.length(k);
      const double e = norm<D>(m.position[j] - m.position[i]) - xi;
      float& plastic = b.back_extension[history_slot(b, body, i, k)];
      plastic = static_cast<float>(plastic + share * (e - theta * (xi / D) - plastic));
    }
  }
}

}  // namespace rift::pd
