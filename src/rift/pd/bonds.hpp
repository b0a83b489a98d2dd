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
/// A bond across a pre-existing fracture whose interface law failed (interface_law.hpp): no longer
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

/// Bonds that carry fluid pressure (hf/crack_pressure.hpp), row i listing those of particle i: bonds a
/// pressurized pre-crack cuts (never created in Bonds), and bonds from the material to the fluid
/// sites of a borehole (neighbor -1: a lattice site of the body inside the borehole).
struct CrackBonds {
  std::vector<std::int64_t> offset;   // size n+1 (empty rows when nothing is pressurized)
  std::vector<std::int32_t> neighbor; // j, or -1 for a fluid site
  std::vector<float> volume;          // V_j * partial-volume fraction
  std::vector<std::uint16_t> source;  // pressure source: scene crack c, or borehole b as cracks + b
  std::vector<std::array<double, 3>> xi;  // reference bond vector x_j - x_i
  std::vector<double> fluid_weighted_volume;  // m of a fluid site (its whole family); 0 for particles
  std::vector<double> coefficient;    // d omega V_j (1/m_i + 1/m_j), whole-family weighted volumes

  /// |xi| of pressure bond k.
  double length(std::size_t k) const { return std::sqrt(xi[k][0] * xi[k][0] + xi[k][1] * xi[k][1] + xi[k][2] * xi[k][2]); }
};

/// A pre-existing fracture's plane and its interface law (scene::Interface), 3D vectors also in 2D.
struct InterfaceLaw {
  std::array<double, 3> point{}, normal{};  // a point of the plane and its unit normal
  std::array<double, 3> tangent{}, binormal{};  // in-plane axes (2D: binormal is z)
  std::vector<std::array<double, 3>> polygon;    // 2D: the segment's end points; 3D: the polygon
  double length = 0.0;                           // 2D: the segment's length
  double tensile_strength = 0.0, cohesion = 0.0, friction_coefficient = 0.0;  // Pa, Pa, -
  int near_side = 0;  // the side (sign of (x - point) . normal) of the fluid sources; 0 without
  double in_situ_normal_compression = 0.0;  // -n . sigma n of the far-field in-situ stresses, Pa (0 without)
};

/// The bonds that cross a pre-existing fracture, row i listing those of particle i (the mirror
/// bond j-i sits in row j).
struct InterfaceBonds {
  std::vector<std::int64_t> offset;        // size n+1 (empty without interfaces)
  std::vector<std::int64_t> slot;          // the bond's index in Bonds
  std::vector<std::uint16_t> interface;    // the scene's interface
  std::vector<InterfaceLaw> laws;          // per scene interface
  std::vector<std::array<double, 3>> slip; // per entry: the slip of the failed bond's faces so far (interface_law.hpp)
  std::vector<std::uint8_t> across_crack;  // per entry: the failed bond joins the two faces of a crack the fluid fills (hf/crack_junction.hpp)
  std::vector<std::int32_t> particles;     // the particles with a bond across an interface, ascending
  std::vector<std::array<double, 9>> strain;  // per particle above: the rock's strain around it (bulk_strain.hpp), refreshed with the law

  bool empty() const { return slot.empty(); }
};

/// An injected fluid that flows along its cracks by the cubic law (hf/viscous_fluid.hpp): what each
/// node of its network holds, as the volume the fluid takes at zero pressure.
struct ViscousFluid {
  double viscosity = 0.0;  // Pa s; 0: the lumped fluid, one pressure
  bool started = false;
  double stored_time = 0.0, trial_time = 0.0;  // the last load step's end, and the one being solved, s
  double stored_inlet = 0.0, trial_inlet = 0.0;  // the fluid in the borehole's node (its wall particles), m^3
  std::vector<double> stored, trial;  // per particle: the fluid in its node (0 on the borehole's wall), m^3
};

/// The surface of the cracks a fluid fills, as patches (hf/crack_surface.hpp): each a point and a
/// normal, found through a grid of their points.
struct CrackSurface {
  bool made = false;                          // made once at least (before: a scene's initial state)
  std::vector<std::int64_t> patches;          // per patch, in the order they came: a broken bond's entry in its lower end's row, or -1 - a cut bond's
  std::vector<std::array<double, 6>> planes;  // per patch: its point and unit normal (z = 0 in 2D)
  std::vector<std::array<std::int32_t, 6>> moments;  // per patch: the sum of n n^T (xx yy zz xy yz xz) around it, in 2^-20 (hf/crack_surface.hpp)
  std::vector<std::int64_t> sorted_patches;   // the patches' bonds, ascending (which bonds have one)
  std::vector<std::uint64_t> decided;         // a bit per bond entry: a short network bond's entry (each end its own) whose patch, or none, is decided
  double cell = 0.0, reach = 0.0;             // the grid's cell size; how far a patch reaches along its plane, m
  std::vector<std::int64_t> cell_keys;        // the grid: cell keys, ascending
  std::vector<std::uint32_t> in_cell;         // the patch of each entry of cell_keys
  std::vector<std::int64_t> row_keys;         // the grid's rows along x that hold patches, ascending (hf/crack_surface.hpp)
  std::vector<std::size_t> row_first;         // per row, its first entry of cell_keys; then their count
  bool empty() const { return planes.empty(); }
};

/// What the network load reads of a particle with bonds in a fluid's network (an end of the
/// network), under a unit uniform expansion (hf/network_load.hpp).
struct NetworkEnd {
  double theta = 0.0, d_theta = 0.0;  // its dilatation with the network's bonds held intact, and their share of it
  double a = 0.0;                     // A_dev / m
  double held = 0.0, change = 0.0;    // its p with the network held intact, and the network's share (times d / m without the surface correction)
};

/// What the network load's runs read of each particle for one source (hf/network_load_runs.hpp): its
/// terms as an end, from its NetworkEnd (its held term NaN where the source's fluid did not reach
/// it), and per block of network_load_block particles whether one of them has a nonzero term. A
/// cache kept with the ends (made again where they are), not state: empty, it is made from the ends.
struct NetworkRunTerms {
  std::vector<double> change, held;  // held: NaN where the source's fluid is not (hf/network_load_runs.hpp)
  std::vector<std::uint8_t> block_has_end;
};
inline constexpr std::size_t network_load_block = 64;

/// The fluid each pressure source has in the cracks grown from it (hf/fluid_network.hpp); empty
/// without pressure sources.
struct FluidNetwork {
  std::vector<int> source;                    // per particle: the source whose fluid reaches it, -1 none
  bool relabel = true;                        // the labels are to be made from scratch (the first time, a wall broke down)
  bool pressure_bonds = false;                // the whole model has pressure bonds (pressure_bonds.hpp; a rank's window may hold none)
  std::vector<std::uint64_t> bond_counts;     // per particle at the last update: its intact and broken bonds counted (hf/fluid_network.hpp)
  // the bond states' version (BondStates::version) bond_counts were counted at, and the failed
  // interface bonds of the owned rows then: a cache, not state (0: not counted)
  std::uint64_t counted_states = 0;
  std::int64_t counted_interface_failed = 0;
  std::vector<std::uint8_t> outer_surface;    // per particle: on the body's outer free surface (pressure_bonds.hpp)
  std::vector<std::uint8_t> in_crack;         // per particle: the fluid reaches it across a crack (a broken or cut bond), not only at a borehole's wall
  std::vector<std::uint8_t> immersed;         // per particle: wet, in a fragment its intact bonds no longer join to the body (hf/fluid_network.hpp): no fluid load
  std::vector<double> pore_stretch;           // per particle: p / (d kappa) where the fluid is in the cracked rock, 0 elsewhere; empty: nowhere (hf/wet_rock.hpp)
  std::vector<std::vector<std::int64_t>> open_interface_bonds;  // per source: the failed interface bonds its fluid fills (both entries), ascending
  CrackSurface crack_surface;                 // the cracks' surface the fluid fills (hf/crack_surface.hpp)
  std::vector<std::int64_t> crossing_broken;  // broken bonds (both entries) that crossed the crack or its extension when they broke, ascending
  // the latest of those, ascending, kept apart until they are a 32nd of crossing_broken's length
  // (hf/crack_surface.hpp record_crossing_breaks): merged into it each step, they moved the whole list
  // each step (20 million entries in the thesis-size example's breaking regime, on one thread)
  std::vector<std::int64_t> crossing_recent;
  /// Whether broken bond entry k crossed the crack or its extension when it broke.
  bool crossed_when_broken(std::int64_t k) const {
    return std::binary_search(crossing_broken.begin(), crossing_broken.end(), k) ||
           std::binary_search(crossing_recent.begin(), crossing_recent.end(), k);
  }
  /// Merges the recent ones into crossing_broken, which then holds them all.
  void settle_crossing_broken() {
    if (crossing_recent.empty()) return;
    const auto before = static_cast<std::ptrdiff_t>(crossing_broken.size());
    crossing_broken.insert(crossing_broken.end(), crossing_recent.begin(), crossing_recent.end());
    std::inplace_merge(crossing_broken.begin(), crossing_broken.begin() + before, crossing_broken.end());
    crossing_broken.erase(std::unique(crossing_broken.begin(), crossing_broken.end()), crossing_broken.end());
    crossing_recent.clear();
  }
  /// Every one of them, ascending (crossing_broken settled, in a copy).
  std::vector<std::int64_t> crossing_broken_whole() const {
    std::vector<std::int64_t> all(crossing_broken.size() + crossing_recent.size());
    std::merge(crossing_broken.begin(), crossing_broken.end(), crossing_recent.begin(), crossing_recent.end(), all.begin());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  }
  // the particles whose bonds changed state, or whose bonds joined or left a network, since the
  // network load was last made (hf/network_load.hpp); all of them while load_from_scratch
  std::vector<std::size_t> load_changed;
  std::vector<std::uint8_t> load_changed_mark;  // per particle: in load_changed
  /// load_changed made again from load_changed_mark, ascending (after the marks were copied)
  void list_load_changed_from_marks() {
    load_changed.clear();
    for (std::size_t i = 0; i < load_changed_mark.size(); ++i)
      if (load_changed_mark[i]) load_changed.push_back(i);
  }
  bool load_from_scratch = true;
  std::vector<std::vector<double>> network_load;         // per source: the force density on each particle per unit pressure (n x d, 1/m); empty: none (hf/network_load.hpp)
  std::vector<std::vector<std::uint8_t>> is_end;         // per source, per particle: it has a bond in the network
  std::vector<std::vector<NetworkEnd>> network_ends;     // per source, per particle: an end's NetworkEnd as network_load was last made (zero: not an end)
  std::vector<NetworkRunTerms> network_run_terms;       // per source: the runs' terms of its ends (a cache, hf/network_load.hpp)
  // per pressure source (the scene's cracks, then its boreholes)
  std::vector<std::uint8_t> dry;         // a crack without pressure of its own: its cut bonds carry a fluid that reaches them
  std::vector<std::uint8_t> sealed;      // a borehole whose wall has not broken down yet: the dry pre-cracks stay shut to its fluid
  std::vector<std::uint8_t> has_network; // its fluid fills broken bonds (its network load is made)
  std::vector<double> reference_volume;  // the cavity's volume in the reference state (a borehole's lattice sites)
  std::vector<double> pressure;          // the last pressure applied, Pa
  std::vector<double> pore_pressure;     // the pressure of the last equilibrium (or time step), which the wet rock feels, Pa (hf/wet_rock.hpp)
  std::vector<double> cavity_volume;     // the last cavity volume (injected sources), m^3
  std::vector<std::uint8_t> vented;      // the fluid reaches the outer surface: it escapes (breakthrough)
  std::vector<std::uint8_t> broke_through;  // vented at any time so far (a laboratory test ends there)
  std::vector<double> escaped_volume;    // injected fluid that escaped while vented (at zero pressure), m^3
  std::vector<ViscousFluid> viscous;     // per source (empty: every fluid lumped)
  // per particle, where a viscous fluid reaches or its network loads the rock (empty: no viscous fluid)
  std::vector<double> local_pressure;       // that fluid's pressure there, Pa
  std::vector<double> local_pore_pressure;  // local_pressure of the last equilibrium (hf/wet_rock.hpp), Pa

  /// Takes the sources' state that changes during a run from `g` (a distributed run's window and the
  /// whole model its checkpoint gathers: the same on every rank).
  void take_sources_state(const FluidNetwork& g) {
    sealed = g.sealed, has_network = g.has_network, pressure = g.pressure, pore_pressure = g.pore_pressure;
    cavity_volume = g.cavity_volume, vented = g.vented, broke_through = g.broke_through, escaped_volume = g.escaped_volume;
  }
  /// Whether source s's fluid flows along its cracks by the cubic law (hf/viscous_fluid.hpp).
  bool flows(std::size_t s) const { return s < viscous.size() && viscous[s].viscosity > 0.0; }
  /// Whether source s's fluid enters the dry pre-cracks it meets (its wall broke down, or has no breakdown pressure).
  bool enters_dry_cracks(int s) const { return s >= 0 && (static_cast<std::size_t>(s) >= sealed.size() || !sealed[static_cast<std::size_t>(s)]); }
};

}  // namespace rift::pd
