// The fluid of each pressure source (the scene's pre-cracks, then its boreholes) and the load it
// puts on the rock at time t. Each evaluation brings the network its fluid fills up to date
// (fluid_network.hpp) with its load per unit pressure (network_load.hpp), finds each source's
// pressure (prescribed, a lumped compressible fluid: lumped_fluid.hpp, or one that flows along its
// cracks: viscous_fluid.hpp), lets a borehole's wall break down, and adds the pressure bonds' and the
// network's forces to the body force (crack_pressure.hpp, network_load.hpp).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "rift/hf/pore_stretch.hpp"
#include "rift/pd/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::hf {

template <int D>
class FluidPressure {
 public:
  /// The scene's pressure sources; a viscous injected fluid's nodes on the model (viscous_fluid.hpp);
  /// the wet rock as the model's bond coupling (wet_rock.hpp).
  FluidPressure(const scene::Scene& s, pd::Model<D>& m);
  /// Adds the fluids' load at time t to m.body_force (nothing without pressure bonds; on every rank
  /// of a distributed run alike, the fluid's sums being over every rank).
  void add_pressure_forces(pd::Model<D>& m, double t) const;
  /// The fluid is in equilibrium with the rock: the wet rock takes its pressures (pore_stretch.hpp).
  void at_equilibrium(pd::Model<D>& m) const { equilibrate_pore_pressure<D>(m); }
  /// How many fluid sources have vented at the outer surface so far (FluidNetwork::broke_through).
  std::size_t broken_through(const pd::Model<D>& m) const {
    const auto& b = m.fluid_network.broke_through;
    return static_cast<std::size_t>(std::count(b.begin(), b.end(), std::uint8_t{1}));
  }
  /// Whether a fluid's pressure follows the deformation (an injected fluid's, its cavity's volume).
  bool state_dependent() const {
    for (const auto& p : sources_)
      if (p.injected) return true;
    return false;
  }

 private:
  struct Source {
    double pressure = 0.0;  // prescribed (times `time`), or the pressure at t = 0 of an injection
    scene::TimeFunction time;
    bool injected = false;
    double injection_rate = 0.0, fluid_bulk_modulus = 0.0;
    double system_volume = 0.0;  // the injection system's fluid at the source's pressure, m^3
    std::optional<double> breakdown_pressure;  // the wall's, Pa (FluidNetwork::sealed)
  };
  std::vector<Source> sources_;  // cracks, then boreholes
};

}  // namespace rift::hf
