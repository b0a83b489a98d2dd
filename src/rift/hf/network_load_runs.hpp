// The network load (network_load.hpp) of the bodies without the surface correction, in one pass over the
// runs of bonds (pd/bond_runs.hpp). Without the correction every factor of a bond is one, and t of end e
// of a bond under the unit expansion (network_load.hpp end_force_state) is omega |xi| times a number of e
// alone, from its NetworkEnd z:
//   a network bond: t_e = omega |xi| held_e,   held_e = z.held + z.a (1 - z.theta / d),
//   an intact bond: t_e = omega |xi| change_e, change_e = z.change - z.a z.d_theta / d,
// both zero where e has no network bond (z zero). held_e is NaN where the fluid did not reach e, so a broken
// bond's held_i + held_j is a number exactly where the bond is the network's (no array of wet ends). The
// pair force of F - F^s along xi is -(t_i + t_j) V / |xi|: a bond adds -omega V (s_i + s_j) xi to g_i (the
// opposite to g_j), s the ends' change or held by the bond's state; per run (one family offset) a constant
// vector times a sum of two numbers read contiguously at both ends.
// Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <cstddef>

#include "rift/core/vector_isa.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/pd/bond_runs.hpp"

namespace rift::hf {

/// One run of the network load pass: the lower ends' arrays start at a, the upper ends' at b;
/// `mask` (Masked: pd/bond_runs.hpp run_mask): which bonds are intact; held: NaN where the network's
/// fluid did not reach the particle (FluidNetwork::source); k: -omega V xi of the run's family; g:
/// the sums, per component.
struct NetworkLoadRun {
  std::size_t length = 0;
  const double *change_a = nullptr, *change_b = nullptr, *held_a = nullptr, *held_b = nullptr;
  RunMask mask;  // Masked
  double kx = 0.0, ky = 0.0, kz = 0.0;
  double *fxa = nullptr, *fya = nullptr, *fza = nullptr, *fxb = nullptr, *fyb = nullptr, *fzb = nullptr;
  bool ends_apart = false;  // pd/bond_runs.hpp ends_apart_in_vectors: the one-loop form
};

/// s_i + s_j of a bond (the file's comment): the ends' changes for an intact bond, their held values
/// for a broken bond between two wet particles (a network bond: the sum a number), else nothing.
[[gnu::always_inline]] inline double network_bond_sum(bool intact, double change_i, double change_j, double held_i, double held_j) {
  const double held = held_i + held_j;
  const double network = held == held ? held : 0.0;
  return intact ? change_i + change_j : network;
}

/// The pair terms (s_i + s_j) k of a run's bonds, bond t's to out(t, ...) (pd/bond_runs.hpp
/// PairForcesToEnds, PairForcesToBuffers).
template <int D, bool Masked, class Out>
[[gnu::always_inline]] inline void network_load_run_terms(std::size_t length, const double* __restrict change_a,
                                                          const double* __restrict change_b, const double* __restrict held_a,
                                                          const double* __restrict held_b, const double* __restrict alive, double kx,
                                                          double ky, double kz, Out out) {
#pragma omp simd safelen(simd_ends_apart)
  for (std::size_t t = 0; t < length; ++t) {
    const bool intact = Masked ? alive[t] != 0.0 : true;
    const double w = network_bond_sum(intact, change_a[t], change_b[t], held_a[t], held_b[t]);
    out(t, w * kx, w * ky, w * kz, 0.0);
  }
}

template <int D, bool Masked>
struct NetworkLoadRunKernel {
  [[gnu::always_inline]] static bool run(const NetworkLoadRun& a) {
    alignas(64) double own_alive[max_run_length];
    const double* alive = nullptr;
    if constexpr (Masked) alive_from_mask(a.mask, a.length, own_alive, alive);  // a broken bond adds where it is the network's
    if (a.ends_apart) {  // in one loop (pd/bond_runs.hpp ends_apart_in_vectors)
      network_load_run_terms<D, Masked>(a.length, a.change_a, a.change_b, a.held_a, a.held_b, alive, a.kx, a.ky, a.kz,
                                        PairForcesToEnds<D, false>(a));
      return false;
    }
    alignas(64) double g[3][max_run_length];
    network_load_run_terms<D, Masked>(a.length, a.change_a, a.change_b, a.held_a, a.held_b, alive, a.kx, a.ky, a.kz,
                                      PairForcesToBuffers<D, false>{g[0], g[1], g[2], nullptr});
    add_pair_forces_to_run_ends<D>(a, g);
    return false;
  }
};

}  // namespace rift::hf
