// Regions: solid shapes (box, cylinder, sphere, polygon prism, half-space) combined by union,
// difference and intersection. Used to fill bodies with particles and to select particles for
// boundary conditions. 2D scenes use z = 0.
#pragma once
#include <memory>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/scene/scene.hpp"

namespace rift::geometry {

class Region {
 public:
  /// Build the region named `name` (and its children) from the scene's definitions.
  static Region build(const scene::Scene& s, const std::string& name);
  bool contains(const Point3& p) const;
  /// Axis-aligned bounds (may be infinite for half-spaces).
  void bounds(Point3& lo, Point3& hi) const;

 private:
  const scene::RegionDef* def_ = nullptr;
  int dimension_ = 3;
  std::vector<Region> children_;
};

}  // namespace rift::geometry
