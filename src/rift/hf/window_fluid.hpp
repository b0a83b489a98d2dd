// A distributed run's window of the fluid (pd/window.hpp window_of makes the rest of the window): the
// sources' state as it is, a viscous fluid's nodes and pressures, the particles' labels, marks and
// network load of a continued run cut to the window (a run that starts has none yet; they follow from
// the bonds' states and the sources', fluid_network.hpp), the outer surface cut to the window, the
// crossing marks and open interface bonds of the window's rows, and the crack surface made again;
// and how far past its owned range a window reaches where the fluid reads far.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/hf/crack_surface.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/pd/window.hpp"

namespace rift::hf {

/// How many bonds' reaches a window holds past its owned range where a fluid fills cracks that grow
/// (fluid_network.hpp) or flows (fluid_reads_far): the network load of an owned particle reads the
/// network ends among its neighbours, each end its whole row (two reaches of whole rows); the crack
/// surface an owned bond may cross has its patches and their normals from the short bonds around the
/// bond's ends, a spacing or two further.
inline constexpr std::size_t fluid_ghost_reaches = 3;

/// Whether the scene's fluid fills cracks that can grow (pressure bonds in rock whose bonds break),
/// or flows along them (viscous_fluid.hpp: a flow bond's conductance reads the bulk strain and the
/// family moments of its ends, an owned particle's neighbour among them, each over its whole row),
/// or the scene has interfaces (geomech/interface_law.hpp: the law of a bond with an owned end reads the
/// fluid in the interface at its other end, over that end's whole row).
template <int D>
bool fluid_reads_far(const Model<D>& m) {
  if (!m.interface_bonds.laws.empty()) return true;
  if (m.crack_bonds.neighbor.empty()) return false;
  for (std::size_t s = 0; s < m.fluid_network.dry.size(); ++s)
    if (m.fluid_network.flows(s)) return true;
  for (const pd::BodyInfo& body : m.bodies)
    if (body.constants.critical_stretch > 0.0) return true;
  return false;
}

/// The fluid of window w (`window`: its particles' numbers in the whole model m), from m's.
template <int D>
void window_fluid(const Model<D>& m, const pd::Numbering& window, Model<D>& w) {
  FluidNetwork& f = w.fluid_network;
  const FluidNetwork& g = m.fluid_network;
  f.pressure_bonds = g.pressure_bonds, f.dry = g.dry, f.reference_volume = g.reference_volume;
  f.take_sources_state(g);
  // a viscous fluid's: the fluid in the window's nodes and the pressure at its particles
  f.viscous = g.viscous;
  for (ViscousFluid& v : f.viscous) v.stored = pd::slice(v.stored, window), v.trial = pd::slice(v.trial, window);
  f.local_pressure = pd::slice(g.local_pressure, window), f.local_pore_pressure = pd::slice(g.local_pore_pressure, window);
  f.outer_surface = pd::slice(g.outer_surface, window);
  // a continued run's labels, marks and network load (run/distributed.hpp gather_fluid; a run that
  // starts has none yet)
  f.relabel = g.relabel, f.load_from_scratch = g.load_from_scratch;
  f.source = pd::slice(g.source, window), f.bond_counts = pd::slice(g.bond_counts, window);
  f.in_crack = pd::slice(g.in_crack, window), f.immersed = pd::slice(g.immersed, window);
  f.pore_stretch = pd::slice(g.pore_stretch, window), f.load_changed_mark = pd::slice(g.load_changed_mark, window);
  f.list_load_changed_from_marks();
  f.network_load.resize(g.network_load.size()), f.is_end.resize(g.is_end.size()), f.network_ends.resize(g.network_ends.size());
  for (std::size_t s = 0; s < g.network_load.size(); ++s) f.network_load[s] = pd::slice(g.network_load[s], window, D);
  for (std::size_t s = 0; s < g.is_end.size(); ++s) f.is_end[s] = pd::slice(g.is_end[s], window);
  for (std::size_t s = 0; s < g.network_ends.size(); ++s) f.network_ends[s] = pd::slice(g.network_ends[s], window);
  // the crossing marks and the open interface bonds of the window's rows, each bond found by its
  // neighbour (a ghost's row is cut)
  const Bonds& b = m.bonds;
  const Bonds& c = w.bonds;
  auto window_bonds = [&](const std::vector<std::int64_t>& list) {
    std::vector<std::int64_t> out;
    for (const std::int64_t k : list) {
      const std::size_t i = window.here(b.row_of(k)), j = window.here(static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]));
      if (i == Numbering::none || j == Numbering::none) continue;
      const auto first = c.neighbor.begin() + c.offset[i], last = c.neighbor.begin() + c.offset[i + 1];
      out.push_back(std::lower_bound(first, last, static_cast<std::int32_t>(j)) - c.neighbor.begin());
    }
    return out;  // ascending: rows and their neighbours keep their order in the window
  };
  f.crossing_broken = window_bonds(g.crossing_broken_whole()), f.crossing_recent.clear();
  f.open_interface_bonds.assign(g.dry.size(), {});
  for (std::size_t s = 0; s < g.open_interface_bonds.size() && s < g.dry.size(); ++s) f.open_interface_bonds[s] = window_bonds(g.open_interface_bonds[s]);
  f.crack_surface.made = g.crack_surface.made;
  if (f.crack_surface.made) remake_crack_surface<D>(w);
}

}  // namespace rift::hf
