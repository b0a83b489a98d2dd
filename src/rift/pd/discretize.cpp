#include "rift/pd/discretize.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "rift/geometry/precrack.hpp"
#include "rift/geometry/region.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/interface_bonds.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/normal_stress_failure.hpp"
#include "rift/pd/pressure_bonds.hpp"
#include "rift/pd/surface_correction.hpp"
#include "rift/pd/ves.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

double partial_volume_fraction(const int* o, int dimension, double h, scene::Body::PartialVolume scheme) {
  double r2 = 0;
  for (int k = 0; k < dimension; ++k) r2 += double(o[k]) * o[k];
  const double r = std::sqrt(r2);
  if (scheme == scene::Body::PartialVolume::lammps) {
    // LAMMPS PERI: bonds with |xi| <= delta; linear taper from 1 at delta - dx/2 to 1/2 at delta.
    if (r > h) return 0.0;
    return std::abs(r - h) <= 0.5 ? (h + 0.5 - r) : 1.0;
  }
  const double half_diag = 0.5 * std::sqrt(double(dimension));
  if (r + half_diag <= h) return 1.0;
  if (r - half_diag >= h) return 0.0;
  // geometric fraction of the cell inside the ball, by a 16^D midpoint rule
  constexpr int n = 16;
  int inside = 0, total = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < (dimension == 3 ? n : 1); ++c) {
        double p[3] = {o[0] + (a + 0.5) / n - 0.5, o[1] + (b + 0.5) / n - 0.5, dimension == 3 ? o[2] + (c + 0.5) / n - 0.5 : 0.0};
        inside += (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= h * h);
        ++total;
      }
  return double(inside) / total;
}

namespace {

struct Offset {
  std::array<int, 3> o;
  double fraction;
};

std::vector<Offset> family_offsets(int dimension, double h, scene::Body::PartialVolume scheme) {
  std::vector<Offset> out;
  const int r = static_cast<int>(std::ceil(h + 1.0));
  const int rz = dimension == 3 ? r : 0;
  for (int z = -rz; z <= rz; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        if (x == 0 && y == 0 && z == 0) continue;
        int o[3] = {x, y, z};
        double f = partial_volume_fraction(o, dimension, h, scheme);
        if (f > 0.0) out.push_back({{x, y, z}, f});
      }
  return out;  // ordered as the lattice is numbered (x fastest), so rows come out sorted by j
}

/// Position of the body's lattice site (i, j, k): lattice_origin + (index + 1/2) spacing.
template <int D>
Point3 lattice_site(const scene::Body& b, long x, long y, long z) {
  const long ijk[3] = {x, y, z};
  Point3 p{0, 0, 0};
  for (int k = 0; k < D; ++k) p[k] = b.lattice_origin[k] + (double(ijk[k]) + 0.5) * b.spacing;
  return p;
}

template <int D>
void fill_body(const scene::Scene& s, const scene::Body& b, std::size_t index, Model<D>& m,
               std::vector<std::array<long, 3>>& lattice_index) {
  auto region = geometry::Region::build(s, b.region);
  std::vector<geometry::Region> holes;
  for (const auto& h : s.boreholes) holes.push_back(geometry::Region::build(s, h.region));
  Point3 lo, hi;
  region.bounds(lo, hi);
  for (int k = 0; k < D; ++k)
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]))
      throw SceneError(b.where, "bodies." + b.name + ".region", "region \"" + b.region + "\" is unbounded; intersect it with a box");
  std::array<long, 3> first{0, 0, 0}, last{0, 0, 0};
  for (int k = 0; k < D; ++k) {
    first[k] = static_cast<long>(std::ceil((lo[k] - b.lattice_origin[k]) / b.spacing - 0.5));
    last[k] = static_cast<long>(std::floor((hi[k] - b.lattice_origin[k]) / b.spacing - 0.5));
  }
  double cells = 1;
  for (int k = 0; k < D; ++k) cells *= double(last[k] - first[k] + 1);
  if (cells > 2e9) throw SceneError(b.where, "bodies." + b.name + ".spacing", "spacing is too fine for the region: more than 2e9 lattice sites");
  const double cell_volume = std::pow(b.spacing, D) * (D == 2 ? s.thickness : 1.0);
  for (long z = first[2]; z <= last[2]; ++z)
    for (long y = first[1]; y <= last[1]; ++y)
      for (long x = first[0]; x <= last[0]; ++x) {
        const Point3 p = lattice_site<D>(b, x, y, z);
        if (!region.contains(p)) continue;
        bool fluid = false;
        for (const auto& h : holes) fluid = fluid || h.contains(p);
        if (fluid) continue;  // a borehole site: fluid, not material
        Vec<D> v;
        for (int k = 0; k < D; ++k) v[k] = p[k];
        m.reference_position.push_back(v);
        m.volume.push_back(cell_volume);
        m.body.push_back(static_cast<std::uint32_t>(index));
        lattice_index.push_back({x, y, z});
      }
}

template <int D>
void build_bonds(const scene::Scene& s, Model<D>& m, const std::vector<std::array<long, 3>>& lattice_index) {
  const std::size_t n = m.size();
  bool any_fluid = !s.boreholes.empty();
  for (const auto& c : s.cracks) any_fluid = any_fluid || c.pressure > 0.0;
  m.fluid_network.dry.assign(s.cracks.size() + s.boreholes.size(), 0);
  for (std::size_t c = 0; c < s.cracks.size(); ++c) m.fluid_network.dry[c] = s.cracks[c].pressure > 0.0 ? 0 : 1;
  m.fluid_network.sealed.assign(s.cracks.size() + s.boreholes.size(), 0);
  for (std::size_t h = 0; h < s.boreholes.size(); ++h) m.fluid_network.sealed[s.cracks.size() + h] = s.boreholes[h].breakdown_pressure ? 1 : 0;
  std::vector<geometry::PreCrack> cracks;
  std::vector<std::uint16_t> crack_of;  // scene crack of each segment / polygon
  for (std::size_t ci = 0; ci < s.cracks.size(); ++ci) {
    const auto& c = s.cracks[ci];
    if (D == 2) {  // a polyline: one segment each
      for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
        cracks.emplace_back(D, std::vector<Point3>{c.points[k], c.points[k + 1]});
        crack_of.push_back(static_cast<std::uint16_t>(ci));
      }
    } else {
      cracks.emplace_back(D, c.points);
      crack_of.push_back(static_cast<std::uint16_t>(ci));
    }
  }
  std::vector<geometry::PreCrack> interfaces;
  for (const auto& f : s.interfaces) interfaces.emplace_back(D, f.points);
  Bonds& b = m.bonds;
  b.offset.assign(n + 1, 0);
  // bonds across pre-existing fractures (interface_bonds.hpp): their place in row i and the interface
  std::vector<std::vector<std::pair<std::uint32_t, std::uint16_t>>> across(n);
  // pressure bonds (hf/crack_pressure.hpp): bonds the cracks cut (when the scene has a fluid) and bonds
  // to the fluid sites of boreholes
  std::vector<std::vector<std::int32_t>> wet_nb(n);
  std::vector<std::vector<float>> wet_frac(n);
  std::vector<std::vector<std::uint16_t>> wet_crack(n);
  std::vector<std::vector<std::array<double, 3>>> wet_xi(n);
  std::vector<std::vector<double>> wet_m(n);  // fluid site: its whole-family weighted volume
  auto record_pressure_bond = [&](std::size_t i, std::int32_t j, double fraction, std::size_t source, const std::array<double, 3>& xi,
                                  double fluid_m) {
    wet_nb[i].push_back(j);
    wet_frac[i].push_back(static_cast<float>(fraction));
    wet_crack[i].push_back(static_cast<std::uint16_t>(source));
    wet_xi[i].push_back(xi);
    wet_m[i].push_back(fluid_m);
  };
  for (std::size_t bi = 0; bi < m.bodies.size(); ++bi) {
    auto& info = m.bodies[bi];
    const auto& body = s.bodies[bi];
    const double h = info.constants.horizon / info.constants.spacing;
    auto offsets = family_offsets(D, h, body.partial_volume);
    // the body's family offsets, with the index of each one's reverse
    const std::size_t first_family = m.bonds.families.size();
    info.first_family = first_family;
    info.family_count = offsets.size();
    if (first_family + offsets.size() > std::numeric_limits<std::uint16_t>::max() + std::size_t{1})
      throw SceneError(body.where, "bodies." + body.name + ".horizon",
                       "the bodies' families have more than 65536 lattice offsets in all; use fewer spacings per horizon");
    const double site_volume = std::pow(body.spacing, D) * (D == 2 ? s.thickness : 1.0);
    for (const auto& off : offsets) {
      FamilyOffset f;
      for (int k = 0; k < D; ++k) f.xi[static_cast<std::size_t>(k)] = off.o[static_cast<std::size_t>(k)] * body.spacing;
      f.length = std::sqrt(f.xi[0] * f.xi[0] + f.xi[1] * f.xi[1] + f.xi[2] * f.xi[2]);
      f.inverse_length = 1.0 / f.length;
      f.volume = site_volume * off.fraction;
      m.bonds.families.push_back(f);
    }
    for (std::size_t a = 0; a < offsets.size(); ++a)
      for (std::size_t c = 0; c < offsets.size(); ++c)
        if (offsets[c].o[0] == -offsets[a].o[0] && offsets[c].o[1] == -offsets[a].o[1] && offsets[c].o[2] == -offsets[a].o[2])
          m.bonds.families[first_family + a].mirror = static_cast<std::uint32_t>(first_family + c);
    // boreholes: bonds to their lattice sites carry the fluid pressure; a fluid site's weighted
    // volume is that of a whole family
    const auto region = geometry::Region::build(s, body.region);
    Point3 region_lo, region_hi;
    region.bounds(region_lo, region_hi);
    std::vector<geometry::Region> holes;
    for (const auto& hole : s.boreholes) holes.push_back(geometry::Region::build(s, hole.region));
    double whole_family = 0.0;
    for (const auto& off : offsets) {
      double r2 = 0.0;
      for (int k = 0; k < D; ++k) r2 += double(off.o[k]) * off.o[k];
      const double xi = std::sqrt(r2) * body.spacing;
      whole_family += influence(info.constants.influence, xi, info.constants.horizon) * xi * xi * site_volume * off.fraction;
    }
    // the boreholes' reference volumes: their lattice sites within the body's bounds
    m.fluid_network.reference_volume.resize(s.cracks.size() + s.boreholes.size(), 0.0);
    for (std::size_t h = 0; h < holes.size(); ++h) {
      Point3 hole_lo, hole_hi;
      holes[h].bounds(hole_lo, hole_hi);
      std::array<long, 3> from{0, 0, 0}, to{0, 0, 0};
      for (int k = 0; k < D; ++k) {
        const double lo_k = std::max(hole_lo[k], region_lo[k]), hi_k = std::min(hole_hi[k], region_hi[k]);
        from[k] = static_cast<long>(std::ceil((lo_k - body.lattice_origin[k]) / body.spacing - 0.5));
        to[k] = static_cast<long>(std::floor((hi_k - body.lattice_origin[k]) / body.spacing - 0.5));
      }
      std::int64_t sites = 0;
      for (long z = from[2]; z <= to[2]; ++z)
        for (long y = from[1]; y <= to[1]; ++y)
          for (long x = from[0]; x <= to[0]; ++x) {
            if (holes[h].contains(lattice_site<D>(body, x, y, z))) ++sites;
          }
      m.fluid_network.reference_volume[s.cracks.size() + h] += double(sites) * site_volume;
    }
    // dense lattice -> particle map over the body's index box
    std::array<long, 3> lo{0, 0, 0}, hi{0, 0, 0};
    lo = hi = lattice_index[info.first];
    for (std::size_t i = info.first; i < info.last; ++i)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], lattice_index[i][k]), hi[k] = std::max(hi[k], lattice_index[i][k]);
    const long nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
    std::vector<std::int32_t> map(static_cast<std::size_t>(nx * ny * nz), -1);
    auto cell = [&](long x, long y, long z) { return static_cast<std::size_t>(((z - lo[2]) * ny + (y - lo[1])) * nx + (x - lo[0])); };
    for (std::size_t i = info.first; i < info.last; ++i)
      map[cell(lattice_index[i][0], lattice_index[i][1], lattice_index[i][2])] = static_cast<std::int32_t>(i);
    // cracks (and interfaces) whose bounding box, grown by the horizon, can cut this body's bonds
    auto grown_boxes = [&](const std::vector<geometry::PreCrack>& planes) {
      std::vector<std::pair<std::size_t, std::array<Point3, 2>>> boxes;
      for (std::size_t ci = 0; ci < planes.size(); ++ci) {
        Point3 clo, chi;
        planes[ci].bounds(clo, chi);
        for (int k = 0; k < 3; ++k) clo[k] -= info.constants.horizon * 1.5, chi[k] += info.constants.horizon * 1.5;
        boxes.push_back({ci, {clo, chi}});
      }
      return boxes;
    };
    const auto near = grown_boxes(cracks), near_interfaces = grown_boxes(interfaces);
    // i's family: counted (fill false), or written at b.offset[i] with its pressure bonds and the
    // bonds across interfaces recorded (fill true); returns the number of bonds
    auto row = [&](std::size_t i, bool fill) {
      std::int64_t count = 0;
      const auto& li = lattice_index[i];
      Point3 pi{0, 0, 0};
      for (int k = 0; k < D; ++k) pi[k] = m.reference_position[i][k];
      auto within = [&](const std::vector<std::pair<std::size_t, std::array<Point3, 2>>>& boxes) {
        std::vector<std::size_t> list;
        for (const auto& [c, box] : boxes) {
          bool in = true;
          for (int k = 0; k < D; ++k) in = in && pi[k] >= box[0][k] && pi[k] <= box[1][k];
          if (in) list.push_back(c);
        }
        return list;
      };
      const auto cutting = within(near), crossing = within(near_interfaces);
      for (std::size_t a = 0; a < offsets.size(); ++a) {
        const auto& off = offsets[a];
        long x = li[0] + off.o[0], y = li[1] + off.o[1], z = li[2] + off.o[2];
        const bool in_box = !(x < lo[0] || x > hi[0] || y < lo[1] || y > hi[1] || z < lo[2] || z > hi[2]);
        std::int32_t j = in_box ? map[cell(x, y, z)] : -1;
        if (j < 0) {
          if (!fill || holes.empty()) continue;
          const Point3 site = lattice_site<D>(body, x, y, z);
          // inside the body's bounds: the body's region may be the block with the hole cut out
          bool inside = true;
          for (int k = 0; k < D; ++k) inside = inside && site[k] >= region_lo[k] && site[k] <= region_hi[k];
          if (!inside) continue;
          for (std::size_t hi_ = 0; hi_ < holes.size(); ++hi_) {
            if (!holes[hi_].contains(site)) continue;
            std::array<double, 3> xi{0, 0, 0};
            for (int k = 0; k < D; ++k) xi[k] = off.o[k] * body.spacing;
            record_pressure_bond(i, -1, off.fraction, s.cracks.size() + hi_, xi, whole_family);
            break;
          }
          continue;
        }
        bool cut = false;
        if (!cutting.empty()) {
          Point3 pj{0, 0, 0};
          for (int k = 0; k < D; ++k) pj[k] = m.reference_position[j][k];
          for (auto c : cutting) {
            if (!cracks[c].cuts(pi, pj)) continue;
            // with a fluid in the scene, a cut bond carries its crack's pressure or, for a crack
            // without one, the fluid that reaches it (hf/fluid_network.hpp)
            if (!cut && any_fluid && fill) {
              std::array<double, 3> xi{0, 0, 0};
              for (int k = 0; k < D; ++k) xi[k] = pj[k] - pi[k];
              record_pressure_bond(i, j, off.fraction, crack_of[c], xi, 0.0);
            }
            cut = true;
          }
        }
        if (cut) continue;
        if (fill && !crossing.empty()) {
          Point3 pj{0, 0, 0};
          for (int k = 0; k < D; ++k) pj[k] = m.reference_position[j][k];
          for (auto f : crossing)
            if (interfaces[f].cuts(pi, pj)) {
              across[i].push_back({static_cast<std::uint32_t>(count), static_cast<std::uint16_t>(f)});
              break;
            }
        }
        if (fill) {
          const auto k = static_cast<std::size_t>(b.offset[i] + count);
          b.neighbor[k] = j;
          b.family[k] = static_cast<std::uint16_t>(first_family + a);
        }
        ++count;
      }
      return count;
    };
    // count, make the rows' offsets, fill: the bonds go straight to their place
#pragma omp parallel for if(rift::parallel::worth_a_team(info.last - info.first)) schedule(dynamic, 256)
    for (std::size_t i = info.first; i < info.last; ++i) b.offset[i + 1] = row(i, false);
    for (std::size_t i = info.first; i < info.last; ++i) b.offset[i + 1] += b.offset[i];
    b.neighbor.resize(static_cast<std::size_t>(b.offset[info.last]));
    b.family.resize(static_cast<std::size_t>(b.offset[info.last]));
#pragma omp parallel for if(rift::parallel::worth_a_team(info.last - info.first)) schedule(dynamic, 256)
    for (std::size_t i = info.first; i < info.last; ++i) row(i, true);
    const SlabCut slabs = cut_into_slabs(b, info.first, info.last);
    info.slab_length = slabs.length, info.slab_count = slabs.count;
    make_bond_runs(b, info);
  }
  parallel_fill(b.intact.replace(), b.neighbor.size(), bond_intact);
  InterfaceBonds& ib = m.interface_bonds;
  if (!s.interfaces.empty()) {
    ib.offset.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      ib.offset[i + 1] = ib.offset[i] + static_cast<std::int64_t>(across[i].size());
      for (const auto& [q, f] : across[i]) {
        ib.slot.push_back(b.offset[i] + q);
        ib.interface.push_back(f);
      }
    }
  }
  CrackBonds& w = m.crack_bonds;
  w.offset.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) w.offset[i + 1] = w.offset[i] + static_cast<std::int64_t>(wet_nb[i].size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t q = 0; q < wet_nb[i].size(); ++q) {
      const auto j = wet_nb[i][q];
      // a fluid site has the volume of a lattice cell of the particle's body
      const double vj = j >= 0 ? m.volume[static_cast<std::size_t>(j)] : m.volume[i];
      w.neighbor.push_back(j);
      w.volume.push_back(static_cast<float>(vj * wet_frac[i][q]));
      w.source.push_back(wet_crack[i][q]);
      w.xi.push_back(wet_xi[i][q]);
      w.fluid_weighted_volume.push_back(wet_m[i][q]);
    }
  std::vector<bool> wet(s.boreholes.size(), false);
  for (auto src : w.source)
    if (src >= s.cracks.size()) wet[src - s.cracks.size()] = true;
  for (std::size_t h = 0; h < s.boreholes.size(); ++h)
    if (!wet[h])
      throw SceneError(s.boreholes[h].where, "boreholes[" + std::to_string(h) + "].region",
                       "region \"" + s.boreholes[h].region + "\" touches no material: none of its lattice sites inside a body's bounds "
                       "lies within a horizon of a particle");
}

}  // namespace

template <int D>
Model<D> discretize(const scene::Scene& s) {
  Model<D> m;
  m.thickness = D == 2 ? s.thickness : 1.0;
  std::vector<std::array<long, 3>> lattice_index;
  for (std::size_t bi = 0; bi < s.bodies.size(); ++bi) {
    const auto& b = s.bodies[bi];
    BodyInfo info;
    info.name = b.name;
    info.first = m.reference_position.size();  // m.size() counts positions, set after the loop
    info.origin = static_cast<std::int64_t>(info.first);
    info.whole_first = info.first;
    fill_body<D>(s, b, bi, m, lattice_index);
    info.last = m.reference_position.size();
    if (info.last == info.first)
      throw SceneError(b.where, "bodies." + b.name, "region \"" + b.region + "\" holds no lattice site at spacing " +
                                                        std::to_string(b.spacing) + " m; make the region larger or the spacing finer");
    info.constants = make_constants(s, s.materials[b.material], b.horizon, b.spacing);
    m.bodies.push_back(info);
  }
  if (m.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw SceneError({s.file, 0, 0}, "bodies", "more than 2^31 particles");
  m.position = m.reference_position;
  const std::size_t n = m.size();
  m.velocity.assign(n, Vec<D>{});
  m.force.assign(n, Vec<D>{});
  m.body_force.assign(n, Vec<D>{});
  m.dilatation.assign(n, 0.0);
  m.dilatation_coupling.assign(n, 0.0);
  m.damage.assign(n, 0.0);
  m.constrained.assign(n, 0);
  m.stretch_limit.resize(n);
  for (std::size_t i = 0; i < n; ++i) m.stretch_limit[i] = m.constants_of(i).critical_stretch;
  m.next_stretch_limit = m.stretch_limit;
  for (const auto& body : m.bodies)
    if (body.constants.normal_stress_failure) m.failure_strain.assign(n * stress_components<D>, 0.0);

  build_bonds<D>(s, m, lattice_index);

  const auto factor_row_owners = assign_factor_rows<D>(m);
  apply_surface_correction<D>(m, factor_row_owners);
  // weighted volume m_i = sum omega_i |xi|^2 V_j (Silling et al. 2007, eq. 21), with the particle's own
  // (surface-corrected) influence function; fixed at set-up as in LAMMPS
  m.weighted_volume.assign(n, 0.0);
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) {
      double w = 0.0;
      for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) {
        const double xi = m.bonds.length(k);
        w += m.bonds.correction(i, k) * influence(c.influence, xi, c.horizon) * xi * xi * m.bonds.volume(k);
      }
      m.weighted_volume[i] = w;
    }
  }
  compute_dilatation_weights<D>(m, factor_row_owners);
  prepare_viscous_history<D>(m, [](const BodyInfo& body) { return law_traits(body.constants.model).bond_history; });
  prepare_pressure_bonds<D>(m);
  prepare_interfaces<D>(s, m);

  for (const auto& iv : s.initial_velocities) {
    const auto selected = geometry::indices_inside<D>(geometry::Region::build(s, iv.region), n,
                                                      [&](std::size_t i) { return m.reference_position[i]; });
    for (auto i : selected)
      for (int k = 0; k < D; ++k) m.velocity[i][k] = iv.velocity[k];
    if (selected.empty())
      throw SceneError(iv.where, "initial_velocity.region", "region \"" + iv.region + "\" selects no particle");
  }
  return m;
}

template Model<2> discretize<2>(const scene::Scene&);
template Model<3> discretize<3>(const scene::Scene&);

}  // namespace rift::pd
