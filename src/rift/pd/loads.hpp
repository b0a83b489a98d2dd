// What the steppers (velocity_verlet.hpp, dynamic_relaxation.hpp, static_equilibrium.hpp) ask of the
// loads on a model, at the named stages of their step. The boundary conditions (load/boundary.hpp)
// answer it alone; a scene's loads (run/scene_loads.hpp) add the fluid's pressure (hf/).
#pragma once
#include <cstddef>

#include "rift/pd/model.hpp"

namespace rift::pd {

template <int D>
class Loads {
 public:
  virtual ~Loads() = default;
  /// After the forces: the external force density at time t, m.body_force (cleared first).
  virtual void apply_body_forces(Model<D>& m, double t) const = 0;
  /// Before the drift and after the closing kick (dt = 0): the velocity of constrained components
  /// over the step (t, t + dt).
  virtual void prescribe_velocity(Model<D>& m, double t, double dt) const = 0;
  /// After the drift: the exact positions of displacement-controlled components at time t.
  virtual void prescribe_position(Model<D>& m, double t) const = 0;
  /// Whether the external force follows the deformation (an injected fluid's pressure its cavity's
  /// volume): a relaxation applies it again at each iteration.
  virtual bool state_dependent() const = 0;
  /// The fluid and the rock have come to equilibrium: the end of a time step, of a relaxation, or of
  /// a converged static solve (hf/pore_stretch.hpp: the wet rock takes the fluid's pressure).
  virtual void at_equilibrium(Model<D>& m) const = 0;
  /// How many of the loads' fluid sources have broken through to the outer surface so far: a
  /// laboratory test ends there, so a load step's breaking passes stop where the count grows.
  virtual std::size_t broken_through(const Model<D>& m) const = 0;

 protected:
  Loads() = default;
  Loads(const Loads&) = default;
  Loads& operator=(const Loads&) = default;
};

}  // namespace rift::pd
