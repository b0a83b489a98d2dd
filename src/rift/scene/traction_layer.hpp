// A traction T on a boundary region becomes the body-force density T / depth on the particles the
// region selects, so the region must be `depth` deep. A layer thinner than one row of particles
// cannot be: the row it selects is a whole spacing deep and would carry T * spacing / depth.
#pragma once
#include <fmt/format.h>

#include <string>

namespace rift::scene {

inline std::string thinner_than_a_row(double depth, double spacing) {
  return fmt::format("a traction layer {:g} m deep is thinner than one row of particles ({:g} m apart), whose row would carry "
                     "{:.3g} times the traction; set layer_depth to a whole number of rows and select a region that deep",
                     depth, spacing, spacing / depth);
}

}  // namespace rift::scene
