#include "rift/fracture/crack_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rift::fracture {

double crack_direction_degrees(const std::vector<DamagePoint>& field, double tip_x, double tip_y, double r_min,
                               double r_max, double threshold, int side_sign) {
  // damage-weighted principal axis of the offsets from the tip, oriented away from the tip
  double sxx = 0, sxy = 0, syy = 0, mx = 0, my = 0;
  int count = 0;
  for (const auto& p : field) {
    if (p.damage < threshold) continue;
    const double dx = p.x - tip_x, dy = p.y - tip_y;
    const double r = std::hypot(dx, dy);
    if (r < r_min || r > r_max || dy * side_sign <= 0) continue;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
    mx += dx, my += dy;
    ++count;
  }
  if (count < 3) return std::numeric_limits<double>::quiet_NaN();
  // the axis through the tip that best fits the points: largest eigenvector of the second moment
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  double ux = std::cos(angle), uy = std::sin(angle);
  if (ux * mx + uy * my < 0) ux = -ux, uy = -uy;
  return std::atan2(uy, ux) * 180.0 / 3.14159265358979323846;
}

double damage_front_x(const std::vector<DamagePoint>& field, double y_lo, double y_hi, double threshold) {
  double front = -std::numeric_limits<double>::infinity();
  for (const auto& p : field)
    if (p.damage >= threshold && p.y >= y_lo && p.y <= y_hi) front = std::max(front, p.x);
  return front;
}

int branches_crossing(const std::vector<DamagePoint>& field, double line_x, double spacing, double threshold, double gap) {
  std::vector<double> ys;
  for (const auto& p : field)
    if (std::abs(p.x - line_x) <= 0.5 * spacing && p.damage >= threshold) ys.push_back(p.y);
  std::sort(ys.begin(), ys.end());
  int branches = ys.empty() ? 0 : 1;
  for (std::size_t k = 1; k < ys.size(); ++k)
    if (ys[k] - ys[k - 1] > gap) ++branches;
  return branches;
}

}  // namespace rift::fracture
