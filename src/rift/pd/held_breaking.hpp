// A scope in which no bond breaks: the bodies' breakable flags are cleared while it lives.
#pragma once
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::pd {

/// Holds every bond of the model (no bond or interface bond may break) while it lives.
template <int D>
class HeldBreaking {
 public:
  explicit HeldBreaking(Model<D>& m) : m_(m) {
    for (auto& b : m_.bodies) breakable_.push_back(b.constants.breakable), b.constants.breakable = false;
  }
  ~HeldBreaking() {
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) m_.bodies[b].constants.breakable = breakable_[b];
  }
  HeldBreaking(const HeldBreaking&) = delete;
  HeldBreaking& operator=(const HeldBreaking&) = delete;

 private:
  Model<D>& m_;
  std::vector<bool> breakable_;
};

}  // namespace rift::pd
