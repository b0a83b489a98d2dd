// The load of a fluid on the rock around the cracks it has filled: the discrete unjacketed test. Cracks
// holding fluid at p, with -p on the outer boundary too, compress a solid uniformly by -p I with no
// effective stress (Biot coefficient 1; Detournay and Cheng 1993, section 2.2). The fluid of source s loads
// particle i by p_s g_s,i, with g the model's own:
//   g_s,i = (F_i(eps) - F_i^s(eps)) / (eps d kappa_i),
// F(eps) the internal force density under the uniform expansion x = (1 + eps) X with the bonds as they are,
// F^s the same with s's network's broken bonds held intact. Every model is linear in a uniform expansion,
// so g does not depend on eps and the strain -p / (d kappa) is an equilibrium of the loaded network (LPS,
// flat crack: traction p on each face). Viscoelastic: the instantaneous (LPS) response. Cut bonds and a
// borehole's wall keep the force flux (crack_pressure.hpp). g is made only on the network's ends and their
// neighbours, from each end's kept NetworkEnd; without the surface correction by runs of bonds
// (network_load_runs.hpp). Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include "rift/hf/fluid_network.hpp"
#include "rift/hf/network_load_runs.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/parallel/sort.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/laws/registry.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace rift::hf {

namespace detail {

/// NetworkEnd of particle i (network_end) from its sums over the intact bonds (th, q) and over the
/// network's (d_th, d_q).
template <int D>
NetworkEnd end_from_sums(const Model<D>& m, std::size_t i, double th, double q, double d_th, double d_q) {
  const auto& c = m.constants_of(i);
  const double m_i = m.weighted_volume[i], scale = c.surface_correction ? 1.0 : dilatation_scale<D>(m_i);
  th = (th + d_th) * scale, d_th *= scale;
  NetworkEnd z;
  z.theta = th, z.d_theta = d_th;
  z.a = m_i > 0.0 ? c.lps_deviatoric_coefficient() / m_i : 0.0;
  // b_ij p_i, with b_ij = omega |xi| d / m_i without the surface correction: the scale folded into p
  z.held = pressure_factor<D>(c.kappa, th, z.a, q + d_q - th * m_i / D) * scale;
  z.change = pressure_factor<D>(c.kappa, d_th, z.a, d_q - d_th * m_i / D) * scale;
  return z;
}

/// What the network load reads of particle i (PMB: nothing) under the unit uniform expansion
/// y = 2 X (e = |xi|): its theta and P (lps.hpp lps_dilatation) with the network's bonds held
/// intact, the network bonds' share of each (F^s less F), and its p of both (force_state).
/// `is_end`: whether i has a bond in the network (an end), found in the same pass. `state_based`:
/// whether i's law reads the dilatation (laws/registry.hpp).
template <int D, class InNetwork>
NetworkEnd network_end(const Model<D>& m, std::size_t i, bool state_based, InNetwork in_network, bool& is_end) {
  const Bonds& b = m.bonds;
  const auto& c = m.constants_of(i);
  is_end = false;
  if (!state_based) {
    for (auto k = b.offset[i]; k < b.offset[i + 1] && !is_end; ++k) is_end = b.intact[static_cast<std::size_t>(k)] != bond_intact && in_network(i, k);
    return {};
  }
  double th = 0.0, q = 0.0, d_th = 0.0, d_q = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    const bool intact = b.intact[static_cast<std::size_t>(k)] == bond_intact;
    if (!intact && !in_network(i, k)) continue;
    is_end |= !intact;
    const double xi = b.length(k), ev = xi * b.volume(k);
    const double w = influence(c.influence, xi, c.horizon) * xi * ev;
    const BondFactors& g = b.factors_of(i, k);
    const double t = c.surface_correction ? g.dilatation_weight * ev : w, u = c.surface_correction ? g.correction * w : w;
    if (intact) th += t, q += u;
    else d_th += t, d_q += u;
  }
  return end_from_sums<D>(m, i, th, q, d_th, d_q);
}

/// Per family offset of the model, its body's omega(|xi|), |xi| / d and omega |xi|^2 V (a bond's
/// term of theta and q without the surface correction, as network_end makes it): read from a
/// table, the passes below divide by nothing per bond (a division was a sixth of their time).
struct FamilyTerms {
  std::vector<double> omega, length_over_d, weight;
};

template <int D>
FamilyTerms family_terms(const Model<D>& m) {
  FamilyTerms t;
  const auto& families = m.bonds.families;
  t.omega.assign(families.size(), 0.0), t.length_over_d.assign(families.size(), 0.0), t.weight.assign(families.size(), 0.0);
  for (const auto& body : m.bodies)
    for (std::size_t a = body.first_family; a < body.first_family + body.family_count; ++a) {
      const double xi = families[a].length;
      t.omega[a] = influence(body.constants.influence, xi, body.constants.horizon);
      t.length_over_d[a] = xi / D;
      t.weight[a] = t.omega[a] * xi * (xi * families[a].volume);
    }
  return t;
}

/// network_end of source s where g is made by the runs (load_by_runs: no surface correction, no
/// interface law, so a bond is intact or broken, and a broken one is in s's network where the fluid
/// of s reached both ends): the same sums to the bit, without a branch on a bond's state (in the
/// damaged rows, where it is a coin toss, the branches' misses were most of network_end's time).
/// Every term of q is theta's (omega |xi|^2 V, from `terms`), so q and theta are one sum. A particle
/// the fluid of s has not reached has no network bond: not an end, nothing summed. Zero where i is
/// not an end (as update_network_load keeps it).
template <int D>
NetworkEnd uncorrected_network_end(const Model<D>& m, std::size_t i, int s, const FamilyTerms& terms, bool& is_end) {
  const Bonds& b = m.bonds;
  const int* const source = m.fluid_network.source.data();
  is_end = false;
  if (source[i] != s) return {};
  const double* const weight = terms.weight.data();
  double th = 0.0, d_th = 0.0;  // adding +0.0 leaves a sum's bits as they are
  bool end = false;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    const auto state = b.intact[static_cast<std::size_t>(k)];
    const bool network = state == bond_broken && source[static_cast<std::size_t>(b.neighbor[k])] == s;
    const double w = weight[b.family[static_cast<std::size_t>(k)]];
    th += state == bond_intact ? w : 0.0;
    d_th += network ? w : 0.0;
    end |= network;
  }
  is_end = end;
  return end ? end_from_sums<D>(m, i, th, th, d_th, d_th) : NetworkEnd{};
}

/// t of end z of a bond (force_state) under the unit expansion: with the network held (a network
/// bond), or its change (an intact bond); zero where the particle is not an end (z all zero).
/// xi_over_d: |xi| / d.
inline double end_force_state(const NetworkEnd& z, bool intact, const MaterialConstants& c, const BondFactors& g, double omega, double xi,
                              double xi_over_d) {
  const double weight = c.surface_correction ? double(g.dilatation_weight) : omega * xi;
  if (!intact) return force_state(weight, z.held, z.a, g.correction, omega, xi - z.theta * xi_over_d);
  return weight * z.change - z.a * g.correction * omega * z.d_theta * xi_over_d;
}

/// Whether two NetworkEnd hold the same values (an end's change reaches its neighbours only then).
inline bool same_end(const NetworkEnd& a, const NetworkEnd& z) {
  return a.theta == z.theta && a.d_theta == z.d_theta && a.a == z.a && a.held == z.held && a.change == z.change;
}

/// One pass over the rows of the particles `changed` (ascending; marked in `in_changed`) that
/// makes, for one source, into g (g_i = (F_i - F^s_i) / (d kappa_i)):
/// - F_x - F^s_x of each of them (no bond breaking, the VES by its LPS response) under the unit uniform expansion y = 2 X: F with the bonds as they are, F^s
///   with the network's broken bonds (in_network(i, k): entry k of row i, not intact) held intact as
///   well. Every model is linear in a uniform expansion (e = eps |xi|, y / |y| = xi / |xi|), so this
///   is the difference under any expansion eps divided by eps, and needs no positions. The formulas
///   of pmb.hpp and lps.hpp, summed as the difference itself: a network bond adds -f^s (its pair
///   force in F^s); an intact bond adds the change of its pair force, which is linear in the
///   changes of its ends' dilatation and P (pd/laws/ordinary_state.hpp force_state, pressure_factor), nonzero only
///   where an end has network bonds (an end: is_end[i], its NetworkEnd ends[i], zero for the others); every other
///   bond adds nothing and is skipped. So a particle's sum reads its network bonds and its bonds to
///   ends alone, and F and F^s never cancel each other's rounding.
/// - With `before` (their NetworkEnd as g was last made; empty: g made from scratch, nothing to
///   correct), the change their ends make on the neighbours that are not among them, added to
///   their g. Such a neighbour j keeps its own bonds' states and
///   memberships (both ends of a bond that changed are in `changed`) and its own NetworkEnd, so of
///   its sum only the terms of its bonds to a changed end x change, and in them only t_x
///   (end_force_state): by -(t_x now - t_x before) along xi_jx.
/// Each thread owns a range of particles (split at equal counts of `changed`): it sums the rows of
/// the changed particles in it (their g made again), and adds the corrections to the neighbours in it, in the order of
/// `changed`, from the ends within a bond's reach of it. So the result does not depend on the
/// number of threads, and each changed row is read once for both (they were two passes, a third of
/// the network load each).
template <int D, class InNetwork>
void changed_rows_pass(const Model<D>& m, const std::vector<std::size_t>& changed, const std::vector<NetworkEnd>& before,
                       const std::vector<std::uint8_t>& is_end, const std::vector<NetworkEnd>& ends, const FamilyTerms& terms,
                       const std::vector<std::uint8_t>& in_changed, InNetwork in_network, std::vector<double>& g) {
  const Bonds& b = m.bonds;
  const std::size_t n = m.size(), count = changed.size();
  if (count == 0) return;
  constexpr std::int64_t prefetch_ahead = 12;
  auto now = [&](std::size_t q) { return ends[changed[q]]; };  // zero where not an end
  // the entries whose NetworkEnd changed, and how far a bond of theirs reaches in particle numbers
  // (rows are sorted by neighbour)
  std::vector<std::uint8_t> moved(count, 0);
  std::size_t reach = 0;
  if (!before.empty())
    for (std::size_t q = 0; q < count; ++q) {
      const std::size_t x = changed[q];
      if (same_end(now(q), before[q]) || b.offset[x + 1] == b.offset[x]) continue;
      moved[q] = 1;
      const auto low = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(b.offset[x])]);
      const auto high = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(b.offset[x + 1] - 1)]);
      reach = std::max({reach, x > low ? x - low : 0, high > x ? high - x : 0});
    }
  const std::vector<LawTraits> laws = body_laws(m.bodies);
#pragma omp parallel if(rift::parallel::worth_a_team(count))
  {
#ifdef _OPENMP
    const auto id = static_cast<std::size_t>(omp_get_thread_num()), threads = static_cast<std::size_t>(omp_get_num_threads());
#else
    const std::size_t id = 0, threads = 1;
#endif
    const std::size_t lo = id == 0 ? 0 : changed[count * id / threads], hi = id + 1 == threads ? n : changed[count * (id + 1) / threads];
    // the changed particles in [lo, hi) and the ends that can reach it: `changed` is ascending
    for (auto q = static_cast<std::size_t>(std::lower_bound(changed.begin(), changed.end(), lo > reach ? lo - reach : 0) - changed.begin());
         q < count && changed[q] < hi + reach; ++q) {
      const std::size_t x = changed[q];
      const auto& c = m.constants_of(x);  // and of every neighbour: bonds join particles of one body
      const bool pmb = !laws[m.body[x]].state_based;  // a bond-based law (PMB): its pair forces do not read the ends
      const bool own = x >= lo && x < hi, correct = moved[q] && !pmb;
      if (!own && !correct) continue;
      const NetworkEnd z = now(q), old = correct ? before[q] : NetworkEnd{};
      Vec<D> sum{};
      const std::int64_t row_end = b.offset[x + 1];
      for (auto k = b.offset[x]; k < row_end; ++k) {
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        // the neighbours' NetworkEnd and g are scattered over a few planes of the lattice: asked
        // for some bonds ahead
        if (k + prefetch_ahead < row_end) {
          const auto ahead = static_cast<std::size_t>(b.neighbor[k + prefetch_ahead]);
          __builtin_prefetch(&ends[ahead]);
          __builtin_prefetch(&g[ahead * D], 1);
        }
        const bool intact = b.intact[static_cast<std::size_t>(k)] == bond_intact;
        const bool corrects = correct && j >= lo && j < hi && !in_changed[j];
        const bool sums = own && (intact ? !pmb && (is_end[x] || is_end[j]) : true);
        if (!corrects && !sums) continue;
        if (!intact && !in_network(x, k)) continue;
        const std::size_t a = b.family[static_cast<std::size_t>(k)];
        if (sums) {
          const FamilyOffset& family = b.families[a];
          const double xi = family.length, omega = terms.omega[a];
          double pair;  // F less F^s of this bond
          if (pmb) {
            pair = -pmb_bond_force(c.micromodulus * omega, 1.0, pmb_factor(b.correction(x, k), b.mirror_correction(j, k)));
          } else {
            auto t = [&](std::size_t e, const BondFactors& f) {
              if (!is_end[e]) return 0.0;
              return end_force_state(ends[e], intact, c, f, omega, xi, terms.length_over_d[a]);
            };
            pair = -(t(x, b.factors_of(x, k)) + t(j, b.mirror_factors_of(j, k)));
          }
          // along y_j - y_i, whose direction is xi's
          const double scale = pair * family.volume * family.inverse_length;
          for (int r = 0; r < D; ++r) sum[r] += scale * family.xi[static_cast<std::size_t>(r)];
        }
        if (corrects) {
          const std::size_t mirror = b.families[a].mirror;
          const FamilyOffset& family = b.families[mirror];  // j's side, xi_jx
          const double xi = family.length, omega = terms.omega[mirror], xi_over_d = terms.length_over_d[mirror];
          const BondFactors& factors = b.factors_of(x, k);  // x's side of the bond
          const double t_change =
              end_force_state(z, intact, c, factors, omega, xi, xi_over_d) - end_force_state(old, intact, c, factors, omega, xi, xi_over_d);
          const double scale = -t_change * family.volume * family.inverse_length / (D * c.kappa);
          for (int r = 0; r < D; ++r) g[j * D + static_cast<std::size_t>(r)] += scale * family.xi[static_cast<std::size_t>(r)];
        }
      }
      if (!own) continue;
      const double scale = 1.0 / (D * c.kappa);
      for (int r = 0; r < D; ++r) g[x * D + static_cast<std::size_t>(r)] = sum[r] * scale;
    }
  }
}

/// Whether g is made by the runs (network_load_runs.hpp): every body LPS or VES without the surface
/// correction, with its runs, and no interface law (whose failed bonds join a network only where the
/// fluid opened them: FluidNetwork::open_interface_bonds).
template <int D>
bool load_by_runs(const Model<D>& m) {
  if (!m.interface_bonds.laws.empty()) return false;
  for (const auto& body : m.bodies) {
    if (body.last <= body.first) continue;
    const auto& c = body.constants;
    if (!law_traits(c.model).state_based || c.surface_correction || body.slab_runs.size() < 2)
      return false;
  }
  return true;
}

/// g of source s from its ends (network_load_runs.hpp) by the runs of every body, as the force pass
/// sums (lps.hpp state_based_forces): in an order that depends on the bonds alone, so on any number
/// of threads and ranks the same bits. Only g of the blocks of particles that hold a particle of
/// `changed` (the ends made again) or a neighbour of one is made again (all of them where `all`):
/// g_i reads i's bonds' states and the terms of i and its neighbours alone, so every other g is as
/// it was. A block's g is made from every run that reaches the block, as the whole pass makes it,
/// so it is the same bits as the pass over every run made from scratch. The runs' terms of the ends
/// are kept in `cache` from call to call and made again for `changed` alone (they were made for
/// every particle each call: a pass over 4 million NetworkEnd at the thesis size).
/// `terms`: each family offset's omega (family_terms).
template <int D>
void network_load_by_runs(const Model<D>& m, int s, const std::vector<NetworkEnd>& ends, const std::vector<std::size_t>& changed, bool all,
                          const FamilyTerms& terms, NetworkRunTerms& cache, std::vector<double>& g) {
  const Bonds& b = m.bonds;
  const FluidNetwork& f = m.fluid_network;
  const std::size_t n = m.size();
  constexpr std::size_t block = network_load_block;
  const std::size_t blocks = (n + block - 1) / block;
  // the runs' terms of every particle where g is made from scratch, where the cache is new, or on N
  // ranks (each call gives every ghost its owner's NetworkEnd again: refresh_ghost_ends)
  const bool every = all || cache.change.size() != n || cache.block_has_end.size() != blocks || m.ghosts;
  if (every) cache.change.resize(n), cache.held.resize(n), cache.block_has_end.resize(blocks);
  double* const change = cache.change.data();
  double* const held = cache.held.data();
  auto terms_of = [&](std::size_t i) {
    const NetworkEnd& z = ends[i];
    change[i] = z.change - z.a * z.d_theta / D;
    held[i] = f.source[i] == s ? z.held + z.a * (1.0 - z.theta / D) : std::numeric_limits<double>::quiet_NaN();  // NaN: dry
  };
  const std::size_t count = every ? n : changed.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(count)) schedule(static)
  for (std::size_t q = 0; q < count; ++q) terms_of(every ? q : changed[q]);
  // per block, whether its g is made again: the calling thread's, the team writes it through the
  // pointer
  static thread_local std::vector<std::uint8_t> remade;
  remade.assign(blocks, all ? 1 : 0);
  std::uint8_t* const block_remade = remade.data();
  std::uint8_t* const block_has_end = cache.block_has_end.data();
  if (!all) {
#pragma omp parallel for if(rift::parallel::worth_a_team(changed.size() * 16)) schedule(static)
    for (std::size_t q = 0; q < changed.size(); ++q) {
      const std::size_t x = changed[q];
      std::atomic_ref<std::uint8_t>(block_remade[x / block]).store(1, std::memory_order_relaxed);
      for (auto k = b.offset[x]; k < b.offset[x + 1]; ++k)
        std::atomic_ref<std::uint8_t>(block_remade[static_cast<std::size_t>(b.neighbor[k]) / block]).store(1, std::memory_order_relaxed);
    }
  }
  // the sums of the blocks made again start at zero (the others' are not read); whether a block
  // holds an end (change nonzero, or held a nonzero number) changes only where an end was made
  // again, in a block made again: a run that reaches no block of either kind adds nothing to a g
  // made again, and is skipped (at the thesis size a pass over every run was a tenth of an early step)
  std::array<double*, 3> sum{};
  for (int q = 0; q < D; ++q) sum[static_cast<std::size_t>(q)] = pass_buffer(n, component(PassBuffer::force_x, q));
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t first = 0; first < n; first += block) {
    if (!every && !block_remade[first / block]) continue;
    const std::size_t last = std::min(n, first + block);
    bool any = false;
    for (std::size_t i = first; i < last; ++i) any |= change[i] != 0.0 || (held[i] == held[i] && held[i] != 0.0);
    block_has_end[first / block] = any ? 1 : 0;
    if (block_remade[first / block])
      for (int q = 0; q < D; ++q) std::fill(sum[static_cast<std::size_t>(q)] + first, sum[static_cast<std::size_t>(q)] + last, 0.0);
  }
  // whether a block of [first, first + length) is so marked
  auto any_in = [&](const std::uint8_t* marked, std::size_t first, std::size_t length) {
    for (std::size_t q = first / block; q <= (first + length - 1) / block; ++q)
      if (marked[q]) return true;
    return false;
  };
  const VectorIsa isa = vector_isa();
  for (const auto& body : m.bodies) {
    if (body.last <= body.first) continue;
    const RowStates rows = whole_rows(b, body);
    for_each_run_by_slabs(body, [&](const BondRun& run) {
      const std::size_t length = run.length, i = static_cast<std::size_t>(run.i), j = static_cast<std::size_t>(run.j);
      if (!any_in(block_remade, i, length) && !any_in(block_remade, j, length)) return;
      if (!any_in(block_has_end, i, length) && !any_in(block_has_end, j, length)) return;  // zeros: every sum's bits as they are
      const FamilyOffset& family = b.families[run.family];
      const double scale = -terms.omega[run.family] * family.volume;  // -omega V
      std::array<double, 3> k{};
      for (int q = 0; q < D; ++q) k[static_cast<std::size_t>(q)] = scale * family.xi[static_cast<std::size_t>(q)];
      if (length < short_run) {  // bond by bond
        for (std::size_t t = 0; t < length; ++t) {
          const double w = network_bond_sum(run_bond_intact(b, run, rows, t), change[i + t], change[j + t], held[i + t], held[j + t]);
          for (std::size_t q = 0; q < static_cast<std::size_t>(D); ++q) sum[q][i + t] += w * k[q], sum[q][j + t] -= w * k[q];
        }
        return;
      }
      alignas(64) double alive[max_run_length];
      static thread_local NetworkLoadRun a;  // the thread's: every run sets what its form reads
      const bool masked = run_mask(b, run, rows, alive, a.mask);
      a.length = length;
      a.change_a = change + i, a.change_b = change + j, a.held_a = held + i, a.held_b = held + j;
      a.kx = k[0], a.ky = k[1], a.kz = k[2];
      a.fxa = sum[0] + i, a.fya = sum[1] + i, a.fxb = sum[0] + j, a.fyb = sum[1] + j;
      if constexpr (D == 3) a.fza = sum[2] + i, a.fzb = sum[2] + j;
      a.ends_apart = ends_apart_in_vectors(run);
      if (masked) vector_clone<NetworkLoadRunKernel<D, true>, NetworkLoadRun>(isa)(a);
      else vector_clone<NetworkLoadRunKernel<D, false>, NetworkLoadRun>(isa)(a);
    });
  }
  // g_i = (F_i - F^s_i) / (d kappa_i) of the blocks made again
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t first = 0; first < n; first += block) {
    if (!block_remade[first / block]) continue;
    for (std::size_t i = first; i < std::min(n, first + block); ++i) {
      const double scale = 1.0 / (D * m.constants_of(i).kappa);
      for (std::size_t q = 0; q < static_cast<std::size_t>(D); ++q) g[i * D + q] = sum[q][i] * scale;
    }
  }
}

/// The ghosts' is_end and NetworkEnd from their owners (nothing on one rank).
template <int D>
void refresh_ghost_ends(const Model<D>& m, std::vector<std::uint8_t>& is_end, std::vector<NetworkEnd>& ends) {
  if (!m.ghosts) return;
  static_assert(sizeof(NetworkEnd) == 5 * sizeof(double));
  constexpr std::size_t width = 6;
  std::vector<double> packed(is_end.size() * width);
  for (std::size_t i = 0; i < is_end.size(); ++i) {
    const NetworkEnd& z = ends[i];
    const std::array<double, width> row{double(is_end[i]), z.theta, z.d_theta, z.a, z.held, z.change};
    std::copy(row.begin(), row.end(), packed.begin() + static_cast<std::ptrdiff_t>(i * width));
  }
  m.ghosts->refresh(packed.data(), width);
  for (std::size_t i = 0; i < is_end.size(); ++i) {
    const double* row = &packed[i * width];
    is_end[i] = row[0] != 0.0 ? 1 : 0;
    ends[i] = NetworkEnd{row[1], row[2], row[3], row[4], row[5]};
  }
}

}  // namespace detail

/// Makes g_s for every source whose network changed since the last call (call after
/// update_fluid_network). Reads the model, changes nothing of its state.
/// Incremental: g_i reads the bonds of i and the NetworkEnd of its neighbours, so it changes only
/// where a bond of i or of a neighbour changed state or joined or left the network since the last
/// call (FluidNetwork::load_changed, which update_fluid_network keeps). g of those particles is
/// evaluated again by the same sum as from scratch; on their neighbours the terms of the changed
/// ends are corrected by what changed (changed_rows_pass), which equals g made from scratch up to
/// the rounding of the corrections (1e-16 of the largest |g| per correction; within 1e-13 in
/// tests/test_network_load.cpp).
template <int D>
void update_network_load(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  const bool scratch = f.load_from_scratch;
  // on N ranks every rank goes on where any has something to evaluate (the ends are exchanged)
  const auto& ranks = ranks_of<D>(m);
  if (ranks.distributed() ? !ranks.any(scratch || !f.load_changed.empty()) : !scratch && f.load_changed.empty()) return;
  const Bonds& b = m.bonds;
  const std::size_t n = m.size();
  const std::size_t sources = f.dry.size();
  const detail::FamilyTerms terms = detail::family_terms<D>(m);
  const bool by_runs = detail::load_by_runs<D>(m);
  f.network_load.resize(sources), f.is_end.resize(sources), f.network_ends.resize(sources), f.network_run_terms.resize(sources);
  for (std::size_t s = 0; s < sources; ++s) {
    auto& g = f.network_load[s];
    auto& is_end = f.is_end[s];
    auto& ends = f.network_ends[s];
    if (s >= f.has_network.size() || !f.has_network[s]) {
      g.clear(), is_end.clear(), ends.clear(), f.network_run_terms[s] = {};
      continue;
    }
    const bool all = scratch || g.empty();  // g made from scratch: every particle evaluated
    // the ends' NetworkEnd by particle: a row's neighbours' are then near each other in memory (kept
    // in a list in the order the ends came, their reads missed the cache: a third of the pass)
    if (all) g.assign(n * D, 0.0), is_end.assign(n, 0), ends.assign(n, NetworkEnd{});
    const int source = static_cast<int>(s);
    auto in_network = [&](std::size_t i, std::int64_t k) { return network_of_bond(f, b, i, k) == source; };
    // the ends whose bonds changed state or joined or left the network (both ends of each are in
    // load_changed): their NetworkEnd made again
    std::vector<std::size_t> changed;
    std::vector<NetworkEnd> before;  // their NetworkEnd as g was last made (zero: not an end)
    if (all) {
      changed.resize(n);
      for (std::size_t i = 0; i < n; ++i) changed[i] = i;
    } else {
      changed = f.load_changed;
      rift::parallel::sort(changed);
      if (!by_runs) {  // the runs make g from the ends alone
        before.resize(changed.size());
        for (std::size_t q = 0; q < changed.size(); ++q) before[q] = ends[changed[q]];
      }
    }
    // in one pass each: whether it is an end, and its NetworkEnd
    const std::vector<LawTraits> laws = body_laws(m.bodies);
#pragma omp parallel for if(rift::parallel::worth_a_team(changed.size())) schedule(static)
    for (std::size_t q = 0; q < changed.size(); ++q) {
      const std::size_t i = changed[q];
      bool end = false;
      const NetworkEnd z = by_runs ? detail::uncorrected_network_end<D>(m, i, source, terms, end) : detail::network_end<D>(m, i, laws[m.body[i]].state_based, in_network, end);
      is_end[i] = end ? 1 : 0;
      ends[i] = end ? z : NetworkEnd{};
    }
    // a ghost's row is cut to the window: its NetworkEnd is its owner's
    detail::refresh_ghost_ends<D>(m, is_end, ends);
    // g by the runs on the blocks within reach of those made again, or of those made again and
    // their neighbours' changed by the changes of their ends
    if (by_runs) detail::network_load_by_runs<D>(m, source, ends, changed, all, terms, f.network_run_terms[s], g);
    else detail::changed_rows_pass<D>(m, changed, before, is_end, ends, terms, f.load_changed_mark, in_network, g);
  }
  f.load_from_scratch = false;
  for (const std::size_t i : f.load_changed) f.load_changed_mark[i] = 0;
  f.load_changed.clear();
}

/// Forgets the network load: the next update_network_load makes it from scratch.
inline void forget_network_load(FluidNetwork& f) {
  f.network_load.clear();
  f.load_from_scratch = true;
}

}  // namespace rift::hf
