// Viscoelastic ordinary state-based peridynamics (Mitchell 2011, SAND2011-8064; LAMMPS peri/ves):
// the linear peridynamic solid of lps.hpp whose deviatoric response has an elastic share 1 - lambda
// and a viscous share lambda acting on e_d - e_b, where the back extension e_b of every bond relaxes
// toward the deviatoric extension e_d = e - theta |xi| / d with the relaxation time tau:
//   d e_b / dt = (e_d - e_b) / tau.
// Over a step dt with e_d linear in time this integrates exactly to (Mitchell 2011, sec. 3):
//   e_b(n+1) = e_d(n) (1 - decay) + e_b(n) decay + beta (e_d(n+1) - e_d(n)),
//   decay = exp(-dt / tau),  beta = 1 - tau (1 - decay) / dt.
// With e_b held fixed over the step, the free energy and its derivative, the force state, are
//   W_i = kappa/2 theta_i^2 + a_i/2 sum_j sigma_ij [(1 - lambda) e_d^2 + lambda (e_d - e_b)^2] V_j,
//   t_i<j> = b_ij (kappa theta_i - a_i P_i / d) + a_i sigma_ij (e_d - lambda e_b),
//   P_i = sum_j sigma_ij (e_d - lambda e_b) |xi| V_j,
// with a_i, sigma_ij, b_ij as in lps.hpp (lambda = 0 gives the LPS exactly). So a sudden deviatoric
// strain held fixed relaxes its stress as G [(1 - lambda) + lambda exp(-t / tau)], the standard linear
// solid. Two differences from LAMMPS peri/ves: t_j<i> uses j's own dilatation and back extension (LAMMPS
// uses theta_i in both halves of the deviatoric term, which breaks Newton's third law where the
// dilatation varies), and the P term of the surface correction (zero without it, as in LAMMPS, up to
// the history of broken bonds).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "rift/core/error.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// Zero history and the reverse-bond slots for the VES bodies (rows are sorted by neighbour).
template <int D>
void prepare_viscous_history(Model<D>& m) {
  bool any = false;
  for (const auto& body : m.bodies) any = any || body.constants.model == scene::ModelKind::ves;
  if (!any) return;
  Bonds& b = m.bonds;
  b.deviatoric_extension.assign(b.neighbor.size(), 0.0);
  b.back_extension.assign(b.neighbor.size(), 0.0);
  b.mirror_slot.assign(b.neighbor.size(), 0);
  const auto n = static_cast<std::int64_t>(b.offset.size()) - 1;
  for (std::int64_t i = 0; i < n; ++i)
    if (b.offset[i + 1] - b.offset[i] > std::numeric_limits<std::uint16_t>::max())
      throw PhysicsError("a particle has more than 65535 bonds; the viscoelastic model needs fewer (a smaller horizon / spacing)");
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = b.neighbor[k];
      const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
      b.mirror_slot[k] = static_cast<std::uint16_t>(std::lower_bound(first, last, static_cast<std::int32_t>(i)) - first);
    }
}

/// First pass: dilatation, bond breaking (as lps_dilatation), then the back extension of every intact
/// bond advanced over dt (dt = 0: held) and P_i.
template <int D, scene::Influence Omega>
void ves_dilatation(Model<D>& m, const BodyInfo& body, double dt) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double horizon = c.horizon, s00 = c.critical_stretch, alpha = c.alpha, lambda = c.viscous_fraction;
  const bool breakable = c.breakable, advance = dt > 0.0;
  const double x = advance ? dt / c.relaxation_time : 0.0;
  const double one_minus_decay = -std::expm1(-x), decay = 1.0 - one_minus_decay;
  const double beta = advance ? 1.0 - one_minus_decay / x : 0.0;
#pragma omp parallel for schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const Vec<D> xi_pos = m.position[i];
    const double s0_i = m.stretch_limit[i];
    double theta = 0.0;
    double s_min = std::numeric_limits<double>::max();
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!b.intact[k]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const double xi = b.length[k];
      const double e = norm<D>(m.position[j] - xi_pos) - xi;
      if (breakable && e > xi * std::min(s0_i, m.stretch_limit[j])) {
        b.intact[k] = 0;  // the mirror bond in row j is broken by the same test
        continue;
      }
      s_min = std::min(s_min, e / xi);
      theta += b.dilatation_weight[k] * e * b.volume[k];
    }
    double p = 0.0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!b.intact[k]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const double xi = b.length[k];
      const double ed = norm<D>(m.position[j] - xi_pos) - xi - theta * xi / D;
      double eb = b.back_extension[k];
      if (advance) {
        eb = b.deviatoric_extension[k] * one_minus_decay + eb * decay + beta * (ed - b.deviatoric_extension[k]);
        b.back_extension[k] = eb;
        b.deviatoric_extension[k] = ed;
      }
      p += b.correction[k] * influence(Omega, xi, horizon) * (ed - lambda * eb) * xi * b.volume[k];
    }
    m.dilatation[i] = theta;
    m.dilatation_coupling[i] = p;
    if (alpha > 0.0 && s_min < std::numeric_limits<double>::max()) m.next_stretch_limit[i] = s00 - alpha * s_min;
  }
}

/// Second pass: f_i = sum_j (t_i<j> + t_j<i>) V_j along the deformed bond.
template <int D, scene::Influence Omega>
void ves_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double horizon = c.horizon, kappa = c.kappa, a_dev = c.lps_deviatoric_coefficient(), lambda = c.viscous_fraction;
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
      const double eb_j = b.back_extension[static_cast<std::size_t>(b.offset[j]) + b.mirror_slot[k]];
      const double t_i = force_state(b.dilatation_weight[k], pressure_i, a_i, b.correction[k], omega, e - theta_i * xi / D - lambda * b.back_extension[k]);
      const double t_j = force_state(b.mirror_dilatation_weight[k], pressure_j, a_j, b.mirror_correction[k], omega, e - theta_j * xi / D - lambda * eb_j);
      const double scalar = (t_i + t_j) * b.volume[k] / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
    }
    m.force[i] = f;
  }
}

/// W_i (uses the current dilatation and back extensions).
template <int D>
double ves_energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double theta = m.dilatation[i], lambda = c.viscous_fraction;
  double dev = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (!b.intact[k]) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const double xi = b.length[k];
    const double ed = norm<D>(m.position[j] - m.position[i]) - xi - theta * xi / D;
    const double ev = ed - b.back_extension[k];
    dev += b.correction[k] * influence(c.influence, xi, c.horizon) * ((1.0 - lambda) * ed * ed + lambda * ev * ev) * b.volume[k];
  }
  return 0.5 * c.kappa * theta * theta + 0.5 * c.lps_deviatoric_coefficient() / m.weighted_volume[i] * dev;
}

}  // namespace rift::pd
