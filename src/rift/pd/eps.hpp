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

#include "rift/pd/bond_runs.hpp"
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

/// The sums of each particle's family over the body's runs (bond_runs.hpp, in the passes' order of
/// slabs, so the same bits on any thread count and any rank's window): ||t_d||^2 of its trial state
/// over its intact bonds into norm2, and sum_j (a_i g omega |xi|)^2 V_j over every bond of its row
/// (broken ones too: damage does not move the yield surface) into family2.
template <int D, scene::Influence Omega, bool Corrected>
void deviatoric_norms(const Model<D>& m, const BodyInfo& body, const RowStates& rows, double* norm2, double* family2) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double a_dev = c.lps_deviatoric_coefficient();
  double* const a = pass_buffer(m.size(), PassBuffer::deviatoric_coefficient);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j) {
    a[j] = m.weighted_volume[j] > 0.0 ? a_dev / m.weighted_volume[j] : 0.0;
    norm2[j] = 0.0, family2[j] = 0.0;
  }
  const auto x = positions_by_component<D>(m.position, body);
  const double* const theta = m.dilatation.data();
  for_each_run_by_slabs(body, [&](const BondRun& run) {
    const FamilyOffset& family = b.families[run.family];
    const double xi = family.length, omega = influence(Omega, xi, c.horizon), length_over_d = xi / D, xi2v = xi * xi * family.volume;
    const std::size_t h = history_index(body, static_cast<std::size_t>(run.i), run.family, 0);  // the run's bonds in consecutive slots
    const float* const back_i = b.back_extension.data() + h;
    const float* const back_j = b.back_extension.data() + mirror_history_slot(h);
    for (std::size_t t = 0; t < run.length; ++t) {
      const std::size_t i = static_cast<std::size_t>(run.i) + t, j = static_cast<std::size_t>(run.j) + t;
      double g_i = 1.0, g_j = 1.0;
      if constexpr (Corrected) {
        g_i = b.factors[static_cast<std::size_t>(b.factor_row[i] + run.family)].correction;
        g_j = b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)].correction;
      }
      const double w_i = a[i] * g_i * omega, w_j = a[j] * g_j * omega;
      family2[i] += w_i * w_i * xi2v, family2[j] += w_j * w_j * xi2v;
      if (!run_bond_intact(b, run, rows, t)) continue;
      const double e = norm<D>(run_ends_at<D>(run, t, x).eta) - xi;
      const double t_i = w_i * (e - theta[i] * length_over_d - back_i[t]), t_j = w_j * (e - theta[j] * length_over_d - back_j[t]);
      norm2[i] += t_i * t_i * family.volume, norm2[j] += t_j * t_j * family.volume;
    }
  });
}

/// beta_i of every particle of the body (1 where the trial state lies inside the yield surface),
/// from the current positions and dilatations and the stored plastic extensions: the owned
/// particles' (a ghost's sums are cut to the window; its owner's beta comes in the exchange).
template <int D, scene::Influence Omega>
void plastic_yield_scales(const Model<D>& m, const BodyInfo& body, const RowStates& rows, std::vector<double>& beta) {
  const double shear = YieldShear::of<D>(body.constants).factor;
  double* const norm2 = pass_buffer(m.size(), PassBuffer::coupling);
  double* const family2 = pass_buffer(m.size(), PassBuffer::smallest_stretch);
  if (body.constants.surface_correction) deviatoric_norms<D, Omega, true>(m, body, rows, norm2, family2);
  else deviatoric_norms<D, Omega, false>(m, body, rows, norm2, family2);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const double psi0 = shear * family2[i];
    beta[i] = 0.5 * norm2[i] > psi0 ? std::sqrt(2.0 * psi0 / norm2[i]) : 1.0;
  }
}

/// e_p of both directions of every intact bond of the body's runs after the return map, e_p +=
/// (1 - beta)(e_d - e_p) with each end's beta (the window's ghosts' from their owners: both ranks of
/// a pair keep its history alike).
template <int D>
void commit_plastic_extension(Model<D>& m, const BodyInfo& body, const RowStates& rows, const std::vector<double>& beta) {
  Bonds& b = m.bonds;
  const auto x = positions_by_component<D>(m.position, body);
  const double* const theta = m.dilatation.data();
  for_each_run_by_slabs(body, [&](const BondRun& run) {
    const FamilyOffset& family = b.families[run.family];
    const double xi = family.length, length_over_d = xi / D;
    const std::size_t h = history_index(body, static_cast<std::size_t>(run.i), run.family, 0);
    float* const back_i = b.back_extension.data() + h;
    float* const back_j = b.back_extension.data() + mirror_history_slot(h);
    for (std::size_t t = 0; t < run.length; ++t) {
      const std::size_t i = static_cast<std::size_t>(run.i) + t, j = static_cast<std::size_t>(run.j) + t;
      if ((beta[i] == 1.0 && beta[j] == 1.0) || !run_bond_intact(b, run, rows, t)) continue;
      const double e = norm<D>(run_ends_at<D>(run, t, x).eta) - xi;
      back_i[t] = static_cast<float>(back_i[t] + (1.0 - beta[i]) * (e - theta[i] * length_over_d - back_i[t]));
      back_j[t] = static_cast<float>(back_j[t] + (1.0 - beta[j]) * (e - theta[j] * length_over_d - back_j[t]));
    }
  });
}

}  // namespace rift::pd
