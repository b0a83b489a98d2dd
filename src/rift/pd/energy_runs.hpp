// The strain energy density of every particle of a body, its bonds taken in runs (bond_runs.hpp)
// as the force passes take them, for the history's energy columns. The row forms (pmb.hpp
// pmb_energy_density, lps.hpp state_based_energy_density) gather every neighbour and find every
// bond's history slot one bond at a time: a history row cost about four steps of the VES cube. The
// same sums here, over each pair once:
//   PMB:      W_i = c/4 sum_j g_i omega s^2 |xi| V_j                               (Silling and Askari 2005)
//   LPS, VES: W_i = kappa/2 theta_i^2 + a_i/2 sum_j g_i omega [(1 - lambda) e_d^2 + lambda (e_d - e_b)^2] V_j
// (lambda = 0 for the LPS; e_d = e - theta_i |xi| / d and e_b i's back extension, ves.hpp), equal to
// the row forms up to the order of the sums (tests/test_bond_runs.cpp).
#pragma once
#include <cmath>
#include <cstddef>

#include "rift/core/vector_isa.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// One run of the energy sums: the lower ends' arrays start at a, the upper ends' at b; `alive`
/// (Masked); the influence factors g of both ends (Corrected); the dilatations (State) and the back
/// extensions of both directions (Viscous).
struct EnergyRun {
  std::size_t length = 0;
  const double *xa = nullptr, *ya = nullptr, *za = nullptr, *xb = nullptr, *yb = nullptr, *zb = nullptr;
  const double *alive = nullptr, *correction_a = nullptr, *correction_b = nullptr, *theta_a = nullptr, *theta_b = nullptr;
  const float *back_a = nullptr, *back_b = nullptr;
  double bond_length = 0.0, inverse_length = 0.0, weight = 0.0, lambda = 0.0;  // weight: omega V (PMB: omega |xi| V)
  double *sum_a = nullptr, *sum_b = nullptr;
};

/// Each end's share of the sums above (PMB: omega s^2 |xi| V; State: omega [...] V), times its g.
template <int D, bool State, bool Viscous, bool Corrected, bool Masked>
[[gnu::always_inline]] inline void energy_run_terms(
    std::size_t length, const double* __restrict xa, const double* __restrict ya, const double* __restrict za,
    const double* __restrict xb, const double* __restrict yb, const double* __restrict zb, const double* __restrict alive,
    const double* __restrict correction_a, const double* __restrict correction_b, const double* __restrict theta_a,
    const double* __restrict theta_b, const float* __restrict back_a, const float* __restrict back_b, double bond_length,
    double inverse_length, double weight, double lambda, double* __restrict wa, double* __restrict wb) {
  const double length_over_d = bond_length / D;
  for (std::size_t t = 0; t < length; ++t) {
    double ex, ey, ez;
    const double e = std::sqrt(run_bond_vector<D>(xa, ya, za, xb, yb, zb, t, ex, ey, ez)) - bond_length;
    double share_a, share_b;
    if constexpr (State) {
      const double dev_a = e - theta_a[t] * length_over_d, dev_b = e - theta_b[t] * length_over_d;
      if constexpr (Viscous) {
        const double viscous_a = dev_a - back_a[t], viscous_b = dev_b - back_b[t];
        share_a = (1.0 - lambda) * dev_a * dev_a + lambda * viscous_a * viscous_a;
        share_b = (1.0 - lambda) * dev_b * dev_b + lambda * viscous_b * viscous_b;
      } else {
        share_a = dev_a * dev_a, share_b = dev_b * dev_b;
      }
    } else {
      const double s = e * inverse_length;
      share_a = share_b = s * s;
    }
    share_a *= weight, share_b *= weight;
    if constexpr (Corrected) share_a *= correction_a[t], share_b *= correction_b[t];
    if constexpr (Masked) {
      const bool on = alive[t] != 0.0;
      share_a = on ? share_a : 0.0, share_b = on ? share_b : 0.0;
    }
    wa[t] = share_a, wb[t] = share_b;
  }
}

template <int D, bool State, bool Viscous, bool Corrected, bool Masked>
struct EnergyRunKernel {
  [[gnu::always_inline]] static bool run(const EnergyRun& a) {
    alignas(64) double wa[max_run_length], wb[max_run_length];
    energy_run_terms<D, State, Viscous, Corrected, Masked>(a.length, a.xa, a.ya, a.za, a.xb, a.yb, a.zb, a.alive, a.correction_a,
                                                           a.correction_b, a.theta_a, a.theta_b, a.back_a, a.back_b, a.bond_length,
                                                           a.inverse_length, a.weight, a.lambda, wa, wb);
    add_to_run_ends(a.sum_a, wa, a.length);
    add_to_run_ends(a.sum_b, wb, a.length);
    return false;
  }
};

/// W_i of the body's particles into w (indexed as the model; w[first, last) written). The
/// dilatations and back extensions are the model's as they stand (those of its last force
/// evaluation).
template <int D, bool State, bool Viscous, bool Corrected>
void strain_energy_densities(const Model<D>& m, const BodyInfo& body, double* w) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double lambda = Viscous ? c.viscous_fraction : 0.0;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) w[i] = 0.0;
  const auto x = positions_by_component<D>(m.position, body);
  const RowStates rows = whole_rows(b, body);
  const VectorIsa isa = vector_isa();
  for_each_run_by_slabs(body, [&](const BondRun& run) {
    const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
    const FamilyOffset& family = b.families[run.family];
    alignas(64) double alive[max_run_length], correction_a[max_run_length], correction_b[max_run_length];
    const bool masked = mask_run(b, run, rows, alive);
    if (masked && !any_set(alive, length)) return;  // every bond of the run broken: nothing to add
    if constexpr (Corrected)
      for (std::size_t t = 0; t < length; ++t) {
        correction_a[t] = b.factors[static_cast<std::size_t>(b.factor_row[i + t] + run.family)].correction;
        correction_b[t] = b.factors[static_cast<std::size_t>(b.factor_row[j + t] + family.mirror)].correction;
      }
    static thread_local EnergyRun a;  // the thread's: every run sets what its form reads (not zeroed each run)
    a.length = length;
    a.xa = x[0] + i, a.ya = x[1] + i, a.xb = x[0] + j, a.yb = x[1] + j;
    if constexpr (D == 3) a.za = x[2] + i, a.zb = x[2] + j;
    a.alive = alive, a.correction_a = correction_a, a.correction_b = correction_b;
    if constexpr (State) a.theta_a = m.dilatation.data() + i, a.theta_b = m.dilatation.data() + j;
    if constexpr (Viscous) {
      const std::size_t h = history_index(body, i, run.family, 0);
      a.back_a = b.back_extension.data() + h, a.back_b = b.back_extension.data() + mirror_history_slot(h);
    }
    const double omega = influence(c.influence, family.length, c.horizon);
    a.bond_length = family.length, a.inverse_length = family.inverse_length, a.lambda = lambda;
    a.weight = State ? omega * family.volume : omega * family.length * family.volume;
    a.sum_a = w + i, a.sum_b = w + j;
    if (masked)
      vector_clone<EnergyRunKernel<D, State, Viscous, Corrected, true>, EnergyRun>(isa)(a);
    else
      vector_clone<EnergyRunKernel<D, State, Viscous, Corrected, false>, EnergyRun>(isa)(a);
  });
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    if constexpr (State) {
      const double a_i = m.weighted_volume[i] > 0.0 ? c.lps_deviatoric_coefficient() / m.weighted_volume[i] : 0.0;
      w[i] = 0.5 * c.kappa * m.dilatation[i] * m.dilatation[i] + 0.5 * a_i * w[i];
    } else {
      w[i] *= 0.25 * c.micromodulus;
    }
  }
}

}  // namespace rift::pd
