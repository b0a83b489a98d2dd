// Pre-cracks: a bond whose segment crosses a crack (2D segment, 3D planar polygon) is not created.
#pragma once
#include <vector>

#include "rift/core/vec.hpp"

namespace rift::geometry {

class PreCrack {
 public:
  PreCrack(int dimension, std::vector<Point3> points);
  /// True when the segment p -> q crosses the crack.
  bool cuts(const Point3& p, const Point3& q) const;
  void bounds(Point3& lo, Point3& hi) const;
  /// 3D: the polygon's normal by Newell's method (not normalized; its length is twice the area).
  const Point3& normal() const { return normal_; }

 private:
  int dimension_;
  std::vector<Point3> points_;
  Point3 normal_{};
  int drop_axis_ = 2;  // 3D: axis dropped to test the crossing point inside the polygon
};

}  // namespace rift::geometry
