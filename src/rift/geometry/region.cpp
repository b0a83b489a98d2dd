#include "rift/geometry/region.hpp"

#include <algorithm>
#include <limits>

namespace rift::geometry {

using scene::Shape;

Region Region::build(const scene::Scene& s, const std::string& name) {
  Region r;
  r.def_ = s.find_region(name);
  r.dimension_ = s.dimension;
  for (const auto& c : r.def_->of) r.children_.push_back(build(s, c));
  return r;
}

namespace {
// Even-odd rule point-in-polygon test.
bool in_polygon(const std::vector<std::array<double, 2>>& v, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const auto& a = v[i];
    const auto& b = v[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}
}  // namespace

bool Region::contains(const Point3& p) const {
  const auto& d = *def_;
  switch (d.shape) {
    case Shape::box:
      for (int k = 0; k < dimension_; ++k)
        if (p[k] < d.min[k] || p[k] > d.max[k]) return false;
      return true;
    case Shape::sphere: {
      double r2 = 0;
      for (int k = 0; k < dimension_; ++k) r2 += (p[k] - d.center[k]) * (p[k] - d.center[k]);
      return r2 <= d.radius * d.radius;
    }
    case Shape::cylinder: {
      if (dimension_ == 2) {
        double dx = p[0] - d.center[0], dy = p[1] - d.center[1];
        return dx * dx + dy * dy <= d.radius * d.radius;
      }
      Point3 rel{p[0] - d.center[0], p[1] - d.center[1], p[2] - d.center[2]};
      double len2 = dot<3>(d.axis, d.axis);
      double t = dot<3>(rel, d.axis) / len2;
      if (t < 0.0 || t > 1.0) return false;
      Point3 radial{rel[0] - t * d.axis[0], rel[1] - t * d.axis[1], rel[2] - t * d.axis[2]};
      return dot<3>(radial, radial) <= d.radius * d.radius;
    }
    case Shape::polygon:
      if (dimension_ == 3 && (p[2] < d.z_min || p[2] > d.z_max)) return false;
      return in_polygon(d.vertices, p[0], p[1]);
    case Shape::half_space: {
      double s = 0;
      for (int k = 0; k < dimension_; ++k) s += (p[k] - d.center[k]) * d.normal[k];
      return s <= 0.0;
    }
    case Shape::union_of:
      return std::any_of(children_.begin(), children_.end(), [&](const Region& c) { return c.contains(p); });
    case Shape::intersection_of:
      return std::all_of(children_.begin(), children_.end(), [&](const Region& c) { return c.contains(p); });
    case Shape::difference_of:
      if (!children_[0].contains(p)) return false;
      for (std::size_t i = 1; i < children_.size(); ++i)
        if (children_[i].contains(p)) return false;
      return true;
  }
  return false;
}

void Region::bounds(Point3& lo, Point3& hi) const {
  const double inf = std::numeric_limits<double>::infinity();
  const auto& d = *def_;
  lo = {-inf, -inf, -inf};
  hi = {inf, inf, inf};
  switch (d.shape) {
    case Shape::box:
      lo = d.min, hi = d.max;
      break;
    case Shape::sphere:
      for (int k = 0; k < 3; ++k) lo[k] = d.center[k] - d.radius, hi[k] = d.center[k] + d.radius;
      break;
    case Shape::cylinder:
      if (dimension_ == 2) {
        for (int k = 0; k < 2; ++k) lo[k] = d.center[k] - d.radius, hi[k] = d.center[k] + d.radius;
      } else {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(d.center[k], d.center[k] + d.axis[k]) - d.radius;
          hi[k] = std::max(d.center[k], d.center[k] + d.axis[k]) + d.radius;
        }
      }
      break;
    case Shape::polygon:
      lo[0] = lo[1] = inf, hi[0] = hi[1] = -inf;
      for (const auto& v : d.vertices)
        for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
      lo[2] = d.z_min, hi[2] = d.z_max;
      break;
    case Shape::half_space:
      break;
    case Shape::union_of: {
      lo = {inf, inf, inf}, hi = {-inf, -inf, -inf};
      for (const auto& c : children_) {
        Point3 l, h;
        c.bounds(l, h);
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], l[k]), hi[k] = std::max(hi[k], h[k]);
      }
      break;
    }
    case Shape::difference_of:
      children_[0].bounds(lo, hi);
      break;
    case Shape::intersection_of:
      for (const auto& c : children_) {
        Point3 l, h;
        c.bounds(l, h);
        for (int k = 0; k < 3; ++k) lo[k] = std::max(lo[k], l[k]), hi[k] = std::min(hi[k], h[k]);
      }
      break;
  }
  if (dimension_ == 2) lo[2] = hi[2] = 0.0;
}

}  // namespace rift::geometry
