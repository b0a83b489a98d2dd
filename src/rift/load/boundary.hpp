// Boundary conditions on regions: fixed, prescribed velocity or displacement per component,
// traction (converted to a body-force density over the loaded particle layer: b = T / depth),
// body force; each scaled by its time function; the in-situ stress as tractions on the faces. Also
// the reaction force on tagged regions. A fluid's pressure is hydraulic fracture's (hf/fluid_pressure.hpp).
#pragma once
#include <string>
#include <vector>

#include "rift/parallel/communicator.hpp"
#include "rift/pd/loads.hpp"
#include "rift/pd/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::load {

template <int D>
class Boundaries final : public pd::Loads<D> {
 public:
  /// Select the particles of every boundary and reaction region (throws SceneError when a
  /// region selects no particle) and mark constrained components on the model.
  Boundaries(const scene::Scene& s, pd::Model<D>& m);
  /// External force density at time t: the tractions' and body forces'.
  void apply_body_forces(pd::Model<D>& m, double t) const override;
  /// Velocity of constrained components over the step (t, t + dt): set before the drift.
  void prescribe_velocity(pd::Model<D>& m, double t, double dt) const override;
  /// Exact positions of displacement-controlled components at time t.
  void prescribe_position(pd::Model<D>& m, double t) const override;
  /// No boundary condition follows the deformation.
  bool state_dependent() const override { return false; }
  void at_equilibrium(pd::Model<D>&) const override {}
  std::size_t broken_through(const pd::Model<D>&) const override { return 0; }
  /// Reaction force of each tagged region: minus the internal force its particles carry, over the
  /// owned particles of every rank of `comm` (a distributed run's), summed exactly.
  std::vector<Vec<D>> reactions(const pd::Model<D>& m, const parallel::Communicator& comm = parallel::Communicator::one()) const;
  const std::vector<std::string>& reaction_names() const { return reaction_names_; }
  /// A distributed run (pd/window.hpp): the loads of the window's particles, numbered as the
  /// window numbers them; the reactions of the owned ones (`owned`, ranges of the whole numbering)
  /// alone (the ranks' reactions add up to the whole run's).
  void restrict_to(const pd::Numbering& window, const std::vector<IndexRange>& owned);
  bool has_kinematic() const { return any_kinematic_; }

 private:
  struct Applied {
    scene::Boundary def;
    std::vector<std::size_t> particles;
  };
  /// Tractions sigma . n of the far-field stresses on the faces of the bodies' bounding box, or
  /// the platens that carry them (pd/platens.hpp).
  void add_in_situ_tractions(const scene::InSituStress& in_situ, pd::Model<D>& m);
  std::vector<Applied> applied_;
  std::vector<std::string> reaction_names_;
  std::vector<std::vector<std::size_t>> reaction_particles_;
  bool any_kinematic_ = false;
};

}  // namespace rift::load
