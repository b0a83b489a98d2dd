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

/// Indices i in [0, n) whose point position(i) (a D-vector) lies inside the region.
template <int D, class Position>
std::vector<std::size_t> indices_inside(const Region& region, std::size_t n, Position&& position) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = position(i);
    Point3 p{0, 0, 0};
    for (int a = 0; a < D; ++a) p[a] = x[a];
    if (region.contains(p)) out.push_back(i);
  }
  return out;
}

}  // namespace rift::geometry
