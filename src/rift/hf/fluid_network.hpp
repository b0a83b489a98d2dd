// Fluid in the cracks that grow from a pressurized borehole or pre-crack. The fluid of a pressure source
// reaches every particle joined to it by a chain of broken bonds: those next to the source (pressure bonds,
// crack_pressure.hpp) and the faces of every crack connected to it. The broken bonds between particles the
// same fluid reaches form its network; the fluid loads the rock around them with the forces that keep a
// uniform compression in equilibrium there (network_load.hpp), so the pressure acts on the crack faces as
// the crack grows (the toughness-dominated limit of hydraulic fracture: no pressure drop along the crack).
// A crack no fluid reaches stays dry, as does a pre-crack without pressure of its own until a fluid reaches
// it across broken bonds or the borehole it starts from; then its cut bonds carry that fluid's pressure. A
// borehole with a breakdown pressure keeps its fluid out of the dry pre-cracks until its pressure first
// reaches it (FluidNetwork::sealed): the breakdown of a wall the lattice does not resolve. A network that
// reaches the outer surface is open (breakthrough): an injected fluid escapes there, and its pressure
// falls to zero while the crack stays open to the surface.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <vector>

#include "rift/core/phase_times.hpp"
#include "rift/geomech/interface_law.hpp"
#include "rift/hf/crack_junction.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/hf/pore_stretch.hpp"
#include "rift/hf/wet_rock.hpp"
#include "rift/parallel/indices_where.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/parallel/sort.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::hf {

/// The source whose pressure the pressure bond k of row i carries: its own, or for a crack without
/// pressure of its own (dry) the fluid that reaches both ends (-1: none).
template <int D>
int pressure_bond_source(const Model<D>& m, std::int64_t k, std::size_t i) {
  const CrackBonds& w = m.crack_bonds;
  const FluidNetwork& f = m.fluid_network;
  if (!f.immersed.empty() && f.immersed[i]) return -1;  // a fragment in the fluid: no net load
  const int own = w.source[static_cast<std::size_t>(k)];
  if (!f.dry[static_cast<std::size_t>(own)]) return own;
  const auto j = w.neighbor[static_cast<std::size_t>(k)];
  if (f.source.empty() || !f.enters_dry_cracks(f.source[i]) || f.source[static_cast<std::size_t>(j)] != f.source[i]) return -1;
  return f.source[i];
}

/// Whether bond k = i-j lets fluid through: broken, or a failed interface whose faces are apart.
template <int D>
bool carries_fluid(const Model<D>& m, std::int64_t k, std::size_t i, std::size_t j) {
  const auto state = m.bonds.intact[static_cast<std::size_t>(k)];
  if (state == bond_broken) return true;
  if (state != bond_interface_failed) return false;
  const InterfaceLaw* law = geomech::interface_of_bond<D>(m, i, k);
  return law && geomech::interface_faces_apart<D>(m, k, i, j, *law);
}

/// The edges along which a fluid at particle i may go on, in the order one rank's search takes
/// them: to(j, false) for each bond of i that carries fluid, then to(j, true) for each bond of i a
/// dry pre-crack cut (which only a fluid that enters dry cracks crosses).
/// Without interface laws a bond carries fluid exactly when it is broken: a row's broken bonds are
/// gathered 64 at a time without a branch per bond (in a damaged row whether a bond is broken is a
/// coin toss, and the branches' misses were most of the search's time), then taken in order.
template <int D, class To>
void for_each_fluid_edge(const Model<D>& m, std::size_t i, To&& to) {
  const Bonds& b = m.bonds;
  const CrackBonds& w = m.crack_bonds;
  if (m.interface_bonds.laws.empty()) {
    constexpr std::int64_t chunk = 64;
    std::int32_t broken[chunk];
    for (auto first = b.offset[i]; first < b.offset[i + 1]; first += chunk) {
      const auto last = std::min(first + chunk, b.offset[i + 1]);
      std::size_t count = 0;
      for (auto k = first; k < last; ++k) {
        broken[count] = b.neighbor[k];
        count += b.intact[static_cast<std::size_t>(k)] == bond_broken ? 1 : 0;
      }
      for (std::size_t q = 0; q < count; ++q) to(static_cast<std::size_t>(broken[q]), false);
    }
  } else {
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
      if (carries_fluid<D>(m, k, i, static_cast<std::size_t>(b.neighbor[k]))) to(static_cast<std::size_t>(b.neighbor[k]), false);
  }
  for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k)
    if (m.fluid_network.dry[w.source[static_cast<std::size_t>(k)]] && w.neighbor[k] >= 0) to(static_cast<std::size_t>(w.neighbor[k]), true);
}

/// The source whose fluid particle i starts with: that of its first cut bond to a crack or borehole
/// with pressure of its own (-1: none, i is not next to a source).
template <int D>
int source_next_to(const Model<D>& m, std::size_t i) {
  const CrackBonds& w = m.crack_bonds;
  for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k)
    if (!m.fluid_network.dry[w.source[static_cast<std::size_t>(k)]]) return w.source[static_cast<std::size_t>(k)];
  return -1;
}

/// Per particle of rows [first, last): its intact and its broken bonds counted (bond states never
/// heal, so any change of state among its bonds changes these). Returns the failed interface bonds
/// of those rows. Where every state is intact or broken (`no_interface`: the model has no interface
/// law), a row the kept rows hold at the states' version is counted from them (pd/bond_runs.hpp
/// kept_row_count), without its states.
inline std::int64_t count_bond_states(const Bonds& b, std::size_t first, std::size_t last, std::vector<std::uint64_t>& counts,
                                      bool no_interface = false) {
  std::vector<Bonds::KeptRows::Made> kept;  // the ranges of kept rows current now
  if (no_interface)
    for (const auto& r : b.kept_rows.made)
      if (r.version == b.intact.version() && r.first < last && first < r.last) kept.push_back(r);
  std::int64_t interface_failed = 0;
#pragma omp parallel for if(rift::parallel::worth_a_team(last - first)) schedule(static) reduction(+ : interface_failed)
  for (std::size_t i = first; i < last; ++i) {
    bool counted = false;
    for (const auto& r : kept)
      if (i >= r.first && i < r.last) counted = kept_row_count(b, r, i, counts[i]);
    if (counted) continue;
    std::uint64_t intact = 0, broken = 0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto state = b.intact[static_cast<std::size_t>(k)];
      intact += state == bond_intact, broken += state == bond_broken;
    }
    counts[i] = intact | broken << 32;
    interface_failed += static_cast<std::int64_t>(b.offset[i + 1] - b.offset[i]) - static_cast<std::int64_t>(intact + broken);
  }
  return interface_failed;
}

namespace detail {

/// Marks immersed the wet particles of the closed pieces found from `starts` (below), and adds the
/// neighbours of those it marked to `candidates`.
template <int D>
void close_pieces(Model<D>& m, const std::vector<std::size_t>& starts, std::vector<std::size_t>& candidates);

/// Peels off, from `candidates` on, the wet particles whose intact bonds do not span D dimensions
/// (below); over_ranks: a distributed run's, each rank deciding its owned particles.
template <int D>
void peel_fragments(Model<D>& m, std::vector<std::size_t> candidates, bool over_ranks);

/// Marks immersed the wet particles of the closed pieces found from `starts`, and peels off, from
/// `candidates` on, the wet particles whose intact bonds do not span D dimensions.
template <int D>
void immerse_fragments(Model<D>& m, const std::vector<std::size_t>& starts, std::vector<std::size_t> candidates) {
  close_pieces<D>(m, starts, candidates);
  peel_fragments<D>(m, std::move(candidates), false);
}

}  // namespace detail

/// Fragments in the fluid. A few particles whose intact bonds no longer join them to the rest of
/// the body (a flake off a borehole's wall, between two cracks), or hold them by bonds that do not
/// span every direction, are surrounded by the fluid, whose pressure on a closed surface has no
/// resultant, and what they displace stays fluid. The loads of
/// the network and the wall (network_load.hpp, crack_pressure.hpp) balance on a particle only as
/// far as the force flux of the wall matches the model's own response, so a detached flake felt a
/// net push and, nothing but the fluid in front of it, moved into the borehole: in Zhou's 2-7
/// (hf_zhou_crossing, at equilibrium) a flake at the wall moved 1.65 mm, the cavity volume counted
/// its travel, and the fluid's pressure fell from 5.4 MPa to 0 in one relaxation. A wet particle
/// whose intact bonds reach fewer particles than a whole family holds is marked immersed: no fluid
/// load, no part of the cavity's volume; so is one whose intact bonds to particles not so marked
/// do not span D dimensions (below).
/// While the network only grows (fluid_network_grows) a particle once immersed stays so: a piece
/// closes only where a bond broke or a fluid came, and peeling only removes directions. So the
/// marks are extended from the particles that changed alone, and equal those made from scratch.
template <int D>
void mark_immersed_fragments(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  const std::size_t n = m.size();
  f.immersed.assign(n, 0);
  std::vector<std::size_t> wet;
  for (std::size_t i = 0; i < n; ++i)
    if (f.source[i] >= 0) wet.push_back(i);
  detail::immerse_fragments<D>(m, wet, wet);
}

namespace detail {

/// The fragments of a distributed run (mark_immersed_fragments): each rank searches for the closed
/// pieces from its owned wet particles, over its window's whole rows (a piece that reaches a row cut
/// to the window counts as joined to the body, as a piece of more than a family does: a piece that
/// small stretched over a bond's reach across the layers, the window's margin, is taken as joined on
/// N ranks where one rank would find it closed), then takes the ghosts' marks from their owners;
/// the peeling goes round by round over every rank, each deciding its own particles from the last
/// round's marks, so it peels what one rank does.
template <int D>
void immerse_over_ranks(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  f.immersed.assign(m.size(), 0);
  std::vector<std::size_t> wet;
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i)
      if (f.source[i] >= 0) wet.push_back(i);
  std::vector<std::size_t> unused;
  close_pieces<D>(m, wet, unused);
  refresh_ghost_values<D>(m, f.immersed);
  std::erase_if(wet, [&](std::size_t i) { return f.immersed[i] != 0; });
  peel_fragments<D>(m, std::move(wet), true);
}

template <int D>
void close_pieces(Model<D>& m, const std::vector<std::size_t>& starts, std::vector<std::size_t>& candidates) {
  FluidNetwork& f = m.fluid_network;
  const Bonds& b = m.bonds;
  const std::size_t n = m.size();
  // Whether a search from a start finds a closed piece depends on the bonds alone (a piece closes
  // where it holds no more than a family), so the starts are searched by the team, each thread with
  // labels of its own, and the closed pieces are marked after, in the order of the starts that found
  // them: the marks and candidates of one thread going through the starts in order (a start in a
  // piece marked before is passed over, and so is a piece found twice).
  struct Closed {
    std::size_t start;  // place in starts
    std::vector<std::size_t> piece;
  };
  std::vector<Closed> closed;
#pragma omp parallel if(rift::parallel::worth_a_team(starts.size()))
  {
    // per particle: 0 not yet reached, -1 joined to more than a family, else the search that reached
    // it; the thread's, kept between calls and left all 0
    static thread_local std::vector<std::int64_t> label;
    label.resize(n, 0);
    std::vector<std::size_t> piece, reached;
    std::vector<Closed> mine;
    std::int64_t search = 0;
#pragma omp for schedule(dynamic, 64) nowait
    for (std::size_t q = 0; q < starts.size(); ++q) {
      const std::size_t start = starts[q];
      if (f.source[start] < 0 || f.immersed[start] || label[start] != 0) continue;
      // a search over intact bonds that stops once the piece holds more than a whole family, or
      // meets a particle an earlier search found so joined
      const std::size_t family = m.bodies[m.body[start]].family_count;
      label[start] = ++search;
      piece.assign(1, start);
      bool is_closed = true;
      for (std::size_t r = 0; r < piece.size() && is_closed; ++r)
        for (auto k = b.offset[piece[r]]; k < b.offset[piece[r] + 1]; ++k) {
          const auto j = static_cast<std::size_t>(b.neighbor[k]);
          if (b.intact[k] != bond_intact || label[j] == search) continue;
          if (label[j] == -1 || piece.size() >= family || any_contains(m.cut_rows, j)) {
            is_closed = false;
            break;
          }
          label[j] = search;
          piece.push_back(j);
        }
      reached.insert(reached.end(), piece.begin(), piece.end());
      if (is_closed) mine.push_back({q, piece});
      else
        for (const std::size_t i : piece) label[i] = -1;
    }
    for (const std::size_t i : reached) label[i] = 0;
#pragma omp critical(rift_close_pieces)
    closed.insert(closed.end(), std::make_move_iterator(mine.begin()), std::make_move_iterator(mine.end()));
  }
  std::sort(closed.begin(), closed.end(), [](const Closed& a, const Closed& c) { return a.start < c.start; });
  for (const Closed& c : closed)
    for (const std::size_t i : c.piece)
      if (f.source[i] >= 0 && !f.immersed[i]) {
        f.immersed[i] = 1;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) candidates.push_back(static_cast<std::size_t>(b.neighbor[k]));
      }
}

template <int D>
void peel_fragments(Model<D>& m, std::vector<std::size_t> candidates, bool over_ranks) {
  FluidNetwork& f = m.fluid_network;
  const Bonds& b = m.bonds;
  const std::size_t n = m.size();
  // a wet particle held by bonds that do not span D dimensions (one bond, or a row of them) turns
  // about them freely: the fluid swung such a particle 0.7 mm about its last bond in 2-7. Peeled
  // off, with the particles it alone held, until every particle left holds on in every direction.
  // Peeling is monotone (a particle peeled off leaves its neighbours fewer directions), so what is
  // left is the same whatever the order: each round decides on every candidate from the last
  // round's flags, in parallel, and the next round looks again only at the wet neighbours of what
  // it peeled.
  // the shape tensor sum n n^T over the intact bonds to particles not immersed, n = xi / |xi| of
  // the bond's family offset (its entries from a table of the offsets' n n^T, in the cache)
  static thread_local std::vector<std::array<double, 6>> direction;
  direction.resize(b.families.size());
  for (std::size_t a = 0; a < b.families.size(); ++a) {
    const FamilyOffset& o = b.families[a];
    std::array<double, 3> n{};
    for (int q = 0; q < D; ++q) n[static_cast<std::size_t>(q)] = o.xi[static_cast<std::size_t>(q)] * o.inverse_length;
    direction[a] = {n[0] * n[0], n[1] * n[1], n[2] * n[2], n[0] * n[1], n[1] * n[2], n[0] * n[2]};
  }
  const std::array<double, 6>* const nn = direction.data();
  auto shape_of = [](const std::array<double, 6>& sum) {
    Eigen::Matrix<double, D, D> shape;
    if constexpr (D == 2) {
      shape << sum[0], sum[3], sum[3], sum[1];
    } else {
      shape << sum[0], sum[3], sum[5], sum[3], sum[1], sum[4], sum[5], sum[4], sum[2];
    }
    return shape;
  };
  // the test: |det S| > 1e-6 (tr S / d)^d. S only grows over the row (by symmetric positive
  // semidefinite terms, and so does its determinant), and its trace is at most the row's bond count
  // (each n n^T has trace 1): a part of the sum whose determinant passes twice the test at that
  // bound passes it whole, and the rest of the row (some hundred bonds, each a random read of its
  // neighbour's mark) is not read. A well-held particle passes within its first 16 bonds.
  constexpr std::int64_t look_every = 16;
  auto spans = [&](std::size_t i) {
    std::array<double, 6> sum{};
    const auto first = b.offset[i], last = b.offset[i + 1];
    const double sure = 2e-6 * std::pow(static_cast<double>(last - first) / D, D);
    for (auto k = first; k < last; ++k) {
      if ((k - first) % look_every == look_every - 1 && std::abs(shape_of(sum).determinant()) > sure) return true;
      if (b.intact[k] != bond_intact || f.immersed[static_cast<std::size_t>(b.neighbor[k])]) continue;
      const auto& add = nn[b.family[static_cast<std::size_t>(k)]];
      for (std::size_t q = 0; q < 6; ++q) sum[q] += add[q];
    }
    const auto shape = shape_of(sum);
    return std::abs(shape.determinant()) > 1e-6 * std::pow(shape.trace() / D, D);
  };
  std::vector<std::uint8_t> peel, queued(n, 0);
  // the wet particles not yet immersed, each once
  std::erase_if(candidates, [&](std::size_t i) {
    if (f.source[i] < 0 || f.immersed[i] || queued[i]) return true;
    queued[i] = 1;
    return false;
  });
  for (const std::size_t i : candidates) queued[i] = 0;
  // on N ranks every rank goes through every round (the ghosts' marks are exchanged in each), and
  // takes as its next candidates its own particles alone
  const auto& ranks = ranks_of<D>(m);
  std::vector<std::size_t> peeled;
  while (over_ranks ? ranks.any(!candidates.empty()) : !candidates.empty()) {
    peel.assign(candidates.size(), 0);
#pragma omp parallel for if(rift::parallel::worth_a_team(candidates.size())) schedule(dynamic, 256)
    for (std::size_t q = 0; q < candidates.size(); ++q) peel[q] = spans(candidates[q]) ? 0 : 1;
    peeled.clear();
    for (std::size_t q = 0; q < candidates.size(); ++q)
      if (peel[q]) f.immersed[candidates[q]] = 1, peeled.push_back(candidates[q]);
    if (over_ranks) {  // and the ghosts their owners peeled in this round
      const std::vector<std::uint8_t> was = f.immersed;
      refresh_ghost_values<D>(m, f.immersed);
      for (std::size_t i = 0; i < n; ++i)
        if (f.immersed[i] && !was[i]) peeled.push_back(i);
    }
    std::vector<std::size_t> next;
    for (const std::size_t i : peeled)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        if (b.intact[k] != bond_intact || f.immersed[j] || f.source[j] < 0 || queued[j] || (over_ranks && !m.owns(j))) continue;
        queued[j] = 1;
        next.push_back(j);
      }
    for (const std::size_t j : next) queued[j] = 0;
    candidates = std::move(next);
  }
}

/// The labels of a distributed run (pd/window.hpp) spread across the cuts between the ranks, after
/// each rank's search over its window (`queue`: the particles it labelled, in order; `spread(i)`
/// goes on from i). Each round takes the ghosts' labels from their owners and goes on from those
/// that came; the rounds end when no rank labelled anything new. A particle a chain of fluid-carrying
/// bonds joins to a source is then labelled by its owner (the chain's particles are labelled in turn,
/// each by its owner from the last one's label as a ghost: a bond's neighbour is in its particle's
/// window), so every owned label is the one-rank run's and every ghost's is its owner's. One fluid
/// spreads at most (two or more: label_as_one_rank): no two labels compete for a particle. A ghost
/// this rank labelled before its owner keeps its label.
template <int D, class Spread>
void spread_over_ranks(Model<D>& m, std::vector<std::size_t>& queue, Spread&& spread) {
  FluidNetwork& f = m.fluid_network;
  const auto& ranks = ranks_of<D>(m);
  for (;;) {
    const std::vector<int> mine = f.source;
    refresh_ghost_values<D>(m, f.source);
    const std::size_t from = queue.size();
    for (std::size_t i = 0; i < mine.size(); ++i) {
      if (f.source[i] == mine[i]) continue;
      if (f.source[i] < 0) f.source[i] = mine[i];
      else if (mine[i] < 0) queue.push_back(i);
    }
    for (std::size_t q = from; q < queue.size(); ++q) spread(queue[q]);
    if (!ranks.any(queue.size() > from)) return;
  }
}

/// The labels of a distributed run where two or more fluids start from their sources: which fluid a
/// particle takes (one a dry pre-crack that both reach, say) follows the order of one rank's search,
/// first reached first served. Every rank gathers the whole run's rows of bonds that carry fluid or
/// cross a dry pre-crack (each rank its owned rows, in the rows' order: the order in which one
/// rank's search goes on from a particle) and the particles next to a source, searches them as one
/// rank does, and keeps its window's labels. `queue` gets the window's particles the fluid reached
/// that are not next to a source; in_crack is marked at both ends of each bond the search crossed.
/// The gathered rows are the networks' (a particle with a bond broken or failed, or on a dry
/// pre-crack's face), not the whole model.
template <int D>
void label_as_one_rank(Model<D>& m, std::vector<std::size_t>& queue) {
  FluidNetwork& f = m.fluid_network;
  const Numbering& numbers = m.numbering;
  auto number = [&](std::size_t i) { return static_cast<std::int64_t>(numbers.whole(i)); };
  // each owned row with any: its number, how many, then each bond's other end j as 2 j, or 2 j + 1
  // across a dry pre-crack (which only a fluid that enters dry cracks crosses)
  std::vector<std::int64_t> rows, seeds;  // seeds: (number, source) of the particles next to a source
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i) {
      const std::size_t at = rows.size();
      rows.push_back(number(i)), rows.push_back(0);
      for_each_fluid_edge<D>(m, i, [&](std::size_t j, bool across_dry) { rows.push_back(2 * number(j) + (across_dry ? 1 : 0)); });
      rows[at + 1] = static_cast<std::int64_t>(rows.size() - at - 2);
      if (rows[at + 1] == 0) rows.resize(at);
      if (const int s = source_next_to<D>(m, i); s >= 0) seeds.push_back(number(i)), seeds.push_back(s);
    }
  const auto& ranks = ranks_of<D>(m);
  const std::vector<std::int64_t> all_rows = ranks.all_gather(rows), all_seeds = ranks.all_gather(seeds);
  std::unordered_map<std::int64_t, std::size_t> row_at;  // a particle's number: where its row starts
  for (std::size_t p = 0; p < all_rows.size(); p += 2 + static_cast<std::size_t>(all_rows[p + 1])) row_at.emplace(all_rows[p], p);
  std::unordered_map<std::int64_t, int> label;
  std::vector<std::int64_t> reached;  // one rank's queue: the seeds ascending (any cut among the ranks)
  std::vector<std::pair<std::int64_t, int>> seed;
  for (std::size_t p = 0; p < all_seeds.size(); p += 2) seed.emplace_back(all_seeds[p], static_cast<int>(all_seeds[p + 1]));
  std::sort(seed.begin(), seed.end());
  for (const auto& [g, s] : seed) {
    label.emplace(g, s);
    reached.push_back(g);
  }
  const std::size_t next_to_source = reached.size();
  auto mark_in_crack = [&](std::int64_t g) {
    if (const std::size_t i = numbers.here(static_cast<std::size_t>(g)); i != Numbering::none) f.in_crack[i] = 1;
  };
  for (std::size_t q = 0; q < reached.size(); ++q) {
    const std::int64_t g = reached[q];
    const int s = label.at(g);
    const auto row = row_at.find(g);
    if (row == row_at.end()) continue;
    const std::size_t p = row->second;
    for (std::size_t e = p + 2; e < p + 2 + static_cast<std::size_t>(all_rows[p + 1]); ++e) {
      const std::int64_t j = all_rows[e] / 2;
      if (all_rows[e] % 2 == 1 && !f.enters_dry_cracks(s)) continue;
      mark_in_crack(g), mark_in_crack(j);
      if (label.emplace(j, s).second) reached.push_back(j);
    }
  }
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto found = label.find(number(i));
    f.source[i] = found == label.end() ? -1 : found->second;
  }
  for (std::size_t q = next_to_source; q < reached.size(); ++q)
    if (const std::size_t i = numbers.here(static_cast<std::size_t>(reached[q])); i != Numbering::none) queue.push_back(i);
}

/// Adds particle i to the particles the network load must evaluate again.
inline void mark_load_changed(FluidNetwork& f, std::size_t i) {
  if (f.load_changed_mark[i]) return;
  f.load_changed_mark[i] = 1;
  f.load_changed.push_back(i);
}

}  // namespace detail

/// Whether the next update may only grow the networks: bonds only break (no failed interface bond,
/// whose faces part and touch again), the labels made once and not to be made again, and one fluid
/// at most starts from its source (two that meet would share their particles by distance).
inline bool fluid_network_grows(const FluidNetwork& f, std::int64_t interface_failed) {
  if (f.relabel || interface_failed > 0) return false;
  return std::count(f.dry.begin(), f.dry.end(), std::uint8_t{0}) <= 1;
}

/// Labels every particle with the pressure source whose fluid reaches it (-1: none), by a search
/// from the particles next to a source (pressure bonds of a borehole or a pressurized crack) across
/// the bonds that carry fluid and the bonds dry pre-cracks cut. Runs again when bonds broke, and
/// every time while failed interfaces may open or close. While the networks only grow
/// (fluid_network_grows), the search goes on from the particles whose bonds broke alone, and the
/// marks, the crack surface and the network load follow from what changed, not from the networks'
/// size: a step's cost follows the bonds that broke in it (the thesis-size example breaks millions).
template <int D>
void update_fluid_network(Model<D>& m) {
  m.coupling = wet_rock_coupling<D>();  // the crack surface made here wets the rock the bond passes break
  FluidNetwork& f = m.fluid_network;
  const Bonds& b = m.bonds;
  const CrackBonds& w = m.crack_bonds;
  const std::size_t n = m.size();
  const bool made = f.source.size() == n && f.bond_counts.size() == n;
  const auto& ranks = ranks_of<D>(m);
  const bool distributed = ranks.distributed();
  // the rows this rank decides: on N ranks its owned particles' (the owners decide the ghosts')
  const std::vector<IndexRange> owned = m.owned(), ghost_rows = m.ghost_ranges();
  // no state changed since the last count (a relaxation's iterations hold the bonds): the counts
  // stand, and no particle's bonds changed on this rank, without a pass over the bonds
  const bool counted = made && f.counted_states == b.intact.version();
  static thread_local std::vector<std::uint64_t> counts;  // the calling thread's, kept between calls
  std::vector<std::uint64_t>& target = counted ? f.bond_counts : counts;
  std::int64_t owned_failed = counted ? f.counted_interface_failed : 0;
  const bool no_interface = m.interface_bonds.laws.empty();  // every state intact or broken
  const auto count_ghost_rows = [&] {
    for (const IndexRange& r : ghost_rows) count_bond_states(b, r.first, r.last, target, no_interface);
  };
  // the particles whose bonds changed state since the last update
  std::vector<std::size_t> changed;
  if (!counted) {
    counts.resize(n);
    for (const IndexRange& r : owned) owned_failed += count_bond_states(b, r.first, r.last, counts, no_interface);
    count_ghost_rows();
    if (made)
      for (const IndexRange& r : owned)
        rift::parallel::append_indices_where(r.first, r.last, changed, [now = counts.data(), before = f.bond_counts.data()](std::size_t i) {
          return now[i] != before[i];
        });
  }
  bool any_changed = !changed.empty();
  if (distributed) {
    // the ghosts' rows as their owners broke them, once a bond changed on any rank
    any_changed = ranks.any(any_changed);
    if (any_changed) {
      refresh_ghost_bond_states<D>(m);
      count_ghost_rows();  // only the ghost rows changed
    }
  }
  if (!counted) std::swap(f.bond_counts, counts);
  f.counted_states = b.intact.version(), f.counted_interface_failed = owned_failed;
  // the failed interface bonds of the whole model (each counted at both ends, as one rank counts them)
  const std::int64_t interface_failed =
      distributed && !m.interface_bonds.laws.empty() ? static_cast<std::int64_t>(ranks.sum(static_cast<double>(owned_failed))) : owned_failed;
  bool grows = made && fluid_network_grows(f, interface_failed);
  if (grows && !any_changed) return;
  // growth from the changed particles alone searches one rank's particles: on N ranks the labels
  // are made again, and the network load evaluated again where growth would (grown)
  const bool grown = grows && distributed;
  if (distributed) grows = false;
  f.load_changed_mark.resize(n, 0);
  for (const std::size_t i : changed) detail::mark_load_changed(f, i);
  f.has_network.resize(f.dry.size(), 0);
  f.open_interface_bonds.resize(f.dry.size());
  f.vented.resize(f.dry.size(), 0);
  f.broke_through.resize(f.dry.size(), 0);
  std::vector<std::size_t> queue;  // the particles the fluid reached in this update's search
  auto reach = [&](std::size_t i, std::size_t j) {
    f.in_crack[i] = f.in_crack[j] = 1;
    if (f.source[j] >= 0) return;
    f.source[j] = f.source[i];
    queue.push_back(j);
  };
  // the fluid of i goes on across its bonds that carry fluid and the dry pre-cracks it may enter:
  // to(j) for each particle j it reaches
  auto spread_from = [&](std::size_t i, auto&& to) {
    for_each_fluid_edge<D>(m, i, [&](std::size_t j, bool across_dry) {
      if (!across_dry || f.enters_dry_cracks(f.source[i])) to(j);
    });
  };
  auto spread = [&](std::size_t i) { spread_from(i, [&](std::size_t j) { reach(i, j); }); };
  if (grows) {
    // on from the wet particles whose bonds broke: a broken bond to a dry particle lets the fluid in.
    // Those particles by the team (a step around a grown crack has tens of thousands): both ends
    // of each bond that carries fluid are in a crack, and the dry particles reached, with the fluid
    // that reached each (from the first of `changed` to reach it), go on in order as before
    std::vector<std::array<std::size_t, 3>> reached;  // (particle, place in changed, source)
#pragma omp parallel if(rift::parallel::worth_a_team(changed.size() * 16))
    {
      std::vector<std::array<std::size_t, 3>> mine;
#pragma omp for schedule(dynamic, 256) nowait
      for (std::size_t q = 0; q < changed.size(); ++q) {
        const std::size_t i = changed[q];
        if (f.source[i] < 0) continue;
        spread_from(i, [&](std::size_t j) {
          std::atomic_ref<std::uint8_t>(f.in_crack[i]).store(1, std::memory_order_relaxed);
          std::atomic_ref<std::uint8_t>(f.in_crack[j]).store(1, std::memory_order_relaxed);
          if (f.source[j] < 0) mine.push_back({j, q, static_cast<std::size_t>(f.source[i])});
        });
      }
#pragma omp critical(rift_fluid_reached)
      reached.insert(reached.end(), mine.begin(), mine.end());
    }
    rift::parallel::sort(reached);
    for (const auto& [j, q, s] : reached)
      if (f.source[j] < 0) f.source[j] = static_cast<int>(s), queue.push_back(j);
    for (std::size_t q = 0; q < queue.size(); ++q) spread(queue[q]);
    for (const std::size_t j : queue) {
      detail::mark_load_changed(f, j);
      if (f.outer_surface.size() == n && f.outer_surface[j]) f.vented[static_cast<std::size_t>(f.source[j])] = 1;
    }
    for (std::size_t s = 0; s < f.vented.size(); ++s) f.broke_through[s] |= f.vented[s];
    // a closed piece or a particle that lost a direction has a bond that broke or a fluid that came
    std::vector<std::size_t> starts = changed;
    starts.insert(starts.end(), queue.begin(), queue.end());
    {
      PhaseClock clock(Phase::fragments);
      detail::immerse_fragments<D>(m, starts, starts);
    }
    for (const std::size_t i : starts)
      if (f.source[i] >= 0 && !f.has_network[static_cast<std::size_t>(f.source[i])])
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
          if (b.intact[static_cast<std::size_t>(k)] == bond_broken && f.source[static_cast<std::size_t>(b.neighbor[k])] == f.source[i])
            f.has_network[static_cast<std::size_t>(f.source[i])] = 1;
    PhaseClock clock(Phase::crack_surface);
    extend_crack_surface<D>(m, starts);
  } else {
    f.relabel = false;
    const std::vector<int> before = made ? f.source : std::vector<int>{};
    f.source.assign(n, -1);
    f.in_crack.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if ((f.source[i] = source_next_to<D>(m, i)) >= 0) queue.push_back(i);
    // the faces of a pressurized pre-crack are in a crack (a borehole's cut bonds end at its sites, -1)
    for (std::size_t i : queue)
      for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k)
        if (!f.dry[w.source[static_cast<std::size_t>(k)]] && w.neighbor[k] >= 0) f.in_crack[i] = 1;
    const std::size_t next_to_source = queue.size();
    if (distributed && std::count(f.dry.begin(), f.dry.end(), std::uint8_t{0}) > 1) {
      detail::label_as_one_rank<D>(m, queue);
    } else {
      for (std::size_t q = 0; q < queue.size(); ++q) spread(queue[q]);
      if (distributed) detail::spread_over_ranks<D>(m, queue, spread);
    }
    // on N ranks: what the owners found of their particles (a ghost's row lacks its bonds beyond
    // the window)
    refresh_ghost_values<D>(m, f.in_crack);
    // breakthrough: a particle on the outer surface that the fluid reached across broken bonds (not
    // the wall of a borehole that itself reaches the surface, whose casing keeps the fluid in). A
    // network can close again (the fluid at zero pressure, failed interface bonds on its path shut),
    // so broke_through keeps that it once did.
    f.vented.assign(f.dry.size(), 0);
    if (f.outer_surface.size() == n)
      for (std::size_t q = next_to_source; q < queue.size(); ++q)
        if (m.owns(queue[q]) && f.outer_surface[queue[q]]) f.vented[static_cast<std::size_t>(f.source[queue[q]])] = 1;
    set_on_any_rank(ranks, f.vented);
    for (std::size_t s = 0; s < f.vented.size(); ++s) f.broke_through[s] |= f.vented[s];
    {
      PhaseClock clock(Phase::fragments);
      if (distributed) detail::immerse_over_ranks<D>(m);
      else mark_immersed_fragments<D>(m);
    }
    // what the network load must evaluate again: both ends of every bond that joined or left a
    // network (those of the particles whose fluid came, went or changed, and the failed interface
    // bonds that opened or shut to a fluid); where the networks grew (on N ranks), what growth
    // marks: the particles whose bonds broke and those the fluid reached, whose evaluation then
    // rounds as one rank's (network_load.hpp)
    if (!made) f.load_from_scratch = true;
    for (std::size_t i = 0; i < before.size(); ++i)
      if (before[i] != f.source[i]) {
        detail::mark_load_changed(f, i);
        if (grown) continue;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
          if (b.intact[static_cast<std::size_t>(k)] != bond_intact) detail::mark_load_changed(f, static_cast<std::size_t>(b.neighbor[k]));
      }
    std::fill(f.has_network.begin(), f.has_network.end(), 0);
    // over every row of the window: a ghost row's bonds lie in the window, their states, labels and
    // (geomech/interface_law.hpp) ends' strains its owner's, and its failed interface bonds that the fluid
    // fills belong in open_interface_bonds (the crack surface and the network load read them)
    std::vector<std::vector<std::int64_t>> open(f.dry.size());
    for (std::size_t i = 0; i < n; ++i) {
      const int s = f.source[i];
      if (s < 0) continue;
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const auto state = b.intact[static_cast<std::size_t>(k)];
        if (state == bond_intact) continue;
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        if (f.source[j] != s || !carries_fluid<D>(m, k, i, j)) continue;
        f.has_network[static_cast<std::size_t>(s)] = 1;
        if (state == bond_interface_failed) open[static_cast<std::size_t>(s)].push_back(k);
      }
    }
    set_on_any_rank(ranks, f.has_network);
    for (std::size_t s = 0; s < open.size(); ++s) {
      std::vector<std::int64_t> opened_or_shut;
      std::set_symmetric_difference(open[s].begin(), open[s].end(), f.open_interface_bonds[s].begin(), f.open_interface_bonds[s].end(),
                                    std::back_inserter(opened_or_shut));
      for (const std::int64_t k : opened_or_shut)
        detail::mark_load_changed(f, b.row_of(k)), detail::mark_load_changed(f, static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]));
      f.open_interface_bonds[s] = std::move(open[s]);
    }
    if (distributed) {
      // the ghosts' marks are their owners' (whose rows are whole)
      refresh_ghost_values<D>(m, f.load_changed_mark);
      f.list_load_changed_from_marks();
    }
    PhaseClock clock(Phase::crack_surface);
    remake_crack_surface<D>(m);
  }
  mark_bonds_across_crack<D>(m);  // the contact of the failed interface bonds at a junction
  update_pore_stretch<D>(m);  // the rock the fluid reached is wet at once
}

/// The broken bonds source s's fluid fills, both entries of each, ascending (the network whose
/// load network_load.hpp makes).
template <int D>
std::vector<std::int64_t> network_bond_list(const Model<D>& m, int s) {
  const FluidNetwork& f = m.fluid_network;
  const Bonds& b = m.bonds;
  std::vector<std::int64_t> list;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
      if (network_of_bond(f, b, i, k) == s) list.push_back(k);
  return list;
}

/// Whether source s's fluid flows by the cubic law, with a pressure per particle (viscous_fluid.hpp).
inline bool is_viscous(const FluidNetwork& f, std::size_t s) {
  return f.flows(s) && !f.local_pressure.empty();
}

/// Adds the fluid's load on the broken bonds of each network to m.body_force: p_s g_s (g: the
/// network load, network_load.hpp; pressure[s] as in add_crack_pressure), or for a viscous fluid
/// p_i g_s,i with p_i its local pressure at particle i.
template <int D>
void add_network_pressure(Model<D>& m, const std::vector<double>& pressure) {
  const FluidNetwork& f = m.fluid_network;
  for (std::size_t s = 0; s < f.network_load.size() && s < pressure.size(); ++s) {
    const auto& g = f.network_load[s];
    const bool local = is_viscous(f, s);
    if (g.empty() || (pressure[s] == 0.0 && !local)) continue;
    const double p = pressure[s];
    const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      if (f.immersed.empty() || !f.immersed[i]) {
        const double p_i = local ? f.local_pressure[i] : p;
        for (int q = 0; q < D; ++q) m.body_force[i][q] += p_i * g[i * D + static_cast<std::size_t>(q)];
      }
  }
}

/// Volume change of source s's cavity (borehole and the cracks joined to it) from the reference
/// state, defined as the work conjugate of the pressure forces: p dV = sum_i f_i . du_i V_i. A bond
/// to a fluid site adds coef |xi| V_i (-xi/|xi| . u_i) (its force keeps the reference direction),
/// a cut bond between two particles adds coef |xi| V_i (|y| - |xi|) / 2 from each end (coef V_i is
/// symmetric), the network's load g_s . u_i V_i. For a flat crack whose faces part by w this is w
/// times the face area. wall_only: the bonds to fluid sites alone (a borehole's own volume).
template <int D>
double cavity_volume_change(const Model<D>& m, int s, bool wall_only = false) {
  const CrackBonds& w = m.crack_bonds;
  const auto& loads = m.fluid_network.network_load;
  const std::vector<double>* network = static_cast<std::size_t>(s) < loads.size() && !loads[static_cast<std::size_t>(s)].empty()
                                           ? &loads[static_cast<std::size_t>(s)] : nullptr;
  // over the owned particles, in the one-rank run's order on any number of ranks (ordered_sum.hpp)
  const auto sums = parallel::exact_sums<1>(ranks_of<D>(m), m.owned(), line_of(m), [&](std::size_t i, std::array<double, 1>& acc) {
    for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
      if (pressure_bond_source<D>(m, k, i) != s || (wall_only && w.neighbor[k] >= 0)) continue;
      const auto& x = w.xi[k];
      const double xi = w.length(static_cast<std::size_t>(k));
      if (w.neighbor[k] < 0) {
        double along = 0.0;  // -xi_hat . u_i
        for (int q = 0; q < D; ++q) along -= x[q] / xi * (m.position[i][q] - m.reference_position[i][q]);
        acc[0] += w.coefficient[k] * xi * m.volume[i] * along;
      } else {
        const double y = norm<D>(m.position[static_cast<std::size_t>(w.neighbor[k])] - m.position[i]);
        acc[0] += 0.5 * w.coefficient[k] * xi * m.volume[i] * (y - xi);
      }
    }
    if (network && !wall_only && (m.fluid_network.immersed.empty() || !m.fluid_network.immersed[i]))
      for (int q = 0; q < D; ++q)
        acc[0] += (*network)[i * D + static_cast<std::size_t>(q)] * (m.position[i][q] - m.reference_position[i][q]) * m.volume[i];
  });
  return sums[0];
}

}  // namespace rift::hf
