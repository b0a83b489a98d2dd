#include "rift/mpm/crack.hpp"

#include <algorithm>
#include <cmath>

namespace rift::mpm {

namespace {
double cross(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }
}  // namespace

CrackSet::CrackSet(const scene::Scene& s, double cell_size) {
  for (const auto& c : s.cracks) {
    Crack crack;
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
      const Vec<2> a{c.points[k][0], c.points[k][1]}, b{c.points[k + 1][0], c.points[k + 1][1]};
      const int pieces = std::max(1, static_cast<int>(std::ceil(norm<2>(b - a) / (0.5 * cell_size))));
      for (int q = (k == 0 ? 0 : 1); q <= pieces; ++q) crack.points.push_back(a + (double(q) / pieces) * (b - a));
    }
    crack.above = crack.below = crack.points;
    cracks_.push_back(std::move(crack));
  }
  update_bounds();
}

void CrackSet::update_bounds() {
  for (auto& c : cracks_) {
    c.lo = c.hi = c.points.front();
    for (const auto* set : {&c.points, &c.above, &c.below})
      for (const auto& p : *set)
        for (int a = 0; a < 2; ++a) c.lo[a] = std::min(c.lo[a], p[a]), c.hi[a] = std::max(c.hi[a], p[a]);
  }
}

void CrackSet::extend(const CrackTip& tip, const Vec<2>& x) {
  auto& c = cracks_[tip.crack];
  for (auto* set : {&c.points, &c.above, &c.below}) {
    if (tip.end == TipEnd::end) set->push_back(x);
    else set->insert(set->begin(), x);
  }
  update_bounds();
}

bool CrackSet::near(const Vec<2>& x, double reach) const {
  for (const auto& c : cracks_)
    if (x[0] >= c.lo[0] - reach && x[0] <= c.hi[0] + reach && x[1] >= c.lo[1] - reach && x[1] <= c.hi[1] + reach) return true;
  return false;
}

int CrackSet::field(const Vec<2>& xp, const Vec<2>& xn) const {
  const Vec<2> d = xn - xp;
  for (const auto& c : cracks_) {
    // quick rejection: the segment's box must meet the crack's box
    if (std::max(xp[0], xn[0]) < c.lo[0] || std::min(xp[0], xn[0]) > c.hi[0] || std::max(xp[1], xn[1]) < c.lo[1] ||
        std::min(xp[1], xn[1]) > c.hi[1])
      continue;
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
      const Vec<2>& a = c.points[k];
      const Vec<2>& b = c.points[k + 1];
      if (std::max(xp[0], xn[0]) < std::min(a[0], b[0]) || std::min(xp[0], xn[0]) > std::max(a[0], b[0]) ||
          std::max(xp[1], xn[1]) < std::min(a[1], b[1]) || std::min(xp[1], xn[1]) > std::max(a[1], b[1]))
        continue;
      const Vec<2> e = b - a;
      // a node exactly on the crack line counts as above it, so every pair is classified the same
      // way from both sides
      const double side_p = cross(e, xp - a), side_n = cross(e, xn - a);
      if (side_p == 0.0 || (side_p > 0) == (side_n >= 0)) continue;
      const double ta = cross(d, a - xp), tb = cross(d, c.points[k + 1] - xp);
      if ((ta > 0) == (tb > 0) && ta != 0.0 && tb != 0.0) continue;
      return side_p > 0 ? 1 : 2;  // crosses: above (left of the crack direction) or below
    }
  }
  return 0;
}

Vec<2> CrackSet::normal(std::size_t c, std::size_t k) const {
  const auto& pts = cracks_[c].points;
  const std::size_t a = k == 0 ? 0 : k - 1, b = std::min(pts.size() - 1, k + 1);
  const Vec<2> t = pts[b] - pts[a];
  const double l = norm<2>(t);
  return {-t[1] / l, t[0] / l};
}

std::array<double, 2> CrackSet::opening(std::size_t c, std::size_t k) const {
  const Vec<2> n = normal(c, k), t{n[1], -n[0]};
  const Vec<2> gap = cracks_[c].above[k] - cracks_[c].below[k];
  return {dot<2>(gap, n), dot<2>(gap, t)};
}

Vec<2> CrackSet::side_point(std::size_t c, std::size_t k, const Vec<2>& x, int side, double offset, std::size_t window) const {
  const auto& pts = cracks_[c].points;
  const std::size_t first = k > window ? k - window : 0, last = std::min(pts.size() - 1, k + window);
  Vec<2> best = pts[k], best_normal = normal(c, k);
  double best_distance = norm<2>(x - best);
  for (std::size_t j = first; j < last; ++j) {
    const Vec<2> e = pts[j + 1] - pts[j];
    const double length2 = dot<2>(e, e);
    if (length2 == 0.0) continue;
    const double t = std::clamp(dot<2>(x - pts[j], e) / length2, 0.0, 1.0);
    const Vec<2> q = pts[j] + t * e;
    const double d = norm<2>(x - q);
    if (d < best_distance) {
      const double l = std::sqrt(length2);
      best_distance = d, best = q, best_normal = {-e[1] / l, e[0] / l};
    }
  }
  return best + ((side == 1 ? 1.0 : -1.0) * offset) * best_normal;
}

CrackSet::Nearest CrackSet::nearest(const Vec<2>& x) const {
  Nearest best;
  for (std::size_t c = 0; c < cracks_.size(); ++c)
    for (std::size_t k = 0; k < cracks_[c].points.size(); ++k) {
      const double d = norm<2>(cracks_[c].points[k] - x);
      if (d < best.distance) best = {c, k, d};
    }
  return best;
}

}  // namespace rift::mpm
