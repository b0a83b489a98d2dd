// Prototype microelastic brittle (PMB) bond force (Silling and Askari 2005, eq. 15-16):
// f = c omega(|xi|) s V_j along the deformed bond, s = (|y| - |xi|) / |xi|; with the surface
// correction each end contributes half with its own influence factor: c (g_i + g_j)/2 omega s V_j. A bond breaks for good
// when s exceeds min(s0_i, s0_j); s0_i = s00 - alpha s_min,i (eq. 23, as LAMMPS peri/pmb); in a
// crack's wet rock the limit is on the effective stretch (effective_stretch.hpp).
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/effective_stretch.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Bond force density per unit V_j along the deformed bond, c omega s (g_i + g_j) / 2.
inline double pmb_bond_force(double micromodulus, double omega, double s, float correction, float mirror_correction) {
  return micromodulus * omega * s * (0.5f * (correction + mirror_correction));
}

/// What the PMB pass reads of a neighbour, packed in one record per particle instead of three
/// arrays: its position, s0_j and its row of factors.
template <int D>
struct BondEndInputs {
  Vec<D> position;
  double stretch_limit;
  std::int64_t factor_row;
};

template <int D, scene::Influence Omega>
void pmb_forces(Model<D>& m, const BodyInfo& body) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double micromodulus = c.micromodulus, horizon = c.horizon;
  const bool breakable = c.breakable;
  const WetRock<D> wet = wet_rock(m);
  // bonds join particles of one body; the buffer is the calling thread's, which the team writes and
  // reads through `in`; `smallest`: the smallest stretch of each particle's intact bonds
  static thread_local std::vector<BondEndInputs<D>> inputs;
  inputs.resize(m.size());
  BondEndInputs<D>* const in = inputs.data();
  double* const smallest = pass_scratch(m.size(), 1);
  constexpr double none = std::numeric_limits<double>::max();
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t j = body.first; j < body.last; ++j) {
    in[j] = {m.position[j], m.stretch_limit[j], b.factor_row[j]};
    m.force[j] = Vec<D>{};
    smallest[j] = none;
  }
  // each bond once, from its lower end (bond_slabs.hpp): s is the same seen from either end, and so
  // is the pair force c omega s (g_i + g_j)/2 V along the bond (one lattice cell volume per body)
  std::vector<std::pair<std::size_t, std::int64_t>> broken, crossing;  // (i, k) of the bonds broken here, and of those across the crack
  const BondView bonds = b.view();
  Vec<D>* const forces = m.force.data();
  // the wet rock's shift is compiled in only where there is wet rock (effective_stretch.hpp), the
  // influence-function factors only with the surface correction (without it they are all 1)
  auto row = [&]<bool Wet, bool Corrected>(std::size_t i) {
    const BondView v = bonds;  // locals: registers (bonds.hpp)
    Vec<D>* const force = forces;
    double* const s_smallest = smallest;
    const BondEndInputs<D>* const ends = in;
    const BondEndInputs<D> own = ends[i];
    Vec<D> f{};
    double s_min = s_smallest[i];
    for (auto k = first_forward_bond(b, i); k < v.offset[i + 1]; ++k) {
      if (v.intact[k] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(v.neighbor[k]);
      const BondEndInputs<D>& other = ends[j];
      const Vec<D> eta = other.position - own.position;
      const double r = norm<D>(eta);
      const FamilyOffset& family = v.families[v.family[k]];
      const double xi = family.length;
      const double s = (r - xi) * family.inverse_length;
      const double limit = std::min(own.stretch_limit, other.stretch_limit);
      bool past = s > limit, crossed = false;
      if constexpr (Wet) past = breakable && breaks_in_wet_rock<D>(wet, c.alpha, i, j, s, limit, crossed);
      if (breakable && past) {
        v.intact[k] = bond_broken;
#pragma omp critical(rift_pmb_broken)
        {
          broken.emplace_back(i, k);
          if (crossed) crossing.emplace_back(i, k);
        }
        continue;
      }
      s_min = std::min(s_min, s);
      s_smallest[j] = std::min(s_smallest[j], s);
      float g_i = 1.0f, g_j = 1.0f;
      if constexpr (Corrected) {
        g_i = v.factors[own.factor_row + v.family[k]].correction;
        g_j = v.factors[other.factor_row + family.mirror].correction;
      }
      const double scalar = pmb_bond_force(micromodulus, influence(Omega, xi, horizon), s, g_i, g_j) * family.volume / r;
      for (int q = 0; q < D; ++q) {
        f[q] += scalar * eta[q];
        force[j][q] -= scalar * eta[q];
      }
    }
    for (int q = 0; q < D; ++q) force[i][q] += f[q];
    s_smallest[i] = s_min;
  };
  auto rows = [&]<bool Wet>() {
    if (c.surface_correction)
      for_each_row_by_slabs(body, [&](std::size_t i) { row.template operator()<Wet, true>(i); });
    else
      for_each_row_by_slabs(body, [&](std::size_t i) { row.template operator()<Wet, false>(i); });
  };
  if (wet)
    rows.template operator()<true>();
  else
    rows.template operator()<false>();
  for (const auto& [i, k] : broken) break_mirror_bond(b, body, i, k);
  record_crossing_breaks<D>(m, crossing);
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
