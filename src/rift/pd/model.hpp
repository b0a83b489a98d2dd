// The state of a peridynamic run: particles as structure-of-arrays, bonds as CSR, one set of
// constants per body. Bodies occupy contiguous particle ranges, so kernels dispatch on the model
// once per body and run tight loops inside.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/pd/bonds.hpp"
#include "rift/pd/fluid_state.hpp"
#include "rift/pd/interface_bonds.hpp"
#include "rift/pd/material_constants.hpp"
#include "rift/core/index_range.hpp"
#include "rift/pd/numbering.hpp"
#include "rift/pd/platens.hpp"

namespace rift::pd {

struct BodyInfo {
  std::string name;
  std::size_t first = 0, last = 0;  // particle range [first, last)
  std::size_t first_family = 0, family_count = 0;  // its family offsets in Bonds::families
  // the slabs of the passes that visit each bond once (bond_slabs.hpp), set with the bonds: the whole
  // body's slab_count slabs, each slab_length long but the last, which takes the rest
  std::size_t slab_length = 1, slab_count = 1;
  std::vector<BondRun> runs;    // its forward bonds as runs (bond_runs.hpp), slab after slab
  std::vector<std::size_t> slab_runs;  // the runs of slab q: [slab_runs[q], slab_runs[q + 1])
  std::int64_t history_base = 0;  // VES: its first slot in Bonds::back_extension (bond_slabs.hpp history_slot)
  // Where the body's numbering starts: particle i is its (i - origin)-th. It is `first`, except in a
  // rank's window of a distributed run (pd/window.hpp), which may begin inside the body: its slabs,
  // runs and VES history blocks count from the whole body's first particle, so every sum of an
  // owned particle is made in the same order as on one rank.
  std::int64_t origin = 0;
  // the whole run's number of the whole body's first particle: the slabs of the passes count from it
  // (bond_slabs.hpp), in a window of any number of ranges of the numbering
  std::size_t whole_first = 0;
  std::size_t first_slab = 0;  // the whole body's number of the first slab here (its parity orders the passes)
  MaterialConstants constants;
};

/// Refreshes the ghost particles' copies of a per-particle field from the ranks that own them, in a
/// distributed run (pd/window.hpp, pd/halo.hpp).
class Ghosts {
 public:
  virtual ~Ghosts() = default;
  /// `field`: `width` doubles per particle, in the window's numbering.
  virtual void refresh(double* field, std::size_t width) const = 0;
};

template <int D>
class BondCoupling;  // bond_coupling.hpp
template <int D>
class ForceStages;  // force_stages.hpp

template <int D>
struct Model {
  // particle fields (SoA)
  std::vector<Vec<D>> reference_position;  // x0
  std::vector<Vec<D>> position;            // x
  std::vector<Vec<D>> velocity;
  std::vector<Vec<D>> force;               // internal force density (N/m^3)
  std::vector<Vec<D>> body_force;          // external force density from loads (N/m^3)
  std::vector<double> volume;
  std::vector<double> weighted_volume;     // m (Silling et al. 2007, eq. 21)
  std::vector<double> dilatation;          // theta
  std::vector<double> dilatation_coupling; // P_i = sum omega_i (e - theta |xi|/d) |xi| V_j (LPS, zero without correction)
  std::vector<double> stretch_limit;       // s0 of each particle (LAMMPS: s00 - alpha s_min)
  std::vector<double> next_stretch_limit;
  std::vector<double> damage;
  // bond_failure = "normal_stress" only (else empty): the small strain of each particle at the
  // current force evaluation, stress_components<D> per particle (normal_stress_failure.hpp)
  std::vector<double> failure_strain;
  std::vector<std::uint32_t> body;
  std::vector<std::uint8_t> constrained;  // bit k: velocity component k is prescribed
  std::vector<Platen> platens;            // rigid loading plates (platens.hpp)

  Bonds bonds;
  CrackBonds crack_bonds;
  InterfaceBonds interface_bonds;
  FluidNetwork fluid_network;
  std::vector<BodyInfo> bodies;
  int dimension = D;
  double thickness = 1.0;
  double time = 0.0;
  // A distributed run (pd/window.hpp): this rank's window of the particles, the owned ones (ranges
  // of it, ascending) and the ghosts around them, which `ghosts` refreshes from their owners. One
  // rank: every particle is owned (no ranges), no ghosts.
  std::vector<IndexRange> owned_ranges;
  Numbering numbering;  // the whole run's numbers of the window's particles (empty: one rank's)
  // the window's particles whose rows are cut to it (ghosts within the bonds' reach of its edges
  // lose their bonds beyond it), ascending; one rank: none
  std::vector<IndexRange> cut_rows;
  const Ghosts* ghosts = nullptr;
  // what hydraulic fracture couples into the bond passes (bond_coupling.hpp; none: they break dry)
  const BondCoupling<D>* coupling = nullptr;
  // what geomechanics adds to each force evaluation (force_stages.hpp; none: a model without interfaces)
  const ForceStages<D>* stages = nullptr;

  std::size_t size() const { return position.size(); }
  /// The owned particles: ranges of the window, ascending (one rank: [0, size())).
  std::vector<IndexRange> owned() const { return owned_ranges.empty() ? std::vector<IndexRange>{{0, size()}} : owned_ranges; }
  bool owns(std::size_t i) const { return owned_ranges.empty() ? i < size() : any_contains(owned_ranges, i); }
  std::size_t owned_count() const { return owned_ranges.empty() ? size() : count_of(owned_ranges); }
  /// The directed bonds of the owned particles' rows.
  std::size_t owned_bonds() const {
    std::size_t count = 0;
    for (const IndexRange& r : owned())
      if (bonds.offset.size() > r.last) count += static_cast<std::size_t>(bonds.offset[r.last] - bonds.offset[r.first]);
    return count;
  }
  /// The ghosts: the window's particles between and around the owned ranges (one rank: none).
  std::vector<IndexRange> ghost_ranges() const {
    std::vector<IndexRange> ghosts;
    std::size_t from = 0;
    for (const IndexRange& r : owned()) {
      if (r.first > from) ghosts.push_back({from, r.first});
      from = std::max(from, r.last);
    }
    if (from < size()) ghosts.push_back({from, size()});
    return ghosts;
  }
  /// The ghosts' copies of a field of doubles or vectors, from their owners (nothing on one rank).
  void refresh_ghosts(std::vector<double>& field, std::size_t width = 1) const {
    if (ghosts && !field.empty()) ghosts->refresh(field.data(), width);
  }
  void refresh_ghosts(std::vector<Vec<D>>& field) const {
    if (ghosts && !field.empty()) ghosts->refresh(field.data()->data(), D);
  }
  const MaterialConstants& constants_of(std::size_t i) const { return bodies[body[i]].constants; }
  Vec<D> displacement(std::size_t i) const { return position[i] - reference_position[i]; }
  /// Whether particle i continues the lattice line along x of particle i - 1: the same body, and
  /// the same y (and z) in the reference. The lines are the units of the exact sums over the owned
  /// particles (parallel/ordered_sum.hpp exact_sums), which every partition keeps whole (window.hpp).
  bool continues_line(std::size_t i) const {
    if (i == 0 || body[i] != body[i - 1]) return false;
    for (int k = 1; k < D; ++k)
      if (reference_position[i][k] != reference_position[i - 1][k]) return false;
    return true;
  }
  /// The lowest and highest reference coordinate on each axis (the block's faces).
  std::array<Vec<D>, 2> reference_bounds() const {
    std::array<Vec<D>, 2> b;
    for (int k = 0; k < D; ++k) b[0][k] = 1e300, b[1][k] = -1e300;
    for (const auto& x : reference_position)
      for (int k = 0; k < D; ++k) b[0][k] = std::min(b[0][k], x[k]), b[1][k] = std::max(b[1][k], x[k]);
    return b;
  }
  static constexpr std::size_t bytes_per_particle() {
    return sizeof(Vec<D>) * 5 + sizeof(double) * 7 + sizeof(std::uint32_t) + sizeof(std::uint8_t);  // the fields above
  }
};

/// Model::continues_line as a callable: the units of exact sums over the owned particles.
template <int D>
auto line_of(const Model<D>& m) {
  return [&m](std::size_t i) { return m.continues_line(i); };
}

}  // namespace rift::pd
