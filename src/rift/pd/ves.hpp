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

#include "rift/core/vector_isa.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/lps_runs.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Zero history for the VES bodies, laid out by lattice offset (bonds.hpp, bond_slabs.hpp
/// history_index): per block of Bonds::history_block particles, two directions of every forward offset.
template <int D>
void prepare_viscous_history(Model<D>& m) {
  std::size_t slots = 0;
  for (auto& body : m.bodies) {
    if (body.constants.model != scene::ModelKind::ves) continue;
    constexpr std::size_t block = Bonds::history_block;
    body.history_base = slots;
    slots += (body.last - body.first + block - 1) / block * (body.family_count / 2) * 2 * block;
  }
  if (slots == 0) return;
  m.bonds.deviatoric_extension.assign(slots, 0.0f);
  m.bonds.back_extension.assign(slots, 0.0f);
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
  const double ratio = advance ? dt / c.relaxation_time : 0.0;  // dt / tau
  const double one_minus_decay = -std::expm1(-ratio), decay = 1.0 - one_minus_decay;
  const double beta = advance ? 1.0 - one_minus_decay / ratio : 0.0;
  double* const smallest = pass_scratch(m.size(), 1);
  dilatation_pass<D, Omega, false>(m, body, nullptr, smallest);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) m.dilatation_coupling[i] = 0.0;
  // each bond once, in runs (bond_runs.hpp, lps_runs.hpp): the back extensions of both directions,
  // and P of both ends
  const auto x = positions_by_component<D>(m.position, body);
  const double* const theta = m.dilatation.data();
  double* const coupling = m.dilatation_coupling.data();
  const std::uint8_t* const whole = whole_rows(b, body);
  const VectorIsa isa = vector_isa();
  // bond t of a run, as a row takes it
  auto settle = [&](const BondRun& run, std::size_t t) {
    const auto [i, j, k, eta] = run_bond_at<D>(b, run, t, x);
    if (b.intact[static_cast<std::size_t>(k)] != bond_intact) return;
    // advances the history in slot h with deviatoric extension ed (in double, stored in single
    // precision) and returns its back extension
    auto back_extension = [&](std::size_t h, double ed) -> double {
      if (advance) {
        const double ed_old = b.deviatoric_extension[h];
        b.back_extension[h] = static_cast<float>(ed_old * one_minus_decay + b.back_extension[h] * decay + beta * (ed - ed_old));
        b.deviatoric_extension[h] = static_cast<float>(ed);
      }
      return b.back_extension[h];
    };
    const FamilyOffset& family = b.families[run.family];
    const double xi = family.length;
    const double e = norm<D>(eta) - xi;
    const double ed_i = e - theta[i] * (xi / D), ed_j = e - theta[j] * (xi / D);  // as the runs (lps_runs.hpp)
    const std::size_t h = history_index(body, i, run.family, 0);
    const double eb_i = back_extension(h, ed_i), eb_j = back_extension(mirror_history_slot(h), ed_j);
    const double w = influence(Omega, xi, horizon) * xi * family.volume;
    coupling[i] += b.factors[static_cast<std::size_t>(b.factor_row[i] + run.family)].correction * w * (ed_i - lambda * eb_i);
    coupling[j] += b.factors[static_cast<std::size_t>(b.factor_row[j] + family.mirror)].correction * w * (ed_j - lambda * eb_j);
  };
  auto run_history = [&]<bool Corrected>(const BondRun& run) {
    const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
    if (length < short_run) {
      for (std::size_t t = 0; t < length; ++t) settle(run, t);
      return;
    }
    const FamilyOffset& family = b.families[run.family];
    alignas(64) double alive[max_run_length], correction_a[max_run_length], correction_b[max_run_length];
    const bool masked = mask_run(b, run, whole, alive);
    if constexpr (Corrected)
      for (std::size_t t = 0; t < length; ++t) {
        correction_a[t] = b.factors[static_cast<std::size_t>(b.factor_row[i + t] + run.family)].correction;
        correction_b[t] = b.factors[static_cast<std::size_t>(b.factor_row[j + t] + family.mirror)].correction;
      }
    const std::size_t h = history_index(body, i, run.family, 0);  // both directions contiguous (bonds.hpp)
    HistoryRun a;
    a.length = length;
    a.xa = x[0] + i, a.ya = x[1] + i, a.xb = x[0] + j, a.yb = x[1] + j;
    if constexpr (D == 3) a.za = x[2] + i, a.zb = x[2] + j;
    a.theta_a = theta + i, a.theta_b = theta + j;
    a.alive = alive, a.correction_a = correction_a, a.correction_b = correction_b;
    a.deviatoric_a = b.deviatoric_extension.data() + h, a.deviatoric_b = b.deviatoric_extension.data() + mirror_history_slot(h);
    a.back_a = b.back_extension.data() + h, a.back_b = b.back_extension.data() + mirror_history_slot(h);
    a.bond_length = family.length, a.weight = influence(Omega, family.length, horizon) * family.length * family.volume;
    a.lambda = lambda, a.one_minus_decay = one_minus_decay, a.decay = decay, a.beta = beta;
    a.coupling_a = coupling + i, a.coupling_b = coupling + j;
    auto kernel = [&]<bool Advance>() {
      if (masked) vector_clone<HistoryRunKernel<D, Corrected, Advance, true>, HistoryRun>(isa)(a);
      else vector_clone<HistoryRunKernel<D, Corrected, Advance, false>, HistoryRun>(isa)(a);
    };
    if (advance) kernel.template operator()<true>();
    else kernel.template operator()<false>();
  };
  if (c.surface_correction)
    for_each_run_by_slabs(body, [&](const BondRun& r) { run_history.template operator()<true>(r); });
  else
    for_each_run_by_slabs(body, [&](const BondRun& r) { run_history.template operator()<false>(r); });
  next_stretch_limits<D>(m, body, smallest);
}

}  // namespace rift::pd
