#include "rift/hf/fluid_pressure.hpp"

#include "rift/core/phase_times.hpp"
#include "rift/hf/crack_pressure.hpp"
#include "rift/hf/lumped_fluid.hpp"
#include "rift/hf/network_load.hpp"
#include "rift/hf/viscous_fluid.hpp"
#include "rift/hf/wet_rock.hpp"
#include "rift/scene/time_function.hpp"

namespace rift::hf {

template <int D>
FluidPressure<D>::FluidPressure(const scene::Scene& s, pd::Model<D>& m) {
  for (const auto& c : s.cracks) sources_.push_back({c.pressure, c.pressure_time, false, 0.0, 0.0, 0.0, {}});
  for (const auto& b : s.boreholes)
    sources_.push_back({b.pressure, b.pressure_time, b.injection_rate.has_value(), b.injection_rate.value_or(0.0), b.fluid_bulk_modulus,
                        b.injection_system_volume, b.breakdown_pressure});
  m.fluid_network.viscous.assign(sources_.size(), {});
  m.coupling = wet_rock_coupling<D>();  // a crack that holds fluid wets the rock the bond passes break
  for (std::size_t h = 0; h < s.boreholes.size(); ++h)
    if (s.boreholes[h].injection_rate) m.fluid_network.viscous[s.cracks.size() + h].viscosity = s.boreholes[h].fluid_viscosity;
}

template <int D>
void FluidPressure<D>::add_pressure_forces(pd::Model<D>& m, double t) const {
  if (!m.fluid_network.pressure_bonds) return;
  // the fluid of each source also fills the cracks grown from it
  PhaseClock clock(Phase::fluid_pressure);
  {
    PhaseClock network_clock(Phase::fluid_network);
    update_fluid_network<D>(m);
  }
  {
    PhaseClock load_clock(Phase::network_load);
    update_network_load<D>(m);
  }
  auto& fluid = m.fluid_network;
  fluid.pressure.assign(sources_.size(), 0.0);
  fluid.cavity_volume.resize(sources_.size(), 0.0);
  fluid.escaped_volume.resize(sources_.size(), 0.0);
  for (std::size_t c = 0; c < sources_.size(); ++c) {
    const auto& src = sources_[c];
    if (!src.injected) {
      fluid.pressure[c] = src.pressure * scene::evaluate(src.time, t);
      continue;
    }
    if (fluid.flows(c)) {  // flow along the cracks by the cubic law
      fluid.pressure[c] = viscous_fluid_pressure<D>(m, c, t, src.injection_rate, src.fluid_bulk_modulus, src.pressure, src.system_volume);
      continue;
    }
    // mass balance of a lumped compressible fluid (lumped_fluid.hpp)
    const double injected = (fluid.reference_volume[c] + src.system_volume) * (1.0 + src.pressure / src.fluid_bulk_modulus) + src.injection_rate * t;
    const LumpedFluidState state =
        lumped_fluid_state(fluid.reference_volume[c], cavity_volume_change<D>(m, static_cast<int>(c)), src.system_volume, injected,
                               c < fluid.vented.size() && fluid.vented[c], fluid.escaped_volume[c], src.fluid_bulk_modulus);
    fluid.cavity_volume[c] = state.cavity_volume;
    fluid.escaped_volume[c] = state.escaped_volume;
    fluid.pressure[c] = state.pressure;
  }
  // a wall breaks down once its fluid's pressure first reaches the breakdown pressure: from the next
  // evaluation on, its fluid enters the dry pre-cracks that start in it (the network is made again)
  for (std::size_t c = 0; c < sources_.size() && c < fluid.sealed.size(); ++c)
    if (fluid.sealed[c] && sources_[c].breakdown_pressure && fluid.pressure[c] >= *sources_[c].breakdown_pressure) {
      fluid.sealed[c] = 0;
      fluid.relabel = true;
    }
  add_crack_pressure<D>(m, fluid.pressure);
  add_network_pressure<D>(m, fluid.pressure);
}

template class FluidPressure<2>;
template class FluidPressure<3>;

}  // namespace rift::hf
