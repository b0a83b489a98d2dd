// Bond families in compressed-sparse-row form: row i lists the bonds of particle i, sorted by
// neighbour (both i-j and j-i are stored, as LAMMPS PERI does; the force passes visit each bond once,
// from its lower end, bond_slabs.hpp). A bond stores its neighbour, its lattice offset (an index into
// the bodies' family offsets: length, neighbour volume, reverse offset) and its state: 7 bytes. The
// influence-function factors of the surface correction sit in one row per particle, shared by the
// particles whose family is whole.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rift/parallel/uninitialized_vector.hpp"
#include "rift/pd/bond_states.hpp"

namespace rift::pd {

/// States of a bond (Bonds::intact).
inline constexpr std::uint8_t bond_broken = 0;
inline constexpr std::uint8_t bond_intact = 1;
/// A bond across a pre-existing fracture whose interface law failed (geomech/interface_law.hpp): no longer
/// part of the material model; a frictional contact between its two particles instead (normal
/// force while the faces are pressed on each other, Coulomb friction along them, none apart).
inline constexpr std::uint8_t bond_interface_failed = 2;

/// One lattice offset of a body's family (discretize.cpp). Every bond with this offset has the same
/// reference vector, length and neighbour volume share, so a bond stores only the offset's index.
struct FamilyOffset {
  std::array<double, 3> xi{};  // reference bond vector x_j - x_i (z = 0 in 2D)
  double length = 0.0;         // |xi| (double: no spurious stretch)
  double inverse_length = 0.0; // 1 / |xi|: the stretch is a product
  double volume = 0.0;         // V_j times the partial-volume fraction of j inside the horizon of i
  std::uint32_t mirror = 0;    // the offset -xi: the bond j-i of the bond i-j
};

/// A run of bonds (bond_runs.hpp): `length` consecutive particles i, i + 1, ... whose bonds of one
/// family offset join them to j, j + 1, ...: on a lattice numbered x fastest, a line of sites and
/// the same line moved by the offset. The passes take a run's bonds together, in vectors.
struct BondRun {
  static constexpr std::uint32_t varies = 0xffffffffu;
  std::int32_t i = 0, j = 0;        // the first particle and its neighbour
  std::uint32_t position = varies;  // the bonds' place in their rows, bond offset[i + t] + position, where all have the same
  std::uint16_t family = 0;         // the offset's index in Bonds::families
  std::uint16_t length = 0;
};

/// What one particle's influence function makes of one family offset (surface_correction.hpp).
struct BondFactors {
  float correction = 1.0f;         // g_i: the particle's influence-function factor (1 when off)
  float dilatation_weight = 0.0f;  // b_ij: theta_i = sum b_ij e_ij V_j (LPS and VES only)
};

/// Raw views of the bond arrays for the hot loops. Copied into a loop's locals these pointers stay in
/// registers; read through the vectors they would be reloaded after every store to a bond's state
/// (a one-byte store may alias anything).
struct BondView {
  const std::int64_t* offset;
  const std::int32_t* neighbor;
  const std::uint16_t* family;
  std::uint8_t* intact;
  const FamilyOffset* families;
  const BondFactors* factors;
  const std::int64_t* factor_row;
};

struct Bonds {
  std::vector<std::int64_t> offset;    // size n+1; row i is [offset[i], offset[i+1])
  // the per-bond arrays are first touched by the passes that fill them (parallel/uninitialized_vector.hpp)
  uninitialized_vector<std::int32_t> neighbor;  // j
  uninitialized_vector<std::uint16_t> family;   // the bond's lattice offset, an index into `families`
  BondStates intact;                            // bond_intact, bond_broken (never heals) or bond_interface_failed
  std::vector<FamilyOffset> families;  // every body's family offsets, body after body
  // The factors of particle i's side of its bonds: factors[factor_row[i] + family[k]]. Particles
  // whose family is whole (no surface, crack or borehole cuts it) have equal factors and share one
  // row per body; the others own one.
  std::vector<std::int64_t> factor_row;
  std::vector<BondFactors> factors;
  // VES only (empty otherwise), per directed bond i-j: i's back extension after the last step
  // (Mitchell 2011; stored in single precision, 6e-8 relative rounding), by
  // lattice offset (bond_slabs.hpp history_slot): per block of history_block particles of a body,
  // per forward family offset, the lower ends' directions of the block's particles, then the upper
  // ends'. A run of bonds (bond_runs.hpp) then finds both directions' histories in two contiguous
  // stretches, and the slots need no index of their own (a slot is kept for an offset whose
  // neighbour is missing: 2% of the slots at the thesis' size, 8% on the 41^3 bench cube).
  static constexpr std::size_t history_block = 256;
  uninitialized_vector<float> back_extension;
  // VES only: the extension e = |y| - |xi| of every pair when the history last advanced, once per
  // pair (both directions share it; single precision), at pair_slot of its direction-0 slot
  // (bond_slabs.hpp), and every particle's dilatation then: a bond's deviatoric extension then,
  // e_d(n) = e(n) - theta_i(n) |xi| / d, is taken from them (viscous_step.hpp
  // last_deviatoric_extension) without a copy per directed bond.
  uninitialized_vector<float> last_extension;
  std::vector<double> history_dilatation;
  // VES only, per particle i: over the intact bonds of its row, the sums of g omega |xi| V times
  // e_d(n) and i's back extension, and of g omega |xi|^2 V (g the surface correction), and how many
  // bonds they were taken over (-1: not yet). P_i of the next step follows from them without a pass
  // over the history (ves.hpp ves_dilatation).
  std::vector<double> deviatoric_sum, back_sum, intact_weighted_volume;
  std::vector<std::int32_t> summed_bonds;
  // VES only: every back extension is zero, as made (ves.hpp prepare_viscous_history), until a force
  // pass first advances them. While the history is held (dt = 0: the in-situ stage, dynamic
  // relaxation) the viscous terms then vanish, and the force pass need not read the history
  // (forces.cpp). A cache, not state: false after a checkpoint's restore and in a window.
  bool back_extension_at_rest = false;
  // The rows made from `intact` for the passes (bond_runs.hpp whole_rows), kept while the states
  // stay as they were: per particle, whether its row is whole and the bits of its intact offsets,
  // and which particles' rows [first, last) were made at which version of the states. A cache, not
  // state: a checkpoint's restore replaces the states, so the rows are made again.
  struct KeptRows {
    struct Made {
      std::size_t first = 0, last = 0;
      std::uint64_t version = 0;
      std::size_t words = 0;  // of the bits of intact offsets per particle (0: none kept)
    };
    std::vector<std::uint8_t> whole;
    std::vector<std::uint64_t> intact;
    std::vector<Made> made;
  };
  mutable KeptRows kept_rows;

  std::int64_t size() const { return static_cast<std::int64_t>(neighbor.size()); }
  /// A pass that writes bond states through the view calls intact.changed() after it.
  BondView view() {
    return {offset.data(), neighbor.data(), family.data(), intact.writable(), families.data(), factors.data(), factor_row.data()};
  }
  /// The particle whose row holds entry k.
  std::size_t row_of(std::int64_t k) const {
    return static_cast<std::size_t>(std::upper_bound(offset.begin(), offset.end(), k) - offset.begin() - 1);
  }
  const FamilyOffset& family_of(std::int64_t k) const { return families[family[static_cast<std::size_t>(k)]]; }
  double length(std::int64_t k) const { return family_of(k).length; }
  double volume(std::int64_t k) const { return family_of(k).volume; }
  /// The factors of i's side of bond k of row i, and of j's side (the bond j-i).
  const BondFactors& factors_of(std::size_t i, std::int64_t k) const {
    return factors[static_cast<std::size_t>(factor_row[i] + family[static_cast<std::size_t>(k)])];
  }
  const BondFactors& mirror_factors_of(std::size_t j, std::int64_t k) const {
    return factors[static_cast<std::size_t>(factor_row[j] + family_of(k).mirror)];
  }
  float correction(std::size_t i, std::int64_t k) const { return factors_of(i, k).correction; }
  float mirror_correction(std::size_t j, std::int64_t k) const { return mirror_factors_of(j, k).correction; }
  /// Bytes held per directed bond: the arrays above with one entry per bond, and the factor rows,
  /// family offsets and the VES history's per-particle arrays spread over the bonds.
  double bytes_per_directed_bond() const {
    if (neighbor.empty()) return 0.0;
    const double per_bond = sizeof(std::int32_t) + sizeof(std::uint16_t) + sizeof(std::uint8_t);
    const double tables = double(factors.size() * sizeof(BondFactors) + families.size() * sizeof(FamilyOffset) +
                                 (back_extension.size() + last_extension.size()) * sizeof(float) +
                                 (history_dilatation.size() + deviatoric_sum.size() + back_sum.size() + intact_weighted_volume.size()) *
                                     sizeof(double) +
                                 summed_bonds.size() * sizeof(std::int32_t));
    return per_bond + tables / double(neighbor.size());
  }
};

}  // namespace rift::pd
