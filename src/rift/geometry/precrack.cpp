#include "rift/geometry/precrack.hpp"

#include <algorithm>
#include <cmath>

namespace rift::geometry {

namespace {
double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
}

PreCrack::PreCrack(int dimension, std::vector<Point3> points) : dimension_(dimension), points_(std::move(points)) {
  if (dimension_ == 3) {
    // Newell's method for the polygon normal.
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const auto& a = points_[i];
      const auto& b = points_[(i + 1) % points_.size()];
      normal_[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal_[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal_[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    drop_axis_ = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(normal_[k]) > std::abs(normal_[drop_axis_])) drop_axis_ = k;
  }
}

bool PreCrack::cuts(const Point3& p, const Point3& q) const {
  if (dimension_ == 2) {
    const auto& a = points_[0];
    const auto& b = points_[1];
    // p and q on opposite sides of the crack line and the crack ends strictly on opposite sides of
    // the line pq. A bond passing exactly through a crack tip is not cut, whatever its orientation,
    // so mirror-symmetric scenes stay symmetric. A point on the line counts with the points to its
    // left (looking from the first point to the second): a row of lattice sites on the line is on
    // one side, so the bonds from it to the other side are cut. (Strictly opposite sides left
    // every bond of such a row whole: Zhou's 90-degree interfaces at 3 mm spacing, hf_zhou_crossing,
    // ran through a column of sites whose rock bonds bridged them.)
    const double d1 = cross2(b[0] - a[0], b[1] - a[1], p[0] - a[0], p[1] - a[1]);
    const double d2 = cross2(b[0] - a[0], b[1] - a[1], q[0] - a[0], q[1] - a[1]);
    const double d3 = cross2(q[0] - p[0], q[1] - p[1], a[0] - p[0], a[1] - p[1]);
    const double d4 = cross2(q[0] - p[0], q[1] - p[1], b[0] - p[0], b[1] - p[1]);
    return (d1 >= 0) != (d2 >= 0) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
  }
  const auto& o = points_[0];
  double sp = 0, sq = 0;
  for (int k = 0; k < 3; ++k) sp += (p[k] - o[k]) * normal_[k], sq += (q[k] - o[k]) * normal_[k];
  if ((sp >= 0) == (sq >= 0)) return false;  // a point on the plane counts with the side its normal points to
  double t = sp / (sp - sq);
  Point3 c{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
  int u = (drop_axis_ + 1) % 3, v = (drop_axis_ + 2) % 3;
  bool inside = false;
  for (std::size_t i = 0, j = points_.size() - 1; i < points_.size(); j = i++) {
    const auto& a = points_[i];
    const auto& b = points_[j];
    if ((a[v] > c[v]) != (b[v] > c[v]) && c[u] < (b[u] - a[u]) * (c[v] - a[v]) / (b[v] - a[v]) + a[u]) inside = !inside;
  }
  return inside;
}

void PreCrack::bounds(Point3& lo, Point3& hi) const {
  lo = hi = points_[0];
  for (const auto& p : points_)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
}

}  // namespace rift::geometry
