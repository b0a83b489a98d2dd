#include "rift/run/memory_estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "rift/geometry/region.hpp"

namespace rift::run {

namespace {

constexpr double pi = 3.14159265358979323846;
// The fewest bytes a run keeps per item (lower bounds: the memory a run takes is above the estimate
// unless its counts are, and those are the bounding box's lattice and bonds, sampled and truncated).
// PD: a particle's fields (pd::Model::bytes_per_particle and its row offsets); a directed bond's
// neighbour, family and state (13.2 to 20.3 measured, bench/README.md). MPM: a point's vectors,
// scalars and two tensors; a grid node's mass and D-vectors per velocity field.
double pd_bytes_per_particle(int D) { return 8.0 * (5 * D + 7) + 5 + 16; }
constexpr double pd_bytes_per_directed_bond = 12.0;
double mpm_bytes_per_point(int D) { return 8.0 * (4 * D + 3 + 2 * D * D); }
double mpm_bytes_per_node_field(int D) { return 8.0 * (1 + 4 * D); }
// discretize.cpp's bounds: lattice sites of a body, and lattice offsets of the bodies' families
constexpr double most_lattice_sites = 2e9;
constexpr double most_family_offsets = 65536;

SourceLocation region_where(const scene::Scene& s, const std::string& name) {
  const auto* r = s.find_region(name);
  return r ? r->where : SourceLocation{s.file, 0, 0};
}

/// Sites of a lattice of `spacing` in the region's bounds (along each axis, and in all), and the
/// share of them inside it.
struct Fill {
  double along[3] = {1, 1, 1};
  double sites = 0.0, share = 0.0;
};

Fill fill_of(const scene::Scene& s, const std::string& region_name, double spacing, const SourceLocation& where, const std::string& key) {
  const bool mpm = s.method == scene::Method::mpm;
  const int D = s.dimension;
  const auto region = geometry::Region::build(s, region_name);
  Point3 lo, hi;
  region.bounds(lo, hi);
  Fill f;
  f.sites = 1.0;
  double extent[3] = {0, 0, 0};
  for (int k = 0; k < D; ++k) {
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]))
      throw SceneError(region_where(s, region_name), "regions." + region_name,
                       fmt::format("region \"{}\" is unbounded along {} (a half-space); intersect it with a box", region_name, "xyz"[k]));
    extent[k] = hi[k] - lo[k];
    f.along[k] = std::max(1.0, std::floor(extent[k] / spacing));
    f.sites *= f.along[k];
  }
  if (!(f.sites <= most_lattice_sites))
    throw SceneError(where, key,
                     fmt::format("{:.3g} {} in the bounds of region \"{}\" ({}), more than the {:g} a body holds; give {} or a smaller region",
                                 f.sites, mpm ? "material points" : "lattice sites", region_name,
                                 D == 2 ? fmt::format("{:g} x {:g} m", extent[0], extent[1])
                                        : fmt::format("{:g} x {:g} x {:g} m", extent[0], extent[1], extent[2]),
                                 most_lattice_sites, mpm ? "larger cells or fewer particles_per_cell" : "a larger spacing"));
  // the share inside: a lattice of at most 2^17 sites over the bounds, at the centres of its cells
  const int per_axis = D == 2 ? 362 : 50;
  long inside = 0, all = 0;
  int n[3] = {1, 1, 1};
  for (int k = 0; k < D; ++k) n[k] = static_cast<int>(std::min<double>(per_axis, std::max(1.0, std::floor(extent[k] / spacing))));
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const int ijk[3] = {x, y, z};
        Point3 p{0, 0, 0};
        for (int k = 0; k < D; ++k) p[k] = lo[k] + (ijk[k] + 0.5) / n[k] * extent[k];
        inside += region.contains(p) ? 1 : 0;
        ++all;
      }
  f.share = double(inside) / double(std::max(1L, all));
  return f;
}

/// Lattice offsets within a horizon of h spacings (the disk's or ball's lattice points).
double family_offsets_estimate(int D, double h) { return D == 2 ? pi * h * h : 4.0 / 3.0 * pi * h * h * h; }

/// Bonds per particle of a box of `along` lattice sites per axis: each offset within the horizon
/// counted by the share of the box's sites that have it (1 - |o_k| / n_k along each axis), so that
/// a plate thinner than the horizon has its truncated families. Past 2e7 offsets to look at, the
/// whole family (family_offsets_estimate).
double bonds_per_particle(int D, double h, const double along[3]) {
  const long r = static_cast<long>(std::floor(h));
  if (std::pow(2.0 * double(r) + 1.0, D) > 2e7) return family_offsets_estimate(D, h);
  const long rz = D == 3 ? r : 0;
  double sum = 0.0;
  for (long z = -rz; z <= rz; ++z)
    for (long y = -r; y <= r; ++y)
      for (long x = -r; x <= r; ++x) {
        if ((x == 0 && y == 0 && z == 0) || double(x * x + y * y + z * z) > h * h) continue;
        const long o[3] = {x, y, z};
        double share = 1.0;
        for (int k = 0; k < D; ++k) share *= std::max(0.0, 1.0 - double(std::abs(o[k])) / along[k]);
        sum += share;
      }
  return sum;
}

}  // namespace

MemoryEstimate estimate_memory(const scene::Scene& s) {
  const int D = s.dimension;
  MemoryEstimate e;
  double offsets_in_all = 0.0;
  for (const auto& b : s.bodies) {
    const std::string key = "bodies." + b.name;
    if (s.method == scene::Method::mpm) {
      const double spacing = s.mpm.cell_size / b.particles_per_cell;
      const Fill f = fill_of(s, b.region, spacing, s.mpm.cell_size_where, "mpm.cell_size");
      e.particles += f.sites * f.share;
      continue;
    }
    const Fill f = fill_of(s, b.region, b.spacing, b.where, key + ".spacing");
    const double h = b.horizon / b.spacing;
    const double offsets = family_offsets_estimate(D, h);
    offsets_in_all += offsets;
    // the exact bound is discretize's; past four times it the offsets alone would not fit
    if (offsets_in_all > 4.0 * most_family_offsets)
      throw SceneError(b.where, key + ".horizon",
                       fmt::format("a horizon of {:g} spacings has about {:.3g} lattice offsets, and the bodies' families hold at most {:g} "
                                   "in all; 3 to 6 spacings is usual",
                                   h, offsets, most_family_offsets));
    const double particles = f.sites * f.share;
    e.particles += particles;
    e.directed_bonds += particles * bonds_per_particle(D, h, f.along);
  }
  if (s.method == scene::Method::mpm) {
    // the grid: the bodies' bounds and three cells each side, or the scene's
    Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& b : s.bodies) {
      Point3 l, u;
      geometry::Region::build(s, b.region).bounds(l, u);
      for (int k = 0; k < D; ++k) lo[k] = std::min(lo[k], l[k]), hi[k] = std::max(hi[k], u[k]);
    }
    if (s.mpm.grid_min) lo = *s.mpm.grid_min, hi = *s.mpm.grid_max;
    e.grid_nodes = 1.0;
    for (int k = 0; k < D; ++k) e.grid_nodes *= (hi[k] - lo[k]) / s.mpm.cell_size + (s.mpm.grid_min ? 1.0 : 7.0);
    const double fields = !s.cracks.empty() ? 3.0 : s.mpm.contact != scene::Mpm::Contact::none ? double(s.bodies.size()) : 1.0;
    e.bytes = e.particles * mpm_bytes_per_point(D) + e.grid_nodes * fields * mpm_bytes_per_node_field(D);
  } else {
    e.bytes = e.particles * pd_bytes_per_particle(D) + e.directed_bonds * pd_bytes_per_directed_bond;
  }
  return e;
}

double machine_memory() {
  double bytes = 0.0;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);)
    if (line.rfind("MemTotal:", 0) == 0) bytes = 1024.0 * std::strtod(line.c_str() + 9, nullptr);  // kB
  for (const char* limit : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(limit);
    std::string text;
    if (in >> text && !text.empty() && text.find_first_not_of("0123456789") == std::string::npos) {
      const double cgroup = std::strtod(text.c_str(), nullptr);
      if (cgroup > 0.0 && (bytes == 0.0 || cgroup < bytes)) bytes = cgroup;
    }
  }
  return bytes;
}

double parse_memory_size(const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return -1.0;
  }
  std::string unit = text.substr(used);
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  const std::string units = "KMGT";
  double scale = 1.0;
  if (unit.size() == 1 && units.find(static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0])))) != std::string::npos)
    scale = std::pow(1024.0, 1.0 + double(units.find(static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0]))))));
  else if (!unit.empty())
    return -1.0;
  if (!std::isfinite(v) || !(v > 0.0)) return -1.0;
  return v * scale;
}

}  // namespace rift::run
