#include "rift/mpm/j_integral.hpp"

#include <cmath>
#include <vector>

#include "rift/mpm/stencil.hpp"

namespace rift::mpm {

namespace {

/// Mass-weighted nodal values per field: stress (xx, yy, xy), displacement gradient
/// (du_x/dx, du_x/dy, du_y/dx, du_y/dy), strain and kinetic energy densities.
struct NodalField {
  double mass = 0.0;
  std::array<double, 9> value{};  // sxx syy sxy  uxx uxy uyx uyy  W  K
};

}  // namespace

namespace {

/// A tip, the crack particle behind it (its direction) and the index of that particle.
struct TipGeometry {
  Vec<2> tip, behind;
  std::size_t next_point;  // crack particle next to the tip
};

TipGeometry tip_geometry(const CrackSet& cracks, const CrackTip& t) {
  const auto& pts = cracks.cracks()[t.crack].points;
  if (t.end == TipEnd::end) return {pts.back(), pts[pts.size() - 2], pts.size() - 2};
  return {pts.front(), pts[1], 1};
}

/// In-plane E' = 4 mu (lambda' + mu) / (lambda' + 2 mu) of the 2D constants: E in plane stress
/// (lambda' = lambda*), E / (1 - nu^2) in plane strain.
double plane_modulus(const material::Constants& c) {
  return 4.0 * c.shear_modulus * (c.lambda + c.shear_modulus) / (c.lambda + 2.0 * c.shear_modulus);
}

}  // namespace

bool material_near(const Model<2>& m, const Vec<2>& x, double radius) {
  for (const auto& xp : m.particles.position)
    if (norm<2>(xp - x) < radius) return true;
  return false;
}

std::vector<CrackTip> interior_tips(const Model<2>& m, const CrackSet& cracks) {
  std::vector<CrackTip> tips;
  const double h = m.grid.cell_size;
  for (std::size_t c = 0; c < cracks.cracks().size(); ++c)
    for (TipEnd e : {TipEnd::start, TipEnd::end}) {
      const auto g = tip_geometry(cracks, {c, e});
      const Vec<2> dir = (1.0 / norm<2>(g.tip - g.behind)) * (g.tip - g.behind);
      if (material_near(m, g.tip + (0.5 * h) * dir, h)) tips.push_back({c, e});
    }
  return tips;
}

CrackTipParameters crack_tip_parameters(const Model<2>& m, const Solver<2>& solver, const CrackTip& t, const JContour& contour) {
  const auto& g = m.grid;
  const auto& ps = m.particles;
  const auto& cracks = solver.cracks();
  const std::size_t fields = static_cast<std::size_t>(g.fields);
  const int cells = contour.cells;
  const auto geo = tip_geometry(cracks, t);
  const Vec<2> tip = geo.tip;
  CrackTipParameters out;
  out.position = tip;
  out.angle = std::atan2(tip[1] - geo.behind[1], tip[0] - geo.behind[0]);
  // 1. extrapolate to the nodes of the contour's neighbourhood, per field
  const double h = g.cell_size;
  const long ci = std::lround((tip[0] - g.origin[0]) / h), cj = std::lround((tip[1] - g.origin[1]) / h);
  const long reach = cells + 3;
  std::vector<NodalField> nodal(g.slots());
  Stencil<2> st;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto& x = ps.position[p];
    if (std::abs(x[0] - (g.origin[0] + ci * h)) > reach * h || std::abs(x[1] - (g.origin[1] + cj * h)) > reach * h) continue;
    if (!make_stencil<2>(m, x, st)) continue;
    const auto& body = m.bodies[ps.body[p]];
    const auto& s = ps.state[p].stress;
    const Tensor<2> H = ps.deformation_gradient[p] - Tensor<2>::Identity();  // du/dX
    const double W = material::strain_energy_density<2>(body.constants, ps.state[p], ps.deformation_gradient[p]);
    const double K = 0.5 * body.constants.density * dot<2>(ps.velocity[p], ps.velocity[p]);
    const std::array<double, 9> v{s(0, 0), s(1, 1), s(0, 1), H(0, 0), H(0, 1), H(1, 0), H(1, 1), W, K};
    for (int q = 0; q < st.count; ++q) {
      const std::size_t node = st.node[static_cast<std::size_t>(q)];
      const double w = st.weight[static_cast<std::size_t>(q)] * ps.mass[p];
      if (w == 0.0) continue;
      const int f = fields > 1 ? cracks.field(x, g.node_position(node)) : 0;
      auto& n = nodal[node * fields + static_cast<std::size_t>(f)];
      n.mass += w;
      for (int k = 0; k < 9; ++k) n.value[static_cast<std::size_t>(k)] += w * v[static_cast<std::size_t>(k)];
    }
  }
  for (auto& n : nodal)
    if (n.mass > 0.0)
      for (auto& v : n.value) v /= n.mass;
  // 2. the contour: grid nodes around (ci, cj), counter-clockwise, as positions
  if (ci - cells < 0 || cj - cells < 0 || ci + cells >= g.nodes[0] || cj + cells >= g.nodes[1]) return out;
  std::vector<std::array<long, 2>> ring;
  for (long i = ci + cells; i >= ci - cells; --i) ring.push_back({i, cj + cells});   // top, right to left
  for (long j = cj + cells - 1; j >= cj - cells; --j) ring.push_back({ci - cells, j});  // left, down
  for (long i = ci - cells + 1; i <= ci + cells; ++i) ring.push_back({i, cj - cells});  // bottom, left to right
  for (long j = cj - cells + 1; j < cj + cells; ++j) ring.push_back({ci + cells, j});   // right, up
  auto position = [&](const std::array<long, 2>& n) { return Vec<2>{g.origin[0] + n[0] * h, g.origin[1] + n[1] * h}; };
  // find the segment of the closed ring that crosses the crack
  const std::size_t count = ring.size();
  std::size_t cut = count;
  for (std::size_t k = 0; k < count; ++k) {
    const Vec<2> a = position(ring[k]), b = position(ring[(k + 1) % count]);
    if (cracks.field(a, b) != 0) {
      cut = k;
      break;
    }
  }
  if (cut == count) return out;  // the contour misses the crack (tip too near an edge)
  out.valid = true;
  // 3. integrate from the far end of the cut segment around to its near end: each face of the
  // crack uses the field of the material on its side
  const Vec<2> a0 = position(ring[cut]), b0 = position(ring[(cut + 1) % count]);
  const double c1 = std::cos(out.angle), s1 = std::sin(out.angle);
  // crossing point of the cut segment with the crack: where the side test changes sign, by bisection
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cracks.field(a0, a0 + mid * (b0 - a0)) != 0 ? hi : lo) = mid;
  }
  const double t_cross = 0.5 * (lo + hi);
  // value of the material on the side of `side_point` at grid node n
  auto value_at = [&](const std::array<long, 2>& n, const Vec<2>& side_point) -> NodalField {
    const std::size_t node = g.index(n[0], n[1], 0);
    const int f = fields > 1 ? cracks.field(side_point, position(n)) : 0;
    return nodal[node * fields + static_cast<std::size_t>(f)];
  };
  struct PathPoint {
    Vec<2> x;
    NodalField v;
  };
  std::vector<PathPoint> path;
  const Vec<2> cross_point = a0 + t_cross * (b0 - a0);
  // start: the face on b0's side, interpolated at the crossing between a0 and b0 (both seen from b0's side)
  {
    auto va = value_at(ring[cut], b0), vb = value_at(ring[(cut + 1) % count], b0);
    NodalField v;
    for (int k = 0; k < 9; ++k) v.value[k] = (1 - t_cross) * va.value[k] + t_cross * vb.value[k];
    path.push_back({cross_point, v});
  }
  for (std::size_t k = 1; k <= count; ++k) {
    const auto& n = ring[(cut + k) % count];
    // material on the node's own side (field 0), the contour being a loop around the tip
    path.push_back({position(n), value_at(n, position(n))});
  }
  {
    auto va = value_at(ring[cut], a0), vb = value_at(ring[(cut + 1) % count], a0);
    NodalField v;
    for (int k = 0; k < 9; ++k) v.value[k] = (1 - t_cross) * va.value[k] + t_cross * vb.value[k];
    path.push_back({cross_point, v});
  }
  // integrand in crack-tip axes: rotate stress and displacement gradient
  auto integrand = [&](const NodalField& f, const Vec<2>& normal) {
    const double sxx = f.value[0], syy = f.value[1], sxy = f.value[2];
    const double ux = f.value[3], uxy = f.value[4], uyx = f.value[5], uyy = f.value[6];
    const double energy = f.value[7] + f.value[8];
    // global-axes J components first: J_m = (W + K) n_m - sigma_ij n_j du_i/dx_m
    const double tx = sxx * normal[0] + sxy * normal[1], ty = sxy * normal[0] + syy * normal[1];  // traction
    const double jx = energy * normal[0] - (tx * ux + ty * uyx);
    const double jy = energy * normal[1] - (tx * uxy + ty * uyy);
    return std::array<double, 2>{jx, jy};
  };
  double jx = 0.0, jy = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const Vec<2> d = path[k + 1].x - path[k].x;
    const double length = norm<2>(d);
    if (length == 0.0) continue;
    const Vec<2> normal{d[1] / length, -d[0] / length};  // outward for counter-clockwise travel
    const auto fa = integrand(path[k].v, normal), fb = integrand(path[k + 1].v, normal);
    jx += 0.5 * (fa[0] + fb[0]) * length;
    jy += 0.5 * (fa[1] + fb[1]) * length;
  }
  // 4. area term (eq. 8): material points inside the contour
  double area_x = 0.0, area_y = 0.0;
  const auto& acceleration = solver.accelerations();
  const auto& velocity_gradient = solver.velocity_gradients();
  std::size_t nearest = ps.size();
  double nearest_distance = 1e300;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto& x = ps.position[p];
    const double d = norm<2>(x - tip);
    if (d < nearest_distance) nearest_distance = d, nearest = p;
    if (!contour.area_term || acceleration.size() != ps.size()) continue;
    const double u = (x[0] - g.origin[0]) / h - double(ci), w = (x[1] - g.origin[1]) / h - double(cj);
    if (std::abs(u) >= cells || std::abs(w) >= cells) continue;
    const Tensor<2> H = ps.deformation_gradient[p] - Tensor<2>::Identity();  // du_i/dx_m (small strain)
    const Tensor<2>& L = velocity_gradient[p];                                // dv_i/dx_m
    const Vec<2>& a = acceleration[p];
    const Vec<2>& v = ps.velocity[p];
    area_x += ps.mass[p] * (a[0] * H(0, 0) + a[1] * H(1, 0) - v[0] * L(0, 0) - v[1] * L(1, 0));
    area_y += ps.mass[p] * (a[0] * H(0, 1) + a[1] * H(1, 1) - v[0] * L(0, 1) - v[1] * L(1, 1));
  }
  // the particle masses carry the thickness; J is per unit thickness like the contour term
  const double thickness = m.thickness;
  area_x /= thickness, area_y /= thickness;
  out.J1_area = area_x * c1 + area_y * s1;
  jx += area_x, jy += area_y;
  out.J1 = jx * c1 + jy * s1;
  out.J2 = -jx * s1 + jy * c1;
  out.G = out.J1;  // eq. 10 with the crack growing straight ahead
  // 5. K_I, K_II by the opening/sliding partition at the crack point next to the tip. opening()
  // measures (above - below) along the crack's left normal and tangent; in crack-tip axes of either
  // end the opening and the sliding keep their signs, so d_n > 0 when the crack opens and d_t > 0
  // when the upper face moves along x_1
  const auto cod = cracks.opening(t.crack, geo.next_point);
  out.opening = cod[0];
  out.sliding = cod[1];
  const double E_prime = nearest < ps.size() ? plane_modulus(m.bodies[ps.body[nearest]].constants) : 0.0;
  const double magnitude = std::hypot(out.opening, out.sliding);
  if (magnitude > 0.0 && out.G > 0.0) {
    const double k = std::sqrt(out.G * E_prime);
    if (solver.faces_closed(m, t.crack, geo.next_point)) {
      // faces in contact behind the tip: no opening mode, all of G is sliding (the surfaces' few-um
      // gap or overlap there is contact noise, not K_I)
      out.KI = 0.0;
      out.KII = (out.sliding < 0.0 ? -1.0 : 1.0) * k;
    } else {
      out.KI = out.opening / magnitude * k;
      out.KII = out.sliding / magnitude * k;
    }
  }
  return out;
}

}  // namespace rift::mpm
