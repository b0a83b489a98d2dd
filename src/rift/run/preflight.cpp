#include "rift/run/preflight.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "rift/geometry/region.hpp"
#include "rift/run/checkpointing.hpp"

namespace rift::run {

namespace {

/// The first folder of `path` (itself or an ancestor) that exists; a file in the way is reported.
void require_writable_folder(const std::string& path, const SourceLocation& where, const std::string& key, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(path), ec);
  if (ec) p = fs::path(path);
  for (fs::path at = p; !at.empty(); at = at.parent_path()) {
    const auto status = fs::status(at, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status))
        throw SceneError(where, key,
                         fmt::format("{} {} {}: {} is a file, not a folder; choose another path", what, path,
                                     at == p ? "is a file" : "lies below a file", at.string()));
      if (access(at.c_str(), W_OK | X_OK) != 0)
        throw SceneError(where, key, fmt::format("{} {}: the folder {} is not writable ({}); choose another path", what, path, at.string(),
                                                 std::strerror(errno)));
      return;
    }
    if (at == at.parent_path()) break;
  }
}

/// Whether a point lies in a body's region or within `reach` of it (probed along each axis).
bool near_a_body(const Point3& p, const std::vector<geometry::Region>& bodies, int D, double reach) {
  for (const auto& body : bodies) {
    if (body.contains(p)) return true;
    for (int k = 0; k < D; ++k)
      for (const double side : {-reach, reach}) {
        Point3 q = p;
        q[k] += side;
        if (body.contains(q)) return true;
      }
  }
  return false;
}

/// Points along a 2D polyline (64 a segment) or over a 3D polygon (its fan of triangles, 45 each).
std::vector<Point3> samples_of(const std::vector<Point3>& points, int D) {
  std::vector<Point3> out;
  auto mix = [](const Point3& a, const Point3& b, const Point3& c, double u, double v) {
    Point3 p;
    for (int q = 0; q < 3; ++q) p[q] = a[q] + u * (b[q] - a[q]) + v * (c[q] - a[q]);
    return p;
  };
  if (D == 2) {
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      for (int k = 0; k <= 64; ++k) out.push_back(mix(points[i], points[i + 1], points[i + 1], k / 64.0, 0.0));
    return out;
  }
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    for (int a = 0; a <= 8; ++a)
      for (int b = 0; a + b <= 8; ++b) out.push_back(mix(points[0], points[i], points[i + 1], a / 8.0, b / 8.0));
  return out;
}

/// Cracks, interfaces and boreholes touch a body (within its horizon, or an MPM cell); no two
/// bodies stand on the same region.
void require_touching_bodies(const scene::Scene& s) {
  const int D = s.dimension;
  std::vector<geometry::Region> bodies;
  double reach = 0.0;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const auto& body = s.bodies[b];
    for (std::size_t c = 0; c < b; ++c)
      if (s.bodies[c].region == body.region)
        throw SceneError(body.where, "bodies." + body.name + ".region",
                         fmt::format("body \"{}\" stands on region \"{}\" too: two bodies cannot fill the same place", s.bodies[c].name,
                                     body.region));
    bodies.push_back(geometry::Region::build(s, body.region));
    reach = std::max(reach, s.method == scene::Method::mpm ? s.mpm.cell_size : body.horizon);
  }
  // bodies overlap nowhere: the overlap of two bounding boxes, where thicker than a lattice spacing
  // (a cell), sampled on a lattice of at most 2^15 points
  auto spacing_of = [&](const scene::Body& b) { return s.method == scene::Method::mpm ? s.mpm.cell_size / b.particles_per_cell : b.spacing; };
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    for (std::size_t c = 0; c < b; ++c) {
      Point3 lo_b, hi_b, lo_c, hi_c, lo, hi;
      bodies[b].bounds(lo_b, hi_b), bodies[c].bounds(lo_c, hi_c);
      const double thinnest = std::min(spacing_of(s.bodies[b]), spacing_of(s.bodies[c]));
      bool apart = false;
      for (int k = 0; k < D; ++k) {
        lo[k] = std::max(lo_b[k], lo_c[k]), hi[k] = std::min(hi_b[k], hi_c[k]);
        apart = apart || !(hi[k] - lo[k] > thinnest) || !std::isfinite(hi[k] - lo[k]);
      }
      if (apart) continue;
      const int n = D == 2 ? 181 : 32;
      for (int z = 0; z < (D == 3 ? n : 1); ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const int ijk[3] = {x, y, z};
            Point3 p{0, 0, 0};
            for (int q = 0; q < D; ++q) p[q] = lo[q] + (ijk[q] + 0.5) / n * (hi[q] - lo[q]);
            if (!bodies[b].contains(p) || !bodies[c].contains(p)) continue;
            const auto& body = s.bodies[b];
            throw SceneError(body.where, "bodies." + body.name + ".region",
                             fmt::format("body \"{}\" overlaps body \"{}\" (both hold {}): bodies fill places apart; cut one out of the "
                                         "other with a \"difference\" region",
                                         body.name, s.bodies[c].name,
                                         D == 2 ? fmt::format("({:.4g}, {:.4g})", p[0], p[1]) : fmt::format("({:.4g}, {:.4g}, {:.4g})", p[0], p[1], p[2])));
          }
    }
  auto require = [&](const std::vector<Point3>& points, const SourceLocation& where, const std::string& key, const char* what) {
    for (const auto& p : samples_of(points, D))
      if (near_a_body(p, bodies, D, reach)) return;
    throw SceneError(where, key, fmt::format("the {} lies outside every body (farther than {:g} m from each): it cuts nothing; check its points "
                                             "against the bodies' regions",
                                             what, reach));
  };
  for (std::size_t k = 0; k < s.cracks.size(); ++k)
    require(s.cracks[k].points, s.cracks[k].points_where, fmt::format("cracks[{}].points", k), "crack");
  for (std::size_t k = 0; k < s.interfaces.size(); ++k)
    require(s.interfaces[k].points, s.interfaces[k].points_where, fmt::format("interfaces[{}].points", k), "interface");
  for (std::size_t k = 0; k < s.boreholes.size(); ++k) {
    // the borehole's region: a lattice of points over its bounds, one of them near a body
    const auto hole = geometry::Region::build(s, s.boreholes[k].region);
    Point3 lo, hi;
    hole.bounds(lo, hi);
    bool touches = false;
    const int n = D == 2 ? 32 : 12;
    for (int z = 0; z < (D == 3 ? n : 1) && !touches; ++z)
      for (int y = 0; y < n && !touches; ++y)
        for (int x = 0; x < n && !touches; ++x) {
          const int ijk[3] = {x, y, z};
          Point3 p{0, 0, 0};
          for (int q = 0; q < D; ++q) p[q] = lo[q] + (ijk[q] + 0.5) / n * (hi[q] - lo[q]);
          touches = hole.contains(p) && near_a_body(p, bodies, D, reach);
        }
    if (!touches)
      throw SceneError(s.boreholes[k].where, fmt::format("boreholes[{}].region", k),
                       fmt::format("region \"{}\" lies outside every body: the borehole has no wall to press on", s.boreholes[k].region));
  }
}

}  // namespace

MemoryEstimate preflight(const scene::Scene& s, const PreflightOptions& o) {
  const MemoryEstimate e = estimate_memory(s);
  const double machine = machine_memory();
  const bool given = o.max_memory > 0.0;
  const double limit = given ? o.max_memory : machine * std::max(1, o.ranks);
  if (limit > 0.0 && e.bytes > limit) {
    const std::string what = s.method == scene::Method::mpm
                                 ? fmt::format("{:.3g} material points and {:.3g} grid nodes", e.particles, e.grid_nodes)
                                 : fmt::format("{:.3g} particles and {:.3g} directed bonds", e.particles, e.directed_bonds);
    const std::string key = s.method == scene::Method::mpm ? "mpm.cell_size" : "bodies." + s.bodies.front().name + ".spacing";
    const SourceLocation where = s.method == scene::Method::mpm ? s.mpm.cell_size_where : s.bodies.front().where;
    throw SceneError(where, key,
                     fmt::format("the scene holds about {}: at least {:.3g} GB, more than {} ({:.3g} GB); give a larger spacing or smaller "
                                 "bodies{}",
                                 what, e.bytes / 1e9, given ? "--max-memory" : o.ranks > 1 ? "the ranks' machines' memory" : "this machine's memory",
                                 limit / 1e9, given ? "" : ", or --max-memory where the machine that runs it has more"));
  }
  require_touching_bodies(s);
  if (!o.output_dir.empty()) {
    require_writable_folder(o.output_dir, {s.file, 0, 0}, "-o", "the output directory");
    const std::string checkpoint = checkpoint_path(s, o.output_dir, 0);
    require_writable_folder(std::filesystem::path(checkpoint).parent_path().string(), s.checkpoint.file_where.line > 0 ? s.checkpoint.file_where : SourceLocation{s.file, 0, 0}, "checkpoint.file",
                            "the checkpoint's folder");
  }
  return e;
}

}  // namespace rift::run
