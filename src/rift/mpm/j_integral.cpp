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

/// The small-strain displacement gradient du_i/dx_j of a material point: its strain (integrated
/// objectively, so free of rotation) plus the rotation, the skew part of F - I. F - I itself would
/// count (cos(theta) - 1) I of a rotation theta as strain (4e-4 at 0.03 rad; it moved J by 0.3% in
/// the ENF beam at 10 kN/m). Neo-Hookean points keep no strain: F - I.
Tensor<2> displacement_gradient(const material::Constants& c, const material::State<2>& s, const Tensor<2>& F) {
  const Tensor<2> H = F - Tensor<2>::Identity();
  if (c.kind == material::Kind::neo_hookean) return H;
  return s.strain + 0.5 * (H - H.transpose());
}

/// In-plane E' = 4 mu (lambda' + mu) / (lambda' + 2 mu) of the 2D constants: E in plane stress
/// (lambda' = lambda*), E / (1 - nu^2) in plane strain.
double plane_modulus(const material::Constants& c) {
  return 4.0 * c.shear_modulus * (c.lambda + c.shear_modulus) / (c.lambda + 2.0 * c.shear_modulus);
}

/// Williams near-tip displacement of unit K_I (mode 1) or K_II (mode 2) in crack-tip axes at polar
/// (r, theta), theta measured from the growth direction (Anderson, Fracture Mechanics, table 2.2).
Vec<2> williams_displacement(int mode, double r, double theta, double mu, double kappa) {
  const double f = std::sqrt(r / (2.0 * M_PI)) / (2.0 * mu);
  const double c = std::cos(0.5 * theta), s = std::sin(0.5 * theta);
  if (mode == 1) return {f * c * (kappa - 1.0 + 2.0 * s * s), f * s * (kappa + 1.0 - 2.0 * c * c)};
  return {f * s * (kappa + 1.0 + 2.0 * c * c), -f * c * (kappa - 1.0 - 2.0 * s * s)};
}

/// The auxiliary field of the interaction integral at (r, theta): displacement gradient du~_i/dx_j
/// (d/dr of the sqrt(r) field is u/2r; d/dtheta by central difference) and the stress from Hooke's
/// law with the 2D constants, kappa = (lambda' + 3 mu) / (lambda' + mu) (3 - 4 nu in plane strain,
/// (3 - nu) / (1 + nu) in plane stress).
struct AuxiliaryField {
  Tensor<2> gradient, stress;
};

AuxiliaryField williams_field(int mode, double r, double theta, const material::Constants& k) {
  const double mu = k.shear_modulus, kappa = (k.lambda + 3.0 * mu) / (k.lambda + mu);
  const double step = 1e-6;
  const Vec<2> u = williams_displacement(mode, r, theta, mu, kappa);
  const Vec<2> du_dtheta = (0.5 / step) * (williams_displacement(mode, r, theta + step, mu, kappa) -
                                           williams_displacement(mode, r, theta - step, mu, kappa));
  const double c = std::cos(theta), s = std::sin(theta);
  AuxiliaryField a;
  for (int i = 0; i < 2; ++i) {
    const double du_dr = 0.5 * u[i] / r;
    a.gradient(i, 0) = du_dr * c - du_dtheta[i] * s / r;
    a.gradient(i, 1) = du_dr * s + du_dtheta[i] * c / r;
  }
  const Tensor<2> strain = 0.5 * (a.gradient + a.gradient.transpose());
  a.stress = k.lambda * strain.trace() * Tensor<2>::Identity() + 2.0 * mu * strain;
  return a;
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
  // the contour: the smallest grid-line rectangle reaching `cells` cells from the tip on every side
  // (around the node nearest the tip when the tip is on a node; symmetric about a crack that runs
  // midway between grid lines, so a symmetric problem reads no spurious K_II)
  const double tu = (tip[0] - g.origin[0]) / h, tv = (tip[1] - g.origin[1]) / h;
  const long i_lo = static_cast<long>(std::floor(tu - cells + 1e-9)), i_hi = static_cast<long>(std::ceil(tu + cells - 1e-9));
  const long j_lo = static_cast<long>(std::floor(tv - cells + 1e-9)), j_hi = static_cast<long>(std::ceil(tv + cells - 1e-9));
  const double ci = 0.5 * double(i_lo + i_hi), cj = 0.5 * double(j_lo + j_hi);
  const long reach = cells + 3;
  std::vector<NodalField> nodal(g.slots());
  Stencil<2> st;
  std::size_t nearest = ps.size();  // the material point nearest the tip: its body's constants
  double nearest_distance = 1e300;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto& x = ps.position[p];
    if (std::abs(x[0] - (g.origin[0] + ci * h)) > reach * h || std::abs(x[1] - (g.origin[1] + cj * h)) > reach * h) continue;
    if (const double d = norm<2>(x - tip); d < nearest_distance) nearest_distance = d, nearest = p;
    if (!make_stencil<2>(m, x, st)) continue;
    const auto& body = m.bodies[ps.body[p]];
    const auto& s = ps.state[p].stress;
    const Tensor<2> H = displacement_gradient(body.constants, ps.state[p], ps.deformation_gradient[p]);
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
  // 2. the contour's grid nodes, counter-clockwise, as positions
  if (i_lo < 0 || j_lo < 0 || i_hi >= g.nodes[0] || j_hi >= g.nodes[1]) return out;
  std::vector<std::array<long, 2>> ring;
  for (long i = i_hi; i >= i_lo; --i) ring.push_back({i, j_hi});          // top, right to left
  for (long j = j_hi - 1; j >= j_lo; --j) ring.push_back({i_lo, j});      // left, down
  for (long i = i_lo + 1; i <= i_hi; ++i) ring.push_back({i, j_lo});      // bottom, left to right
  for (long j = j_lo + 1; j < j_hi; ++j) ring.push_back({i_hi, j});       // right, up
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
  // the interaction integrand for the unit mode-1 and mode-2 auxiliary fields, in crack-tip axes
  // (Q: rows e_1, e_2); theta is continuous along the path, from the lower face to the upper one
  if (nearest == ps.size()) {  // no material near the tip
    out.valid = false;
    return out;
  }
  const auto& constants = m.bodies[ps.body[nearest]].constants;
  Tensor<2> Q;
  Q << c1, s1, -s1, c1;
  auto local = [&](const Vec<2>& v) -> Eigen::Vector2d { return Q * Eigen::Vector2d(v[0], v[1]); };
  auto interaction = [&](const NodalField& f, const Vec<2>& x, double theta, const Vec<2>& normal) {
    Tensor<2> sigma, H;
    sigma << f.value[0], f.value[2], f.value[2], f.value[1];
    H << f.value[3], f.value[4], f.value[5], f.value[6];
    sigma = Q * sigma * Q.transpose(), H = Q * H * Q.transpose();
    const Eigen::Vector2d n = local(normal);
    const double r = local(x - tip).norm();
    std::array<double, 2> value{};
    if (r == 0.0) return value;
    for (int mode = 1; mode <= 2; ++mode) {
      const auto aux = williams_field(mode, r, theta, constants);
      const Tensor<2> aux_strain = 0.5 * (aux.gradient + aux.gradient.transpose());
      const Eigen::Vector2d traction = sigma * n, aux_traction = aux.stress * n;
      value[mode - 1] = (sigma.array() * aux_strain.array()).sum() * n[0] - traction.dot(aux.gradient.col(0)) -
                        aux_traction.dot(H.col(0));
    }
    return value;
  };
  std::vector<double> theta(path.size());
  for (std::size_t k = 0; k < path.size(); ++k) {
    const Eigen::Vector2d y = local(path[k].x - tip);
    theta[k] = std::atan2(y[1], y[0]);
    if (k == 0) {
      if (theta[k] > 0.0) theta[k] -= 2.0 * M_PI;  // the path starts on the lower face
    } else {
      while (theta[k] - theta[k - 1] > M_PI) theta[k] -= 2.0 * M_PI;
      while (theta[k] - theta[k - 1] < -M_PI) theta[k] += 2.0 * M_PI;
    }
  }
  double jx = 0.0, jy = 0.0, interaction_1 = 0.0, interaction_2 = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const Vec<2> d = path[k + 1].x - path[k].x;
    const double length = norm<2>(d);
    if (length == 0.0) continue;
    const Vec<2> normal{d[1] / length, -d[0] / length};  // outward for counter-clockwise travel
    const auto fa = integrand(path[k].v, normal), fb = integrand(path[k + 1].v, normal);
    jx += 0.5 * (fa[0] + fb[0]) * length;
    jy += 0.5 * (fa[1] + fb[1]) * length;
    const auto ia = interaction(path[k].v, path[k].x, theta[k], normal);
    const auto ib = interaction(path[k + 1].v, path[k + 1].x, theta[k + 1], normal);
    interaction_1 += 0.5 * (ia[0] + ib[0]) * length;
    interaction_2 += 0.5 * (ia[1] + ib[1]) * length;
  }
  // 4. area terms (eq. 8 and its interaction part rho a_i du~_i/dx_1): material points inside the contour
  double area_x = 0.0, area_y = 0.0, area_1 = 0.0, area_2 = 0.0;
  const auto& acceleration = solver.accelerations();
  const auto& velocity_gradient = solver.velocity_gradients();
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const auto& x = ps.position[p];
    if (!contour.area_term || acceleration.size() != ps.size()) break;
    const double u = (x[0] - g.origin[0]) / h, w = (x[1] - g.origin[1]) / h;
    if (u <= double(i_lo) || u >= double(i_hi) || w <= double(j_lo) || w >= double(j_hi)) continue;
    // (theta of a point by its side of the crack-tip axis; only points within round-off of a
    // curved crack's faces could take the wrong branch)
    const Eigen::Vector2d y = local(x - tip), a_tip = local(acceleration[p]);
    if (const double r = y.norm(); r > 0.0) {
      const double angle = std::atan2(y[1], y[0]);
      area_1 += ps.mass[p] * a_tip.dot(williams_field(1, r, angle, constants).gradient.col(0));
      area_2 += ps.mass[p] * a_tip.dot(williams_field(2, r, angle, constants).gradient.col(0));
    }
    const Tensor<2> H = displacement_gradient(m.bodies[ps.body[p]].constants, ps.state[p], ps.deformation_gradient[p]);  // du_i/dx_m
    const Tensor<2>& L = velocity_gradient[p];                                // dv_i/dx_m
    const Vec<2>& a = acceleration[p];
    const Vec<2>& v = ps.velocity[p];
    area_x += ps.mass[p] * (a[0] * H(0, 0) + a[1] * H(1, 0) - v[0] * L(0, 0) - v[1] * L(1, 0));
    area_y += ps.mass[p] * (a[0] * H(0, 1) + a[1] * H(1, 1) - v[0] * L(0, 1) - v[1] * L(1, 1));
  }
  // the particle masses carry the thickness; J is per unit thickness like the contour term
  const double thickness = m.thickness;
  area_x /= thickness, area_y /= thickness, area_1 /= thickness, area_2 /= thickness;
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
  const double E_prime = plane_modulus(constants);
  const double k = out.G > 0.0 ? std::sqrt(out.G * E_prime) : 0.0;
  // faces in contact behind the tip: no opening mode (the surfaces' few-um gap or overlap there is
  // contact noise, not K_I), K_II keeps its share
  const bool closed = solver.faces_closed(m, t.crack, geo.next_point);
  // sqrt(E' G) split in the ratio first : second (eqs. 21-22 with d_n : d_t)
  auto partition = [&](double first, double second, double& KI, double& KII) {
    const double magnitude = std::hypot(first, second);
    if (magnitude == 0.0) return;
    KI = closed ? 0.0 : first / magnitude * k;
    KII = second / magnitude * k;
  };
  partition(out.opening, out.sliding, out.KI_cod, out.KII_cod);
  // 6. the interaction integral: I = 2 K / E' for the unit auxiliary field of each mode
  out.KI_interaction = 0.5 * E_prime * (interaction_1 + area_1);
  out.KII_interaction = 0.5 * E_prime * (interaction_2 + area_2);
  if (contour.partition == ModePartition::cod) out.KI = out.KI_cod, out.KII = out.KII_cod;
  else partition(out.KI_interaction, out.KII_interaction, out.KI, out.KII);
  return out;
}

}  // namespace rift::mpm
