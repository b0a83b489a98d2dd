// The state of the fluids that hydraulic fracture (hf/) works on, held by the model (model.hpp) and
// written by its checkpoint (checkpoint_state.hpp): the pressure bonds each source loads, and per
// source the network of cracks its fluid fills, its ends, the surface of its cracks and, for a
// viscous fluid, its flow network's nodes. pd itself sets only what the lattice decides (discretize.cpp:
// the pressure bonds, a source's dry, sealed and reference volume) and carries the crossing marks of
// ghosts (ghost_fields.hpp).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rift::pd {

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
