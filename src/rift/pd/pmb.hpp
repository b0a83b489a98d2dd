// Prototype microelastic brittle (PMB) bond force (Silling and Askari 2005, eq. 15-16):
// f = c omega(|xi|) s V_j along the deformed bond, s = (|y| - |xi|) / |xi|; with the surface
// correction each end contributes half with its own influence factor: c (g_i + g_j)/2 omega s V_j. A bond breaks for good
// when s exceeds min(s0_i, s0_j); s0_i = s00 - alpha s_min,i (eq. 23, as LAMMPS peri/pmb); in a
// crack's wet rock the limit is on the effective stretch (breaking_policy.hpp).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "rift/core/vector_isa.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/breaking_policy.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The bond force density per unit V_j along the deformed bond, c omega s (g_i + g_j) / 2: `coefficient`
/// c omega, `factor` (g_i + g_j) / 2 (pmb_factor; 1 without the surface correction). The law's one
/// statement: the vector runs, the bonds they settle one by one, the bond-pair stress and the network load call it.
[[gnu::always_inline]] inline double pmb_bond_force(double coefficient, double s, double factor) { return coefficient * s * factor; }

/// (g_i + g_j) / 2 of a bond, in single precision as the factors are kept (bonds.hpp BondFactors).
inline float pmb_factor(float correction, float mirror_correction) { return 0.5f * (correction + mirror_correction); }

/// The pair forces of a run of PMB bonds (bond_runs.hpp), bond t's to out(t, g, s) (bond_runs.hpp
/// PairForcesToBuffers or PairForcesToEnds): g, the force density on the lower end per unit V_j,
/// component by component (the upper end takes -g), and s its stretch. The lower ends' positions and
/// stretch limits start at a, the upper ends' at b. `alive` (Masked; else every bond is intact): 1
/// for an intact bond, 0 for another; `factor` (Corrected): (g_i + g_j) / 2. Where `breakable`, an
/// intact bond whose stretch passes its limit, as `Limit` lowers it (breaking_policy.hpp), may break: it adds nothing (g = 0, s = `none`, as a bond that is not
/// intact) and is marked in `past` for the caller to settle bond by bond; returns whether any is.
/// One loop without branches over contiguous arrays, vector code; every bond's force is the row's to
/// the last bit.
template <int D, bool Corrected, class Limit, bool Masked, class Out>
[[gnu::always_inline]] inline bool pmb_run_pair_forces(std::size_t length, const double* __restrict xa, const double* __restrict ya,
                                const double* __restrict za, const double* __restrict xb, const double* __restrict yb,
                                const double* __restrict zb, const double* __restrict limit_a, const double* __restrict limit_b,
                                const double* __restrict pore_a, const double* __restrict pore_b, double shift_scale,
                                const double* __restrict alive, const double* __restrict factor, double bond_length,
                                double inverse_length, double coefficient, double volume, bool breakable, Out out,
                                double* __restrict past) {
  constexpr double none = std::numeric_limits<double>::max();
#pragma omp simd safelen(simd_ends_apart)
  for (std::size_t t = 0; t < length; ++t) {
    double ex, ey, ez;
    const double r2 = run_bond_vector<D>(xa, ya, za, xb, yb, zb, t, ex, ey, ez);
    const double r = std::sqrt(r2);
    const double s = (r - bond_length) * inverse_length;
    const double limit = Limit::lowered(limit_b[t] < limit_a[t] ? limit_b[t] : limit_a[t], pore_a, pore_b, t, shift_scale);
    const bool on = Masked ? alive[t] != 0.0 : true;
    const bool breaks = breakable && on && s > limit;
    past[t] = breaks ? 1.0 : 0.0;
    const bool adds = on && !breaks;
    double scalar = pmb_bond_force(coefficient, s, Corrected ? factor[t] : 1.0);
    scalar = scalar * volume / r;
    scalar = adds ? scalar : 0.0;
    out(t, scalar * ex, scalar * ey, scalar * ez, adds ? s : none);
  }
  return any_set(past, length);
}

/// One run's arrays and constants (pmb_run_pair_forces), and where its forces go: f_a and
/// smallest_a at its lower ends, f_b and smallest_b at its upper ends.
struct PmbRun {
  std::size_t length = 0;
  const double *xa = nullptr, *ya = nullptr, *za = nullptr, *xb = nullptr, *yb = nullptr, *zb = nullptr;
  const double *limit_a = nullptr, *limit_b = nullptr, *pore_a = nullptr, *pore_b = nullptr, *alive = nullptr, *factor = nullptr;
  double shift_scale = 1.0, bond_length = 0.0, inverse_length = 0.0, coefficient = 0.0, volume = 0.0;
  double *fxa = nullptr, *fya = nullptr, *fza = nullptr, *fxb = nullptr, *fyb = nullptr, *fzb = nullptr;
  double *smallest_a = nullptr, *smallest_b = nullptr;
  double* may_break = nullptr;  // where a run that may break a bond leaves which (1: may break), for the caller
  bool breakable = false;
  bool ends_apart = false;  // ends_apart_in_vectors (bond_runs.hpp): the one-loop form
};

/// A run's pair forces added to its ends, but for the bonds that may break: those add nothing and are
/// marked in may_break for the caller to settle one by one (returns whether any is). Where the run's
/// ends lie apart in vectors (PmbRun::ends_apart) in one loop, else through buffers.
template <int D, bool Corrected, class Limit, bool Masked>
struct PmbRunKernel {
  [[gnu::always_inline]] static bool run(const PmbRun& a) {
    // (no lambda here: its body would not take the clone's target)
    if (a.ends_apart)
      return pmb_run_pair_forces<D, Corrected, Limit, Masked>(
          a.length, a.xa, a.ya, a.za, a.xb, a.yb, a.zb, a.limit_a, a.limit_b, a.pore_a, a.pore_b, a.shift_scale, a.alive, a.factor,
          a.bond_length, a.inverse_length, a.coefficient, a.volume, a.breakable, PairForcesToEnds<D, true>(a), a.may_break);
    alignas(64) double g[3][max_run_length], stretch[max_run_length];
    const bool may_break = pmb_run_pair_forces<D, Corrected, Limit, Masked>(
        a.length, a.xa, a.ya, a.za, a.xb, a.yb, a.zb, a.limit_a, a.limit_b, a.pore_a, a.pore_b, a.shift_scale, a.alive, a.factor,
        a.bond_length, a.inverse_length, a.coefficient, a.volume, a.breakable, PairForcesToBuffers<D, true>{g[0], g[1], g[2], stretch},
        a.may_break);
    add_pair_forces_to_run_ends<D>(a, g);
    lower_to_run_stretches(a.smallest_a, stretch, a.length);
    lower_to_run_stretches(a.smallest_b, stretch, a.length);
    return may_break;
  }
};

template <int D, bool Corrected, class Limit, bool Masked>
auto pmb_run_kernel(VectorIsa isa) {
  return vector_clone<PmbRunKernel<D, Corrected, Limit, Masked>, PmbRun>(isa);
}

template <int D, scene::Influence Omega>
void pmb_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double micromodulus = c.micromodulus, horizon = c.horizon;
  const bool breakable = c.breakable;
  // bonds join particles of one body. The positions and forces one array per component (the runs
  // read and write them contiguously), and the smallest stretch of each particle's intact bonds: the
  // calling thread's buffers, which the team reads and writes through these pointers
  const std::size_t n = m.size();
  std::array<double*, 3> x{}, f{};
  for (int q = 0; q < D; ++q)
    x[q] = pass_buffer(n, component(PassBuffer::position_x, q)), f[q] = pass_buffer(n, component(PassBuffer::force_x, q));
  double* const smallest = pass_buffer(n, PassBuffer::smallest_stretch);
  constexpr double none = std::numeric_limits<double>::max();
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j) {
    for (int q = 0; q < D; ++q) x[q][j] = m.position[j][q], f[q][j] = 0.0;
    smallest[j] = none;
  }
  BreakLog log;
  const BondView v = b.view();
  const double* const limits = m.stretch_limit.data();
  const RowStates rows = whole_rows(b, body);
  const VectorIsa isa = vector_isa();
  // bond t of a run, one at a time, as a row would take it: for a run that may break a bond
  auto settle = [&]<bool Corrected>(const auto& breaking, const BondRun& run, std::size_t t) {
    // the rows' states as the pass found them: a run holds each pair once, and the pass breaks the
    // lower end's bond (the mirrors after it), so they are the bond's own state here
    if (!run_bond_intact(b, run, rows, t)) return;
    const auto [i, j, eta] = run_ends_at<D>(run, t, x);
    const double r = norm<D>(eta);
    const FamilyOffset& family = v.families[run.family];
    const double s = (r - family.length) * family.inverse_length;
    const double limit = std::min(limits[i], limits[j]);
    bool crossed = false;
    const bool past = breaking.breaks(breakable, i, j, family.length, s, limit, s > limit, crossed);
    if (breakable && past) {
      const std::int64_t k = run_bond(b, run, t);
      v.intact[k] = bond_broken;
      log.note(i, k, crossed);
      return;
    }
    smallest[i] = std::min(smallest[i], s);
    smallest[j] = std::min(smallest[j], s);
    float g_i = 1.0f, g_j = 1.0f;
    if constexpr (Corrected) {
      g_i = v.factors[v.factor_row[i] + run.family].correction;
      g_j = v.factors[v.factor_row[j] + family.mirror].correction;
    }
    const double scalar = pmb_bond_force(micromodulus * influence(Omega, family.length, horizon), s, pmb_factor(g_i, g_j)) * family.volume / r;
    for (int q = 0; q < D; ++q) {
      f[q][i] += scalar * eta[q];
      f[q][j] -= scalar * eta[q];
    }
  };
  // a run of bonds (bond_runs.hpp): s is the same seen from either end, and so is the pair force
  // c omega s (g_i + g_j)/2 V along the bond. The wet rock's shift is compiled in only where there is
  // wet rock (breaking_policy.hpp), the influence-function factors only with the surface
  // correction (without it they are all 1)
  auto run_forces = [&]<bool Corrected>(const auto& breaking, const BondRun& run) {
    const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
    if (length < short_run) {  // a vector's set-up would cost more than the bonds
      for (std::size_t t = 0; t < length; ++t) settle.template operator()<Corrected>(breaking, run, t);
      return;
    }
    const FamilyOffset& family = v.families[run.family];
    alignas(64) double alive[max_run_length], factor[max_run_length], flagged[max_run_length];
    // the bonds' states (in their lower ends' rows) only where a row is not whole (bond_runs.hpp)
    const bool masked = mask_run(b, run, rows, alive);
    if (masked && !any_set(alive, length)) return;  // every bond of the run broken: nothing to add
    if constexpr (Corrected)
      for (std::size_t t = 0; t < length; ++t)
        factor[t] = pmb_factor(v.factors[v.factor_row[i + t] + run.family].correction, v.factors[v.factor_row[j + t] + family.mirror].correction);
    const double* const pore = breaking.pore_stretch();
    static thread_local PmbRun a;  // the thread's: every run sets what its form reads (not zeroed each run)
    a.length = length;
    a.xa = x[0] + i, a.ya = x[1] + i, a.xb = x[0] + j, a.yb = x[1] + j;
    a.fxa = f[0] + i, a.fya = f[1] + i, a.fxb = f[0] + j, a.fyb = f[1] + j;
    if constexpr (D == 3) a.za = x[2] + i, a.zb = x[2] + j, a.fza = f[2] + i, a.fzb = f[2] + j;
    a.limit_a = limits + i, a.limit_b = limits + j;
    if (pore) a.pore_a = pore + i, a.pore_b = pore + j;
    a.shift_scale = 1.0 + c.alpha;
    a.alive = alive, a.factor = factor;
    a.bond_length = family.length, a.inverse_length = family.inverse_length, a.volume = family.volume;
    a.coefficient = micromodulus * influence(Omega, family.length, horizon);
    a.smallest_a = smallest + i, a.smallest_b = smallest + j;
    a.breakable = breakable;
    a.may_break = flagged;
    a.ends_apart = ends_apart_in_vectors(run);
    bool may_break;
    if (pore)
      may_break = masked ? pmb_run_kernel<D, Corrected, PoreShiftedLimit, true>(isa)(a)
                         : pmb_run_kernel<D, Corrected, PoreShiftedLimit, false>(isa)(a);
    else
      may_break = masked ? pmb_run_kernel<D, Corrected, StretchLimit, true>(isa)(a) : pmb_run_kernel<D, Corrected, StretchLimit, false>(isa)(a);
    if (!may_break) return;
    // the rest of the run is added: the bonds that may break one by one (each bond of a run has its
    // own two ends, so the order of their forces does not matter)
    for (std::size_t t = 0; t < length; ++t)
      if (flagged[t] != 0.0) settle.template operator()<Corrected>(breaking, run, t);
  };
  with_breaking(m, c.alpha, [&](const auto& breaking) {
    if (c.surface_correction)
      for_each_run_by_slabs(body, [&](const BondRun& r) { run_forces.template operator()<true>(breaking, r); });
    else
      for_each_run_by_slabs(body, [&](const BondRun& r) { run_forces.template operator()<false>(breaking, r); });
  });
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j)
    for (int q = 0; q < D; ++q) m.force[j][q] = f[q][j];
  break_mirror_bonds(b, body, log.broken);
  refresh_rows(b, body, rows, log.broken);  // the kept rows as the pass leaves the states
  after_breaking<D>(m, log);
  next_stretch_limits<D>(m, body, smallest);
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
