#include "rift/mpm/discretize.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "rift/geometry/region.hpp"
#include "rift/mpm/stencil_cache.hpp"

namespace rift::mpm {

material::Constants continuum_constants(const scene::Scene& s, const scene::Material& m) {
  material::Constants c;
  using MK = scene::ModelKind;
  c.kind = m.model == MK::neo_hookean ? material::Kind::neo_hookean
           : m.model == MK::j2_plasticity ? material::Kind::j2_plasticity
                                          : material::Kind::linear_elastic;
  c.density = m.density;
  c.shear_modulus = m.shear_modulus;
  c.bulk_modulus = m.bulk_modulus;
  c.lambda = m.bulk_modulus - 2.0 * m.shear_modulus / 3.0;
  // plane stress: sigma_zz = 0 gives the in-plane lambda* = 2 lambda G / (lambda + 2 G)
  if (s.dimension == 2 && s.plane == scene::PlaneCondition::stress)
    c.lambda = 2.0 * c.lambda * c.shear_modulus / (c.lambda + 2.0 * c.shear_modulus);
  c.yield_stress = m.yield_stress;
  c.hardening_modulus = m.hardening_modulus;
  return c;
}

template <int D>
Model<D> discretize(const scene::Scene& s) {
  Model<D> m;
  const double h = s.mpm.cell_size;
  using SK = scene::Mpm::Shape;
  m.shape = s.mpm.shape == SK::linear ? ShapeKind::linear : s.mpm.shape == SK::gimp ? ShapeKind::gimp
          : s.mpm.shape == SK::bspline2 ? ShapeKind::bspline2 : ShapeKind::bspline3;
  // grid: the given box, or the bodies' bounds grown by three cells, snapped to whole cells
  Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  std::vector<geometry::Region> regions;
  for (const auto& b : s.bodies) {
    regions.push_back(geometry::Region::build(s, b.region));
    Point3 l, u;
    regions.back().bounds(l, u);
    for (int a = 0; a < D; ++a) {
      if (!std::isfinite(l[a]) || !std::isfinite(u[a]))
        throw SceneError(b.where, "bodies." + b.name + ".region", "region \"" + b.region + "\" is unbounded; intersect it with a box");
      lo[a] = std::min(lo[a], l[a]), hi[a] = std::max(hi[a], u[a]);
    }
  }
  if (s.mpm.grid_min) {
    lo = *s.mpm.grid_min, hi = *s.mpm.grid_max;
  } else {
    for (int a = 0; a < D; ++a) lo[a] = std::floor(lo[a] / h) * h - 3 * h, hi[a] = std::ceil(hi[a] / h) * h + 3 * h;
  }
  m.grid.cell_size = h;
  for (int a = 0; a < D; ++a) {
    m.grid.origin[a] = lo[a];
    const double cells = std::ceil((hi[a] - lo[a]) / h - 1e-9);
    if (!(cells >= 1)) throw SceneError(s.mpm.grid_max_where, "mpm.grid_max", "the grid must be at least one cell wide");
    if (cells > 1e6) throw SceneError(s.mpm.cell_size_where, "mpm.cell_size",
                                       fmt::format("{:.4g} cells along {}, more than a million; make the cells larger", cells, "xyz"[a]));
    m.grid.nodes[a] = static_cast<long>(cells) + 1;
  }
  // the stencil cache numbers nodes in 32 bits (stencil_cache.hpp); such a grid would not fit in
  // memory anyway (about 100 bytes a node)
  constexpr double numbers = double(std::numeric_limits<typename StencilCache<D>::NodeIndex>::max()) + 1.0;
  if (double(m.grid.nodes[0]) * double(m.grid.nodes[1]) * double(m.grid.nodes[2]) >= numbers)
    throw SceneError(s.mpm.cell_size_where, "mpm.cell_size", "more than 2^32 grid nodes; make the cells larger or the grid smaller");
  // velocity fields per node: 3 with explicit cracks (CRAMP: same side, above, below), one per body
  // with multi-material contact, else 1
  m.grid.fields = !s.cracks.empty() ? 3
                : s.mpm.contact != scene::Mpm::Contact::none && s.bodies.size() > 1 ? static_cast<int>(s.bodies.size())
                                                                                     : 1;
  m.grid.resize();
  // material points: particles_per_cell^D per cell, at sub-cell centres, inside the body's region
  auto& ps = m.particles;
  for (std::size_t bi = 0; bi < s.bodies.size(); ++bi) {
    const auto& b = s.bodies[bi];
    BodyInfo info;
    info.name = b.name;
    info.first = ps.size();
    info.constants = continuum_constants(s, s.materials[b.material]);
    const double spacing = h / b.particles_per_cell;
    m.particle_half_width = 0.5 * spacing;
    m.thickness = D == 2 ? s.thickness : 1.0;
    const double volume = std::pow(spacing, D) * (D == 2 ? s.thickness : 1.0);
    std::array<long, 3> count{1, 1, 1};
    for (int a = 0; a < D; ++a) count[a] = (m.grid.nodes[a] - 1) * b.particles_per_cell;
    for (long k = 0; k < count[2]; ++k)
      for (long j = 0; j < count[1]; ++j)
        for (long i = 0; i < count[0]; ++i) {
          const long ijk[3] = {i, j, k};
          Point3 p{0, 0, 0};
          Vec<D> x;
          for (int a = 0; a < D; ++a) x[a] = p[a] = m.grid.origin[a] + (double(ijk[a]) + 0.5) * spacing;
          if (!regions[bi].contains(p)) continue;
          ps.position.push_back(x);
          ps.reference_position.push_back(x);
          ps.velocity.push_back(Vec<D>{});
          ps.external_force.push_back(Vec<D>{});
          ps.mass.push_back(info.constants.density * volume);
          ps.volume.push_back(volume);
          ps.reference_volume.push_back(volume);
          ps.deformation_gradient.push_back(Tensor<D>::Identity());
          ps.affine_velocity.push_back(Tensor<D>::Zero());
          ps.state.push_back(material::State<D>{});
          ps.body.push_back(static_cast<std::uint32_t>(bi));
        }
    info.last = ps.size();
    if (info.last == info.first)
      throw SceneError(b.where, "bodies." + b.name, "region \"" + b.region + "\" holds no material point; make it larger or the cells smaller");
    m.bodies.push_back(info);
  }
  for (const auto& iv : s.initial_velocities) {
    const auto selected = geometry::indices_inside<D>(geometry::Region::build(s, iv.region), ps.size(),
                                                      [&](std::size_t i) { return ps.position[i]; });
    for (auto i : selected)
      for (int a = 0; a < D; ++a) ps.velocity[i][a] = iv.velocity[a];
    if (selected.empty()) throw SceneError(iv.where, "initial_velocity.region", "region \"" + iv.region + "\" selects no material point");
  }
  return m;
}

template Model<2> discretize<2>(const scene::Scene&);
template Model<3> discretize<3>(const scene::Scene&);

}  // namespace rift::mpm
