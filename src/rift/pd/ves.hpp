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
#include <cmath>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Zero history for the VES bodies.
template <int D>
void prepare_viscous_history(Model<D>& m) {
  bool any = false;
  for (const auto& body : m.bodies) any = any || body.constants.model == scene::ModelKind::ves;
  if (!any) return;
  Bonds& b = m.bonds;
  b.pair_shift.assign(m.size(), 0);
  std::int64_t pairs = 0;  // bonds join both ways, so the pairs are half the directed bonds
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto forward = first_forward_bond(b, i);
    b.pair_shift[i] = pairs - forward;
    pairs += b.offset[i + 1] - forward;
  }
  b.deviatoric_extension.assign(static_cast<std::size_t>(2 * pairs), 0.0f);
  b.back_extension.assign(static_cast<std::size_t>(2 * pairs), 0.0f);
}

/// First pass: dilatation and bond breaking (as the LPS), then the back extension of every intact
/// bond advanced over dt (dt = 0: held) and P_i. The second pass and W_i are the LPS ones with the
/// back extensions (state_based_forces, state_based_energy_density in lps.hpp).
template <int D, scene::Influence Omega>
void ves_dilatation(Model<D>& m, const BodyInfo& body, double dt) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double horizon = c.horizon, lambda = c.viscous_fraction;
  const bool advance = dt > 0.0;
  const double x = advance ? dt / c.relaxation_time : 0.0;
  const double one_minus_decay = -std::expm1(-x), decay = 1.0 - one_minus_decay;
  const double beta = advance ? 1.0 - one_minus_decay / x : 0.0;
  double* const smallest = pass_scratch(m.size(), 1);
  dilatation_pass<D, Omega, false>(m, body, nullptr, smallest);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) m.dilatation_coupling[i] = 0.0;
  // each bond once (bond_slabs.hpp): the back extensions of both directions, and P of both ends
  for_each_row_by_slabs(body, [&](std::size_t i) {
    const Vec<D> xi_pos = m.position[i];
    const double theta_i = m.dilatation[i];
    const std::int64_t row_i = b.factor_row[i];
    double p = 0.0;
    // advances the history in slot h (bonds.hpp) with deviatoric extension ed (in double, stored
    // in single precision) and returns its back extension
    auto back_extension = [&](std::size_t h, double ed) -> double {
      if (advance) {
        const double ed_old = b.deviatoric_extension[h];
        b.back_extension[h] = static_cast<float>(ed_old * one_minus_decay + b.back_extension[h] * decay + beta * (ed - ed_old));
        b.deviatoric_extension[h] = static_cast<float>(ed);
      }
      return b.back_extension[h];
    };
    for (auto k = first_forward_bond(b, i); k < b.offset[i + 1]; ++k) {
      if (b.intact[k] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const auto h = static_cast<std::size_t>(2 * (k + b.pair_shift[i]));  // i-j at h, j-i at h + 1 (history_slot)
      const FamilyOffset& family = b.families[b.family[k]];
      const double xi = family.length;
      const double e = norm<D>(m.position[j] - xi_pos) - xi;
      const double ed_i = e - theta_i * xi / D, ed_j = e - m.dilatation[j] * xi / D;
      const double eb_i = back_extension(h, ed_i), eb_j = back_extension(h + 1, ed_j);
      const double w = influence(Omega, xi, horizon) * xi * family.volume;
      p += b.factors[static_cast<std::size_t>(row_i + b.family[k])].correction * w * (ed_i - lambda * eb_i);
      m.dilatation_coupling[j] += b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)].correction * w * (ed_j - lambda * eb_j);
    }
    m.dilatation_coupling[i] += p;
  });
  next_stretch_limits<D>(m, body, smallest);
}

}  // namespace rift::pd
