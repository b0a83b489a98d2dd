// The pore stretch s_p = p / (d kappa) of the wet rock (hf/wet_rock.hpp: a bond across a crack
// that holds fluid breaks at s0 - (1 + alpha) min(s_p,i, s_p,j)). It follows the fluid network at once;
// its pressure is the fluid's where fluid and rock are in equilibrium: after each explicit time step,
// at the end of each dynamic-relaxation load step and of a converged static solve (the steppers'
// at_equilibrium stage, pd/loads.hpp), not in the relaxation's iterations.
#pragma once
#include <cstddef>

#include "rift/hf/pd_names.hpp"

namespace rift::hf {

/// The pressure of the fluid at particle i, its source's (0 where none reaches): the output field
/// fluid_pressure.
template <int D>
double fluid_pressure_at(const Model<D>& m, std::size_t i) {
  const FluidNetwork& f = m.fluid_network;
  if (f.source.empty() || f.source[i] < 0) return 0.0;
  return f.pressure[static_cast<std::size_t>(f.source[i])];
}

/// The pore stretch s_p = p / (d kappa) of every particle the fluid reaches across a crack, p the
/// pore pressure of its source; none (empty) where no wet particle has pressure. Call when the fluid
/// network's labels or the pore pressures change.
template <int D>
void update_pore_stretch(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  const std::size_t n = m.size();
  // a viscous fluid's pressure at the particle (hf/viscous_fluid.hpp), a lumped one's everywhere
  const bool local = f.local_pore_pressure.size() == n;
  auto pore_pressure = [&](std::size_t i) {
    const int s = f.source[i];
    if (!f.in_crack[i] || s < 0 || static_cast<std::size_t>(s) >= f.pore_pressure.size()) return 0.0;
    const auto source = static_cast<std::size_t>(s);
    if (local && f.flows(source)) return f.local_pore_pressure[i];
    return f.pore_pressure[source];
  };
  bool any = false;
  if (f.in_crack.size() == n && f.source.size() == n)
    for (std::size_t i = 0; i < n && !any; ++i) any = pore_pressure(i) != 0.0;
  if (!any) {
    f.pore_stretch.clear();
    return;
  }
  f.pore_stretch.resize(n);
  for (std::size_t i = 0; i < n; ++i) f.pore_stretch[i] = pore_pressure(i) / (D * m.constants_of(i).kappa);
}

/// The fluid is in equilibrium with the rock (the end of a time step or of a load step): its
/// pressures become the pore pressures.
template <int D>
void equilibrate_pore_pressure(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  if (f.pore_pressure == f.pressure && f.local_pore_pressure == f.local_pressure) return;
  f.pore_pressure = f.pressure;
  f.local_pore_pressure = f.local_pressure;
  update_pore_stretch<D>(m);
}

}  // namespace rift::hf
