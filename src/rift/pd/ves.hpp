// Viscoelastic ordinary state-based peridynamics (Mitchell 2011, SAND2011-8064; LAMMPS peri/ves): the LPS
// of lps.hpp whose deviatoric response has an elastic share 1 - lambda and a viscous share lambda acting
// on e_d - e_b; the back extension e_b relaxes toward e_d = e - theta |xi| / d with relaxation time tau,
//   d e_b / dt = (e_d - e_b) / tau,   exact over a step with e_d linear in time (viscous_step.hpp).
// With e_b held fixed over the step, the free energy and the force state are
//   W_i = kappa/2 theta_i^2 + a_i/2 sum_j sigma_ij [(1 - lambda) e_d^2 + lambda (e_d - e_b)^2] V_j,
//   t_i<j> = b_ij (kappa theta_i - a_i P_i / d) + a_i sigma_ij (e_d - lambda e_b),
//   P_i = sum_j sigma_ij (e_d - lambda e_b) |xi| V_j,
// a_i, sigma_ij, b_ij as in lps.hpp (lambda = 0: the LPS exactly). A held deviatoric strain relaxes as
// G [(1 - lambda) + lambda exp(-t / tau)] (standard linear solid). Unlike LAMMPS peri/ves, t_j<i> uses j's
// own dilatation and back extension (Newton's third law holds), and the surface correction's P term is kept.
// Why: docs/decisions/method-notes.md.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/viscous_step.hpp"
#include "rift/parallel/sort.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Zero history for the VES bodies, laid out by lattice offset (bonds.hpp, bond_slabs.hpp
/// history_index): per block of Bonds::history_block particles, two directions of every forward
/// offset; e(0) = 0 and theta(0) = 0 at the reference positions; the per-particle sums of
/// ves_dilatation to be taken on the first evaluation. `has_history(body)`: whether the body's law
/// keeps a history of each bond (laws/registry.hpp).
template <int D, class HasHistory>
void prepare_viscous_history(Model<D>& m, HasHistory has_history) {
  std::size_t slots = 0;
  for (auto& body : m.bodies) {
    if (!has_history(body)) continue;
    constexpr std::size_t block = Bonds::history_block;
    body.history_base = static_cast<std::int64_t>(slots);
    slots += (body.last - body.first + block - 1) / block * (body.family_count / 2) * 2 * block;
  }
  if (slots == 0) return;
  parallel_fill(m.bonds.back_extension, slots, 0.0f);
  parallel_fill(m.bonds.last_extension, slots / 2, 0.0f);
  m.bonds.history_dilatation.assign(m.size(), 0.0);
  m.bonds.deviatoric_sum.assign(m.size(), 0.0);
  m.bonds.back_sum.assign(m.size(), 0.0);
  m.bonds.intact_weighted_volume.assign(m.size(), 0.0);
  m.bonds.summed_bonds.assign(m.size(), -1);
  m.bonds.back_extension_at_rest = true;
}

/// Bond k of row i's terms in its row's sums (sum_viscous_history): g omega |xi| V times e_d(n),
/// e_b(n) and |xi|.
struct ViscousTerms {
  double deviatoric, back, weighted_volume;
};
template <int D, scene::Influence Omega>
ViscousTerms viscous_terms(const Bonds& b, const BodyInfo& body, std::size_t i, std::int64_t k) {
  const double xi = b.length(k);
  const double w = b.correction(i, k) * influence(Omega, xi, body.constants.horizon) * xi * b.volume(k);  // g omega |xi| V
  const std::size_t h = history_slot(b, body, i, k);
  return {w * last_deviatoric_extension<D>(b, h, i, xi), w * b.back_extension[h], w * xi};
}

/// The sums of particle i's row over its intact bonds (bonds.hpp deviatoric_sum, back_sum,
/// intact_weighted_volume, summed_bonds), from the history.
template <int D, scene::Influence Omega>
void sum_viscous_history(Model<D>& m, const BodyInfo& body, std::size_t i, std::int32_t intact_bonds) {
  Bonds& b = m.bonds;
  double deviatoric = 0.0, back = 0.0, weighted_volume = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[static_cast<std::size_t>(k)] != bond_intact) continue;
    const ViscousTerms t = viscous_terms<D, Omega>(b, body, i, k);
    deviatoric += t.deviatoric, back += t.back, weighted_volume += t.weighted_volume;
  }
  b.deviatoric_sum[i] = deviatoric, b.back_sum[i] = back, b.intact_weighted_volume[i] = weighted_volume;
  b.summed_bonds[i] = intact_bonds;
}

/// Takes the bonds the dilatation pass broke ((i, k) of the lower end's row) out of both ends'
/// sums (sum_viscous_history), term by term, where a row summed again (its bonds' history scattered
/// over the blocks: 6% of a thesis-size step at 7% broken bonds) would give them up to rounding.
/// Each particle's terms go in the order of its row, so the sums do not depend on the order the
/// pass found them in: first those where it is the upper end (neighbours below it), then those
/// where it is the lower end. By the team, each thread a range of particles (a thesis-size step
/// breaks half a million pairs, which one thread took out while the other waited). A row whose
/// intact bonds changed otherwise (an interface law) is still summed again.
template <int D, scene::Influence Omega>
void take_out_of_viscous_sums(Model<D>& m, const BodyInfo& body, std::vector<std::pair<std::size_t, std::int64_t>>& broken) {
  using Entry = std::pair<std::size_t, std::int64_t>;
  Bonds& b = m.bonds;
  if (broken.empty()) return;
  static thread_local std::vector<Entry> upper_ends;  // (j, k of j's row): the calling thread's, the team's through the reference
  std::vector<Entry>& upper = upper_ends;
  upper.resize(broken.size());
  Entry* const up = upper.data();
  const bool team = rift::parallel::worth_a_team(broken.size());
#pragma omp parallel for if(team) schedule(static)
  for (std::size_t q = 0; q < broken.size(); ++q) {
    const auto [i, k] = broken[q];
    up[q] = {static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]), reverse_bond(b, body, i, k)};
  }
  rift::parallel::sort(broken);
  rift::parallel::sort(upper);
  auto take_out = [&](std::size_t i, std::int64_t k) {
    if (b.summed_bonds[i] < 0) return;  // not summed yet
    const ViscousTerms t = viscous_terms<D, Omega>(b, body, i, k);
    b.deviatoric_sum[i] -= t.deviatoric, b.back_sum[i] -= t.back, b.intact_weighted_volume[i] -= t.weighted_volume;
    --b.summed_bonds[i];
  };
  // the particles split into ranges at equal counts of the lower ends' entries
  constexpr std::size_t chunks = 64;
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  auto bound = [&](std::size_t c) { return c == 0 ? 0 : c == chunks ? none : broken[broken.size() * c / chunks].first; };
  auto from = [](const std::vector<Entry>& list, std::size_t p) {
    return std::lower_bound(list.begin(), list.end(), Entry{p, std::numeric_limits<std::int64_t>::min()});
  };
#pragma omp parallel for if(team) schedule(dynamic, 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t first = bound(c), last = bound(c + 1);
    if (first == last) continue;
    auto a = from(broken, first), u = from(upper, first);
    const auto a_end = from(broken, last), u_end = from(upper, last);
    while (a != a_end || u != u_end) {
      const std::size_t p = std::min(a != a_end ? a->first : none, u != u_end ? u->first : none);
      for (; u != u_end && u->first == p; ++u) take_out(p, u->second);
      for (; a != a_end && a->first == p; ++a) take_out(p, a->second);
    }
  }
}

/// First pass: dilatation and bond breaking (as the LPS), then P_i = sum_j g omega |xi| V (e_d -
/// lambda e_b) of the new step per particle, without a pass over the bonds' history: the update of
/// e_b is linear, so over the bonds intact now
///   sum g omega |xi| V e_b(n+1) = (1 - decay - beta) S_d + decay S_b + beta C,
///   C = sum g omega |xi| V e_d(n+1) = q_i - theta_i m'_i / d,
/// S_d, S_b the sums of e_d(n) and the stored e_b(n) (taken again, row by row, for a particle whose
/// intact bonds changed since), q_i = sum g omega |xi| e V (theta_i m_i / d without the surface
/// correction) and m'_i = sum g omega |xi|^2 V over the intact bonds. C and the new sum are the
/// next step's S_d and S_b. The bonds' own histories advance in the force pass (lps.hpp
/// state_based_forces, Viscous), which needs P_i of both ends before it: two passes over the bonds
/// instead of three. P differs from the sum over the stored single-precision back extensions by
/// their rounding (tests/test_viscoelastic.cpp).
/// `rows_out`, where given, receives the rows' states after the pass (dilatation_pass); they give
/// each row's count of intact bonds here.
template <int D, scene::Influence Omega>
void ves_dilatation(Model<D>& m, const BodyInfo& body, double dt, RowStates* rows_out = nullptr) {
  const auto& c = body.constants;
  Bonds& b = m.bonds;
  const double lambda = c.viscous_fraction;
  const ViscousStep step(dt, c.relaxation_time);
  double* const smallest = pass_buffer(m.size(), PassBuffer::smallest_stretch);
  double* const q = pass_buffer(m.size(), PassBuffer::coupling);  // with the surface correction: q_i
  const bool corrected = c.surface_correction;
  std::vector<std::pair<std::size_t, std::int64_t>> broken;
  RowStates local_rows;
  RowStates& rows = rows_out ? *rows_out : local_rows;
  if (corrected) dilatation_pass<D, Omega, true>(m, body, q, smallest, &broken, &rows);
  else dilatation_pass<D, Omega, false>(m, body, nullptr, smallest, &broken, &rows);
  take_out_of_viscous_sums<D, Omega>(m, body, broken);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
  for (std::size_t i = body.first; i < body.last; ++i) {
    const std::int32_t intact_bonds = intact_bond_count(b, rows, i);
    if (intact_bonds != b.summed_bonds[i]) sum_viscous_history<D, Omega>(m, body, i, intact_bonds);
    const double theta = m.dilatation[i], m_intact = b.intact_weighted_volume[i];
    const double deviatoric = corrected ? q[i] - theta * m_intact / D : theta * (m.weighted_volume[i] - m_intact) / D;  // C
    const double back = step.advance ? (step.one_minus_decay - step.beta) * b.deviatoric_sum[i] + step.decay * b.back_sum[i] +
                                           step.beta * deviatoric
                                     : b.back_sum[i];
    m.dilatation_coupling[i] = deviatoric - lambda * back;
    if (step.advance) b.deviatoric_sum[i] = deviatoric, b.back_sum[i] = back;
  }
  next_stretch_limits<D>(m, body, smallest);
}

}  // namespace rift::pd
