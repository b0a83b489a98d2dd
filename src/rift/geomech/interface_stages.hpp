// The pre-existing fractures' part of each force evaluation (pd/force_stages.hpp): before the bond
// passes the interface law fails the bonds it finds exceeded (interface_law.hpp), after them the failed
// bonds press and slide as frictional contacts (interface_contact.hpp). Installed on a model whose scene
// has interfaces (install_interface_stages) by the run's set-up, and by whoever else discretizes one.
#pragma once
#include <cstddef>
#include <cstdint>

#include "rift/geomech/interface_contact.hpp"
#include "rift/geomech/interface_law.hpp"
#include "rift/pd/force_stages.hpp"
#include "rift/pd/model.hpp"

namespace rift::geomech {

template <int D>
class InterfaceStages final : public pd::ForceStages<D> {
 public:
  void before_bond_passes(Model<D>& m) const override { apply_interface_law<D>(m); }
  void after_bond_passes(Model<D>& m, bool advancing) const override { add_interface_contact<D>(m, advancing); }
  bool held_bond_force(const Model<D>& m, std::size_t i, std::size_t j, std::int64_t k, Vec<D>& f) const override {
    const auto q = interface_entry<D>(m, i, k);
    if (q < 0) return false;
    f = interface_contact_force<D>(m, i, j, k, static_cast<std::size_t>(q), nullptr);
    return true;
  }
};

/// Gives the model its interfaces' stages where its scene has interfaces (their laws, pd/interface_bonds.hpp).
template <int D>
void install_interface_stages(Model<D>& m) {
  static const InterfaceStages<D> stages;
  if (!m.interface_bonds.laws.empty()) m.stages = &stages;
}

}  // namespace rift::geomech
