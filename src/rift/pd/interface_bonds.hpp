// The bonds across the scene's pre-existing fractures (scene::Interface), held by the model (model.hpp):
// the plane, axes and strengths of each interface's law, the bonds that cross one and the particles
// with such a bond, set up with the model (discretize.cpp). The law that fails these bonds and the
// contact of the failed ones are geomechanics' (geomech/interface_law.hpp, geomech/interface_contact.hpp).
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/geometry/precrack.hpp"
#include "rift/pd/fluid_state.hpp"
#include "rift/scene/scene.hpp"

namespace rift::pd {

/// A pre-existing fracture's plane and its interface law (scene::Interface), 3D vectors also in 2D.
struct InterfaceLaw {
  std::array<double, 3> point{}, normal{};  // a point of the plane and its unit normal
  std::array<double, 3> tangent{}, binormal{};  // in-plane axes (2D: binormal is z)
  std::vector<std::array<double, 3>> polygon;    // 2D: the segment's end points; 3D: the polygon
  double length = 0.0;                           // 2D: the segment's length
  double tensile_strength = 0.0, cohesion = 0.0, friction_coefficient = 0.0;  // Pa, Pa, -
  int near_side = 0;  // the side (sign of (x - point) . normal) of the fluid sources; 0 without
  double in_situ_normal_compression = 0.0;  // -n . sigma n of the far-field in-situ stresses, Pa (0 without)
};

/// The bonds that cross a pre-existing fracture, row i listing those of particle i (the mirror
/// bond j-i sits in row j).
struct InterfaceBonds {
  std::vector<std::int64_t> offset;        // size n+1 (empty without interfaces)
  std::vector<std::int64_t> slot;          // the bond's index in Bonds
  std::vector<std::uint16_t> interface;    // the scene's interface
  std::vector<InterfaceLaw> laws;          // per scene interface
  std::vector<std::array<double, 3>> slip; // per entry: the slip of the failed bond's faces so far (geomech/interface_contact.hpp)
  std::vector<std::uint8_t> across_crack;  // per entry: the failed bond joins the two faces of a crack the fluid fills (hf/crack_junction.hpp)
  std::vector<std::int32_t> particles;     // the particles with a bond across an interface, ascending
  std::vector<std::array<double, 9>> strain;  // per particle above: the rock's strain around it (bulk_strain.hpp), refreshed with the law

  bool empty() const { return slot.empty(); }
};

template <int D>
struct Model;  // model.hpp

namespace interface_detail {
inline Point3 cross3(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Point3 unit(const Point3& a) { return (1.0 / norm<3>(a)) * a; }
}  // namespace interface_detail

/// The plane, axes and law of a scene interface. 2D: the normal is the segment's direction turned
/// by +90 degrees; 3D: the polygon's normal by Newell's method, the tangent along its first edge.
inline InterfaceLaw make_interface_law(const scene::Interface& f, int dimension) {
  using namespace interface_detail;
  InterfaceLaw law;
  law.point = f.points[0];
  law.polygon = f.points;
  law.tensile_strength = f.tensile_strength;
  law.cohesion = f.cohesion;
  law.friction_coefficient = f.friction_coefficient;
  const Point3 edge = f.points[1] - f.points[0];
  law.tangent = unit(edge);
  if (dimension == 2) {
    law.normal = {-law.tangent[1], law.tangent[0], 0.0};
    law.binormal = {0.0, 0.0, 1.0};
    law.length = norm<3>(edge);
  } else {
    law.normal = unit(geometry::PreCrack(3, f.points).normal());
    law.binormal = cross3(law.normal, law.tangent);
  }
  return law;
}

/// Laws of the scene's interfaces, the particles with bonds across one, the side of each
/// interface the fluid sources are on (the mean position of the particles with pressure bonds) and
/// the normal compression the in-situ stresses put across it (the thesis' EQ 4.4).
template <int D>
void prepare_interfaces(const scene::Scene& s, Model<D>& m) {
  InterfaceBonds& ib = m.interface_bonds;
  ib.laws.clear();
  for (const auto& f : s.interfaces) {
    auto law = make_interface_law(f, D);
    if (s.in_situ.enabled)
      for (int k = 0; k < D; ++k) law.in_situ_normal_compression -= s.in_situ.principal(k) * law.normal[k] * law.normal[k];
    ib.laws.push_back(law);
  }
  ib.particles.clear();
  ib.slip.assign(ib.slot.size(), {0.0, 0.0, 0.0});
  ib.across_crack.assign(ib.slot.size(), 0);
  if (ib.offset.empty()) return;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (ib.offset[i + 1] > ib.offset[i]) ib.particles.push_back(static_cast<std::int32_t>(i));
  std::array<double, 3> centre{0, 0, 0};
  std::size_t count = 0;
  const CrackBonds& w = m.crack_bonds;
  for (std::size_t i = 0; i + 1 < w.offset.size(); ++i)
    if (w.offset[i + 1] > w.offset[i]) {
      for (int k = 0; k < D; ++k) centre[k] += m.reference_position[i][k];
      ++count;
    }
  for (std::size_t f = 0; f < ib.laws.size(); ++f) {
    auto& law = ib.laws[f];
    if (count == 0) continue;
    std::array<double, 3> c = centre;
    for (auto& x : c) x /= double(count);
    const double side = dot<3>(c - law.point, law.normal);
    law.near_side = side > 0.0 ? 1 : side < 0.0 ? -1 : 0;
  }
}

}  // namespace rift::pd
