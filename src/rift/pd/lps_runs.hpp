// The run kernels of the LPS and VES passes (lps.hpp, ves.hpp; runs: bond_runs.hpp). Each takes the
// bonds of one run together in one loop without branches over contiguous arrays, which the compiler
// makes vector code, straight into the run's two ends where they lie apart in vectors
// (ends_apart_in_vectors), else into buffers that are then added to the ends. Every bond's terms are
// the row formulas' to the last bit (the same operations in the same order), but for the deviatoric
// extension e - theta (|xi| / d), which takes |xi| / d per run where a row divided theta |xi| by d
// per bond (a rounding apart; the bonds a run takes one by one use the run's form).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "rift/core/vector_isa.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/breaking_policy.hpp"
#include "rift/pd/laws/ordinary_state.hpp"
#include "rift/pd/viscous_step.hpp"

namespace rift::pd {

/// One run of the dilatation pass: the lower ends' arrays start at a, the upper ends' at b.
/// `mask` (Masked): which bonds are intact (bond_runs.hpp run_mask); Corrected: the dilatation weights b_ij,
/// b_ji and the influence factors g_i, g_j of the run's bonds (bonds.hpp BondFactors).
struct DilatationRun {
  std::size_t length = 0;
  const double *xa = nullptr, *ya = nullptr, *za = nullptr, *xb = nullptr, *yb = nullptr, *zb = nullptr;
  const double *limit_a = nullptr, *limit_b = nullptr, *pore_a = nullptr, *pore_b = nullptr;
  RunMask mask;  // Masked
  const double *weight_a = nullptr, *weight_b = nullptr, *correction_a = nullptr, *correction_b = nullptr;
  double shift_scale = 1.0, bond_length = 0.0, inverse_length = 0.0, volume = 0.0, omega_length = 0.0;  // omega |xi|
  double *theta_a = nullptr, *theta_b = nullptr, *coupling_a = nullptr, *coupling_b = nullptr;
  double *smallest_a = nullptr, *smallest_b = nullptr;
  double* may_break = nullptr;  // where a run that may break a bond leaves which (1: may break), for the caller
  bool breakable = false;
  bool ends_apart = false;  // bond_runs.hpp ends_apart_in_vectors: the one-loop form
};

/// Where a dilatation run's terms go (as bond_runs.hpp PairForcesToBuffers, PairForcesToEnds):
/// bond t's terms of theta (wa, wb) and of q (qa, qb; Coupling) at each end, and its stretch s.
template <bool Coupling>
struct DilatationToBuffers {
  double *wa, *wb, *qa, *qb, *stretch;
  [[gnu::always_inline]] void operator()(std::size_t t, double a, double b, double qa_t, double qb_t, double s) const {
    wa[t] = a, wb[t] = b;
    if constexpr (Coupling) qa[t] = qa_t, qb[t] = qb_t;
    stretch[t] = s;
  }
};
template <bool Coupling>
struct DilatationToEnds {
  double *theta_a, *theta_b, *coupling_a, *coupling_b, *smallest_a, *smallest_b;
  template <class Run>
  explicit DilatationToEnds(const Run& a)
      : theta_a(a.theta_a), theta_b(a.theta_b), coupling_a(a.coupling_a), coupling_b(a.coupling_b), smallest_a(a.smallest_a),
        smallest_b(a.smallest_b) {}
  [[gnu::always_inline]] void operator()(std::size_t t, double a, double b, double qa_t, double qb_t, double s) const {
    theta_a[t] += a, theta_b[t] += b;
    if constexpr (Coupling) coupling_a[t] += qa_t, coupling_b[t] += qb_t;
    smallest_a[t] = s < smallest_a[t] ? s : smallest_a[t];
    smallest_b[t] = s < smallest_b[t] ? s : smallest_b[t];
  }
};

/// The terms of a run's bonds in the dilatation pass (lps.hpp dilatation_pass), bond t's to out(t,
/// ...) (DilatationToBuffers, DilatationToEnds): theta of each end (b e V, or omega |xi| e V without
/// the correction, scaled after the pass), q of each end (g omega |xi| e V, or omega |xi| e V;
/// Coupling), the stretch (`none` where not intact). Where `breakable`, an intact bond whose
/// extension passes |xi| min(s0_i, s0_j), or whose stretch passes that limit as `Limit` lowers it
/// (breaking_policy.hpp), may break: it adds nothing (as a bond that is not intact) and is marked in
/// `past` for the caller to take bond by bond; returns whether any is.
template <int D, bool Corrected, bool Coupling, class Limit, bool Masked, class Out>
[[gnu::always_inline]] inline bool dilatation_run_terms(
    std::size_t length, const double* __restrict xa, const double* __restrict ya, const double* __restrict za,
    const double* __restrict xb, const double* __restrict yb, const double* __restrict zb, const double* __restrict limit_a,
    const double* __restrict limit_b, const double* __restrict pore_a, const double* __restrict pore_b, double shift_scale,
    const double* __restrict alive, const double* __restrict weight_a, const double* __restrict weight_b,
    const double* __restrict correction_a, const double* __restrict correction_b, double bond_length, double inverse_length,
    double volume, double omega_length, bool breakable, Out out, double* __restrict past) {
  constexpr double none = std::numeric_limits<double>::max();
#pragma omp simd safelen(simd_ends_apart)
  for (std::size_t t = 0; t < length; ++t) {
    double ex, ey, ez;
    const double r2 = run_bond_vector<D>(xa, ya, za, xb, yb, zb, t, ex, ey, ez);
    const double e = std::sqrt(r2) - bond_length;
    const double s = e * inverse_length;
    const double limit = limit_b[t] < limit_a[t] ? limit_b[t] : limit_a[t];
    const double lowered = Limit::lowered(limit, pore_a, pore_b, t, shift_scale);
    const bool on = Masked ? alive[t] != 0.0 : true;
    const bool breaks = breakable & on & ((e > bond_length * limit) | (s > lowered));  // no branch: vector code
    past[t] = breaks ? 1.0 : 0.0;
    const bool adds = on && !breaks;
    const double ev = e * volume;
    const double w = omega_length * ev;
    if constexpr (Corrected) {
      out(t, adds ? weight_a[t] * ev : 0.0, adds ? weight_b[t] * ev : 0.0, adds ? correction_a[t] * w : 0.0,
          adds ? correction_b[t] * w : 0.0, adds ? s : none);
    } else {  // both ends take omega |xi| e V, and so does q
      const double both = adds ? w : 0.0;
      out(t, both, both, both, both, adds ? s : none);
    }
  }
  return any_set(past, length);
}

template <int D, bool Corrected, bool Coupling, class Limit, bool Masked>
struct DilatationRunKernel {
  [[gnu::always_inline]] static bool run(const DilatationRun& a) {
    alignas(64) double own_alive[max_run_length];
    const double* alive = nullptr;
    if constexpr (Masked)
      if (!alive_from_mask(a.mask, a.length, own_alive, alive)) return false;  // every bond of the run broken: nothing to add
    if (a.ends_apart)  // in one loop (bond_runs.hpp ends_apart_in_vectors)
      return dilatation_run_terms<D, Corrected, Coupling, Limit, Masked>(
          a.length, a.xa, a.ya, a.za, a.xb, a.yb, a.zb, a.limit_a, a.limit_b, a.pore_a, a.pore_b, a.shift_scale, alive, a.weight_a,
          a.weight_b, a.correction_a, a.correction_b, a.bond_length, a.inverse_length, a.volume, a.omega_length, a.breakable,
          DilatationToEnds<Coupling>(a), a.may_break);
    alignas(64) double wa[max_run_length], wb[max_run_length], qa[max_run_length], qb[max_run_length], stretch[max_run_length];
    const bool may_break = dilatation_run_terms<D, Corrected, Coupling, Limit, Masked>(
        a.length, a.xa, a.ya, a.za, a.xb, a.yb, a.zb, a.limit_a, a.limit_b, a.pore_a, a.pore_b, a.shift_scale, alive, a.weight_a,
        a.weight_b, a.correction_a, a.correction_b, a.bond_length, a.inverse_length, a.volume, a.omega_length, a.breakable,
        DilatationToBuffers<Coupling>{wa, wb, qa, qb, stretch}, a.may_break);
    add_to_run_ends(a.theta_a, wa, a.length);
    add_to_run_ends(a.theta_b, wb, a.length);
    if constexpr (Coupling) {
      add_to_run_ends(a.coupling_a, qa, a.length);
      add_to_run_ends(a.coupling_b, qb, a.length);
    }
    lower_to_run_stretches(a.smallest_a, stretch, a.length);
    lower_to_run_stretches(a.smallest_b, stretch, a.length);
    return may_break;
  }
};

/// One run of the force pass: the lower ends' arrays start at a, the upper ends' at b (positions,
/// pressure factors p, a = A_dev / m, dilatations theta); `mask` (Masked); Corrected: b_ij, b_ji, g_i,
/// g_j; Viscous: the back extensions of both directions (ves.hpp; bonds.hpp), the pairs' extensions
/// and the ends' dilatations of the step before (bonds.hpp last_extension, history_dilatation),
/// lambda and the step's coefficients (viscous_step.hpp).
struct StateForceRun {
  std::size_t length = 0;
  const double *xa = nullptr, *ya = nullptr, *za = nullptr, *xb = nullptr, *yb = nullptr, *zb = nullptr;
  const double *pressure_a = nullptr, *pressure_b = nullptr, *coefficient_a = nullptr, *coefficient_b = nullptr;
  const double *theta_a = nullptr, *theta_b = nullptr;
  RunMask mask;  // Masked
  const double *weight_a = nullptr, *weight_b = nullptr, *correction_a = nullptr, *correction_b = nullptr;
  const double *last_theta_a = nullptr, *last_theta_b = nullptr;
  float *back_a = nullptr, *back_b = nullptr, *last_extension = nullptr;
  double bond_length = 0.0, omega = 0.0, volume = 0.0, lambda = 0.0;
  double one_minus_decay = 0.0, decay = 1.0, beta = 0.0;
  double *fxa = nullptr, *fya = nullptr, *fza = nullptr, *fxb = nullptr, *fyb = nullptr, *fzb = nullptr;
  bool ends_apart = false;  // bond_runs.hpp ends_apart_in_vectors: the one-loop form
};

/// Asks the cache for the `length` history values `ahead` slots on from `start` (for writing). The
/// addresses may lie past the history's end (taken as integers, not pointers): a prefetch never faults.
[[gnu::always_inline]] inline void prefetch_history(const float* start, std::size_t ahead, std::size_t length) {
  constexpr std::size_t line = 64;
  const auto first = reinterpret_cast<std::uintptr_t>(start) + ahead * sizeof(float), last = first + length * sizeof(float);
  for (std::uintptr_t p = first; p < last; p += line) __builtin_prefetch(reinterpret_cast<const void*>(p), 1, 3);
}

/// The pair force densities (t_i<j> + t_j<i>) V / |y| times the deformed bond, per component, of a
/// run's bonds (lps.hpp state_based_forces). Viscous and Advance: the back extension of both
/// directions of every intact bond advances over the step first (viscous_step.hpp, with e_d(n) from
/// the pair's last extension as last_deviatoric_extension takes it, which then becomes e(n+1); a bond
/// that is not intact keeps its history), and the force takes the new one as stored.
template <int D, bool Corrected, bool Viscous, bool Advance, bool Masked, class Out>
[[gnu::always_inline]] inline void state_force_run_terms(
    std::size_t length, const double* __restrict xa, const double* __restrict ya, const double* __restrict za,
    const double* __restrict xb, const double* __restrict yb, const double* __restrict zb, const double* __restrict pressure_a,
    const double* __restrict pressure_b, const double* __restrict coefficient_a, const double* __restrict coefficient_b,
    const double* __restrict theta_a, const double* __restrict theta_b, const double* __restrict alive,
    const double* __restrict weight_a, const double* __restrict weight_b, const double* __restrict correction_a,
    const double* __restrict correction_b, const double* __restrict last_theta_a, const double* __restrict last_theta_b,
    float* __restrict back_a, float* __restrict back_b, float* __restrict last_extension, double lambda, double one_minus_decay, double decay, double beta, double bond_length, double omega,
    double volume, Out out) {
  const double omega_length = omega * bond_length;
  const double length_over_d = bond_length / D;  // e_d = e - theta |xi| / d, without a division per bond
#pragma omp simd safelen(simd_ends_apart)
  for (std::size_t t = 0; t < length; ++t) {
    double ex, ey, ez;
    const double r2 = run_bond_vector<D>(xa, ya, za, xb, yb, zb, t, ex, ey, ez);
    const double r = std::sqrt(r2);
    const double e = r - bond_length;
    double dev_a = e - theta_a[t] * length_over_d, dev_b = e - theta_b[t] * length_over_d;
    if constexpr (Viscous) {
      float eb_a = back_a[t], eb_b = back_b[t];
      if constexpr (Advance) {
        const bool on = Masked ? alive[t] != 0.0 : true;
        const float e_last = last_extension[t];
        const double last_a = e_last - last_theta_a[t] * length_over_d, last_b = e_last - last_theta_b[t] * length_over_d;
        const float new_a = next_back_extension(last_a, eb_a, dev_a, one_minus_decay, decay, beta);
        const float new_b = next_back_extension(last_b, eb_b, dev_b, one_minus_decay, decay, beta);
        eb_a = on ? new_a : eb_a;
        eb_b = on ? new_b : eb_b;
        back_a[t] = eb_a;
        back_b[t] = eb_b;
        last_extension[t] = on ? static_cast<float>(e) : e_last;
      }
      dev_a -= lambda * eb_a;
      dev_b -= lambda * eb_b;
    }
    double t_a, t_b;
    if constexpr (Corrected) {
      t_a = force_state(weight_a[t], pressure_a[t], coefficient_a[t], correction_a[t], omega, dev_a);
      t_b = force_state(weight_b[t], pressure_b[t], coefficient_b[t], correction_b[t], omega, dev_b);
    } else {  // g = 1
      t_a = force_state(omega_length, pressure_a[t], coefficient_a[t], 1.0, omega, dev_a);
      t_b = force_state(omega_length, pressure_b[t], coefficient_b[t], 1.0, omega, dev_b);
    }
    double scalar = (t_a + t_b) * volume / r;
    if constexpr (Masked) scalar = alive[t] != 0.0 ? scalar : 0.0;
    out(t, scalar * ex, scalar * ey, scalar * ez, 0.0);
  }
}

/// The bonds of a history cache line (bonds.hpp: one float a bond and direction, a run's bonds in
/// consecutive slots).
inline constexpr std::size_t history_line = 64 / sizeof(float);

/// How many of a run's bonds come before the first cache line boundary of its history at `slot`
/// (history_line where the run starts on one).
inline std::size_t bonds_to_history_line(const float* slot) {
  const std::size_t into = reinterpret_cast<std::uintptr_t>(slot) % 64 / sizeof(float);
  return history_line - into;
}

template <int D, bool Corrected, bool Viscous, bool Advance, bool Masked>
struct StateForceRunKernel {
  /// The terms of bonds [s, e) of the run to out (bond_runs.hpp PairForcesToEnds and ToBuffers, at s).
  template <class Out>
  [[gnu::always_inline]] static void span_terms(const StateForceRun& a, const double* alive, std::size_t s, std::size_t e, Out out) {
    const double *za = nullptr, *zb = nullptr;
    if constexpr (D == 3) za = a.za + s, zb = a.zb + s;
    const double* const alive_s = Masked ? alive + s : nullptr;
    const double *weight_a = nullptr, *weight_b = nullptr, *correction_a = nullptr, *correction_b = nullptr;
    if constexpr (Corrected) weight_a = a.weight_a + s, weight_b = a.weight_b + s, correction_a = a.correction_a + s, correction_b = a.correction_b + s;
    const double *last_theta_a = nullptr, *last_theta_b = nullptr;
    float *back_a = nullptr, *back_b = nullptr, *last_extension = nullptr;
    if constexpr (Viscous) {
      back_a = a.back_a + s, back_b = a.back_b + s;
      if constexpr (Advance) last_theta_a = a.last_theta_a + s, last_theta_b = a.last_theta_b + s, last_extension = a.last_extension + s;
    }
    state_force_run_terms<D, Corrected, Viscous, Advance, Masked>(
        e - s, a.xa + s, a.ya + s, za, a.xb + s, a.yb + s, zb, a.pressure_a + s, a.pressure_b + s, a.coefficient_a + s,
        a.coefficient_b + s, a.theta_a + s, a.theta_b + s, alive_s, weight_a, weight_b, correction_a, correction_b, last_theta_a,
        last_theta_b, back_a, back_b, last_extension, a.lambda, a.one_minus_decay, a.decay, a.beta, a.bond_length, a.omega, a.volume,
        out);
  }

  /// The terms of bonds [s, e) of the run, straight into the ends (ends_apart) or into g.
  [[gnu::always_inline]] static void terms(const StateForceRun& a, const double* alive, std::size_t s, std::size_t e,
                                           double (&g)[3][max_run_length]) {
    if (a.ends_apart) {  // in one loop (bond_runs.hpp ends_apart_in_vectors)
      PairForcesToEnds<D, false> to_ends(a);
      to_ends.fxa += s, to_ends.fya += s, to_ends.fxb += s, to_ends.fyb += s;
      if constexpr (D == 3) to_ends.fza += s, to_ends.fzb += s;
      span_terms(a, alive, s, e, to_ends);
    } else {
      span_terms(a, alive, s, e, PairForcesToBuffers<D, false>{g[0] + s, g[1] + s, g[2] + s, nullptr});
    }
  }

  [[gnu::always_inline]] static bool run(const StateForceRun& a) {
    alignas(64) double own_alive[max_run_length];
    const double* alive = nullptr;
    if constexpr (Masked)
      if (!alive_from_mask(a.mask, a.length, own_alive, alive)) return false;  // every bond of the run broken: nothing to add
    if constexpr (Viscous) {
      // the history of the runs one family offset on (bonds.hpp: the next history_block pairs of
      // either stream): hardware prefetching loses the streams between runs of a few cache lines
      prefetch_history(a.back_a, 2 * Bonds::history_block, a.length);
      prefetch_history(a.back_b, 2 * Bonds::history_block, a.length);
      if constexpr (Advance) prefetch_history(a.last_extension, Bonds::history_block, a.length);
    }
    alignas(64) double g[3][max_run_length];
    if (Masked && Viscous && skip_broken_spans()) {
      // the spans of broken bonds skipped, cut at the history's cache lines: a line whose bonds are
      // all broken is neither read nor written (bond_runs.hpp RunSpans; steps 909-999 of the
      // thesis-size example 10% faster). Every end takes the same terms in the same order: a broken
      // bond's terms are zero
      RunSpans spans;
      cut_run_spans(alive, a.length, bonds_to_history_line(a.back_a), history_line, spans);
      for (std::size_t c = 0; c < spans.count; ++c) {
        const std::size_t s = spans.at[c], e = spans.at[c + 1];
        if (spans.live[c]) terms(a, alive, s, e, g);
        else if (!a.ends_apart)
          for (std::size_t t = s; t < e; ++t) g[0][t] = 0.0, g[1][t] = 0.0, g[2][t] = 0.0;
      }
    } else {
      terms(a, alive, 0, a.length, g);
    }
    if (!a.ends_apart) add_pair_forces_to_run_ends<D>(a, g);
    return false;
  }
};

}  // namespace rift::pd
