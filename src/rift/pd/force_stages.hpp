// What a stage outside the peridynamic core adds to a force evaluation (compute_forces, forces.hpp):
// geomechanics' pre-existing fractures (geomech/interface_stages.hpp), whose law fails bonds before the
// bond passes and whose failed bonds press and slide as frictional contacts after them. The model holds
// a pointer to it (Model::stages); a model with interfaces and none is a programming error
// (std::logic_error), not a run without its interfaces.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "rift/core/vec.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

template <int D>
class ForceStages {
 public:
  virtual ~ForceStages() = default;
  /// Before the bond passes, from the last evaluation's positions: bonds whose law is exceeded
  /// leave the passes (state bond_interface_failed).
  virtual void before_bond_passes(Model<D>& m) const = 0;
  /// After the bond passes: the forces of the bonds the stage holds, added to m.force; `advancing`:
  /// a step of explicit dynamics (its history moves on), not an iteration of a relaxation.
  virtual void after_bond_passes(Model<D>& m, bool advancing) const = 0;
  /// Whether the stage holds bond k = i-j; if so its force density on i as the last evaluation left
  /// it into `f` (the bond-pair stress, stress.hpp).
  virtual bool held_bond_force(const Model<D>& m, std::size_t i, std::size_t j, std::int64_t k, Vec<D>& f) const = 0;

 protected:
  ForceStages() = default;
  ForceStages(const ForceStages&) = default;
  ForceStages& operator=(const ForceStages&) = default;
};

/// The model's stages; a model whose scene has interfaces (interface_bonds.hpp InterfaceBonds::laws) must have
/// them (std::logic_error: geomech::install_interface_stages was not called).
template <int D>
const ForceStages<D>* force_stages_of(const Model<D>& m) {
  if (!m.stages && !m.interface_bonds.laws.empty())
    throw std::logic_error("a model with interfaces needs their force stages (geomech::install_interface_stages)");
  return m.stages;
}

}  // namespace rift::pd
