// A scene's loads on a peridynamic model, as the steppers ask for them (pd/loads.hpp): its boundary
// conditions (load/boundary.hpp), then the pressure of its fluids (hf/fluid_pressure.hpp).
#pragma once
#include <string>
#include <vector>

#include "rift/hf/fluid_pressure.hpp"
#include "rift/load/boundary.hpp"
#include "rift/pd/loads.hpp"

namespace rift::run {

template <int D>
class SceneLoads final : public pd::Loads<D> {
 public:
  SceneLoads(const scene::Scene& s, pd::Model<D>& m) : boundaries(s, m), fluid(s, m) {}
  /// The boundary conditions' force density, then the fluids' load.
  void apply_body_forces(pd::Model<D>& m, double t) const override {
    boundaries.apply_body_forces(m, t);
    fluid.add_pressure_forces(m, t);
  }
  void prescribe_velocity(pd::Model<D>& m, double t, double dt) const override { boundaries.prescribe_velocity(m, t, dt); }
  void prescribe_position(pd::Model<D>& m, double t) const override { boundaries.prescribe_position(m, t); }
  bool state_dependent() const override { return fluid.state_dependent(); }
  void at_equilibrium(pd::Model<D>& m) const override { fluid.at_equilibrium(m); }
  std::size_t broken_through(const pd::Model<D>& m) const override { return fluid.broken_through(m); }

  load::Boundaries<D> boundaries;
  hf::FluidPressure<D> fluid;
};

}  // namespace rift::run
