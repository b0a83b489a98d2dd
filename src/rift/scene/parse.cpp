#include "rift/scene/parse.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "rift/core/fnv1a.hpp"
#include "rift/scene/toml_reader.hpp"

namespace rift::scene {
namespace {

using R = TomlReader;

Point3 point(R& r, const std::string& k, int dim, bool required) {
  auto v = r.numbers(k, dim);
  if (!v) {
    if (required) throw SceneError(r.where(), r.key(k), "missing required key (a point with " + std::to_string(dim) + " coordinates)");
    return {0, 0, 0};
  }
  Point3 p{0, 0, 0};
  for (int i = 0; i < dim; ++i) p[i] = (*v)[i];
  return p;
}

std::vector<Point3> point_list(R& r, const std::string& k, int dim, int min_count) {
  const toml::node* n = r.node(k);
  if (!n) throw SceneError(r.where(), r.key(k), "missing required key (a list of points)");
  const toml::array* a = n->as_array();
  if (!a) r.fail(k, "expected an array of points like [[x, y], ...], got " + R::type_name(*n));
  if (static_cast<int>(a->size()) < min_count)
    r.fail(k, "expected at least " + std::to_string(min_count) + " points, got " + std::to_string(a->size()));
  std::vector<Point3> out;
  for (const auto& e : *a) {
    auto c = r.numbers_of(e, k, dim);
    Point3 p{0, 0, 0};
    for (int i = 0; i < dim; ++i) p[i] = c[i];
    out.push_back(p);
  }
  return out;
}

TimeFunction time_function(R& parent, const std::string& k) {
  TimeFunction f;
  const toml::table* t = parent.table(k);
  if (!t) return f;
  R r(*t, parent.key(k), parent.file());
  auto kind = r.choice("function", {"constant", "ramp", "step", "table"});
  if (!kind) throw SceneError(r.where(), r.key("function"), "missing required key (constant, ramp, step or table)");
  if (*kind == "constant") {
    f.kind = TimeFunctionKind::constant;
    r.finish({"function"});
  } else if (*kind == "ramp") {
    f.kind = TimeFunctionKind::ramp;
    f.start = r.non_negative("start", r.number("start", 0.0));
    f.end = r.required_number("end", "time at which the ramp reaches 1, s");
    if (!(f.end > f.start)) r.fail("end", "must be greater than start (" + R::fmt_double(f.start) + ")");
    r.finish({"function", "start", "end"});
  } else if (*kind == "step") {
    f.kind = TimeFunctionKind::step;
    f.start = r.non_negative("start", r.required_number("start", "time of the step, s"));
    r.finish({"function", "start"});
  } else {
    f.kind = TimeFunctionKind::table;
    const toml::node* n = r.node("points");
    if (!n || !n->is_array()) throw SceneError(r.where(), r.key("points"), "missing required key (array of [time, factor] pairs)");
    for (const auto& e : *n->as_array()) {
      auto c = r.numbers_of(e, "points", 2);
      if (!f.table.empty() && !(c[0] > f.table.back()[0]))
        throw SceneError(r.at(e), r.key("points"), "times must increase strictly");
      f.table.push_back({c[0], c[1]});
    }
    if (f.table.empty()) r.fail("points", "needs at least one [time, factor] pair");
    r.finish({"function", "points"});
  }
  return f;
}

void parse_scene_table(R& root, Scene& s) {
  const toml::table* t = root.table("scene");
  if (!t) return;
  R r(*t, "scene", s.file);
  if (auto n = r.string("name")) s.name = *n;
  if (auto m = r.choice("method", {"peridynamics", "mpm"})) s.method = *m == "mpm" ? Method::mpm : Method::peridynamics;
  if (auto d = r.integer("dimension")) {
    if (*d != 2 && *d != 3) r.fail("dimension", "must be 2 or 3, got " + std::to_string(*d));
    s.dimension = static_cast<int>(*d);
  }
  if (auto p = r.choice("plane", {"stress", "strain"})) {
    if (s.dimension != 2) r.fail("plane", "only for dimension = 2");
    s.plane = *p == "stress" ? PlaneCondition::stress : PlaneCondition::strain;
  }
  if (auto th = r.number("thickness")) {
    if (s.dimension != 2) r.fail("thickness", "only for dimension = 2");
    s.thickness = r.positive("thickness", *th);
  }
  if (s.dimension == 2 && s.plane == PlaneCondition::none)
    throw SceneError(r.where(), "scene.plane", "missing required key for dimension = 2 (\"stress\" or \"strain\")");
  r.finish({"name", "method", "dimension", "plane", "thickness"});
}

/// Calls f(reader, name) for each sub-table [key.NAME]; at least one is required.
template <class F>
void for_each_named(R& root, const std::string& key, const std::string& example, const std::string& file, F&& f) {
  const toml::table* t = root.table(key);
  if (!t || t->empty()) throw SceneError(root.where(), key, "at least one is required, e.g. [" + key + "." + example + "]");
  for (const auto& [name, node] : *t) {
    const std::string path = key + "." + std::string(name.str());
    if (!node.is_table()) throw SceneError(root.at(node), path, "expected a table");
    R r(*node.as_table(), path, file);
    f(r, std::string(name.str()));
  }
}

/// A scene's warning at the key's place ("file:line:column: warning: 'key': ...", Scene::warnings).
void warn(R& r, Scene& s, const std::string& k, const std::string& msg) {
  const SourceLocation w = r.where(k);
  s.warnings.push_back(w.file + ":" + std::to_string(w.line) + ":" + std::to_string(w.column) + ": warning: '" + r.key(k) + "': " + msg);
}

/// PMB's Poisson ratio is fixed: 1/4 in 3D and plane strain, 1/3 in plane stress (Silling and
/// Askari 2005; the bond constant matches the bulk modulus, make_constants). Another one given is
/// not the material's: a warning with the Young's modulus the bonds then have.
void pmb_poisson_warning(R& r, Scene& s, const Material& m, const std::string& k) {
  const double K = m.bulk_modulus, G = m.shear_modulus;
  const double nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
  const bool stress = s.dimension == 2 && s.plane == PlaneCondition::stress;
  const double fixed = stress ? 1.0 / 3.0 : 0.25;
  if (std::abs(nu - fixed) <= 0.01) return;
  // the modulus the bonds match (material_constants.cpp) and the Young's modulus of PMB with it
  const double E = 9.0 * K * G / (3.0 * K + G);
  const double E_pmb = s.dimension == 3 ? 1.5 * K : stress ? 4.0 / 3.0 * (9.0 * K * G / (3.0 * K + 4.0 * G)) : 1.25 * (K + G / 3.0);
  warn(r, s, k,
       "PMB's Poisson ratio is " + std::string(stress ? "1/3 in plane stress" : s.dimension == 3 ? "1/4 in 3D" : "1/4 in plane strain") +
           ", not " + R::fmt_double(nu) + ": its bonds match the bulk modulus, and their Young's modulus is " + R::fmt_double(E_pmb) +
           " Pa, " + R::fmt_double(E_pmb / E) + " times the one given; use model = \"lps\" for another Poisson ratio");
}

void parse_materials(R& root, Scene& s) {
  for_each_named(root, "materials", "steel", s.file, [&](R& r, const std::string& name) {
    Material m;
    m.name = name;
    m.where = r.where();
    const bool pd = s.method == Method::peridynamics;
    const std::vector<std::string> models = pd ? std::vector<std::string>{"pmb", "lps", "ves", "eps"}
                                               : std::vector<std::string>{"linear_elastic", "neo_hookean", "j2_plasticity"};
    auto model = r.choice("model", models);
    if (!model) throw SceneError(r.where(), r.key("model"), "missing required key (" + R::join(models) + ")");
    const std::map<std::string, ModelKind> kinds{{"pmb", ModelKind::pmb}, {"lps", ModelKind::lps}, {"ves", ModelKind::ves}, {"eps", ModelKind::eps},
        {"linear_elastic", ModelKind::linear_elastic}, {"neo_hookean", ModelKind::neo_hookean}, {"j2_plasticity", ModelKind::j2_plasticity}};
    m.model = kinds.at(*model);
    m.density = r.positive("density", r.required_number("density", "mass density, kg/m^3"));
    auto E = r.number("youngs_modulus"), nu = r.number("poisson_ratio");
    auto K = r.number("bulk_modulus"), G = r.number("shear_modulus");
    if (E || nu) {
      if (K || G) r.fail(K ? "bulk_modulus" : "shear_modulus", "give either youngs_modulus + poisson_ratio or bulk_modulus + shear_modulus, not both");
      if (!E) throw SceneError(r.where(), r.key("youngs_modulus"), "missing required key (poisson_ratio is given)");
      if (!nu) throw SceneError(r.where(), r.key("poisson_ratio"), "missing required key (youngs_modulus is given)");
      r.positive("youngs_modulus", *E);
      if (!(*nu > -1.0 && *nu < 0.5)) r.fail("poisson_ratio", "must lie in (-1, 0.5), got " + R::fmt_double(*nu));
      m.bulk_modulus = *E / (3.0 * (1.0 - 2.0 * *nu));
      m.shear_modulus = *E / (2.0 * (1.0 + *nu));
    } else if (K || G) {
      if (!K) throw SceneError(r.where(), r.key("bulk_modulus"), "missing required key (shear_modulus is given)");
      if (!G) throw SceneError(r.where(), r.key("shear_modulus"), "missing required key (bulk_modulus is given)");
      m.bulk_modulus = r.positive("bulk_modulus", *K);
      m.shear_modulus = r.positive("shear_modulus", *G);
    } else {
      throw SceneError(r.where(), r.key("youngs_modulus"), "missing elastic constants: give youngs_modulus + poisson_ratio or bulk_modulus + shear_modulus");
    }
    std::vector<std::string> allowed{"model", "density", "youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus"};
    if (m.model == ModelKind::pmb) pmb_poisson_warning(r, s, m, nu ? "poisson_ratio" : "shear_modulus");
    if (pd) {
      if (auto inf = r.choice("influence", {"constant", "inverse_distance"}))
        m.influence = *inf == "constant" ? Influence::constant : Influence::inverse_distance;
      if (auto g0 = r.number("fracture_energy")) m.fracture_energy = r.positive("fracture_energy", *g0);
      if (auto s0 = r.number("critical_stretch")) {
        if (m.fracture_energy) r.fail("critical_stretch", "give fracture_energy or critical_stretch, not both");
        m.critical_stretch = r.positive("critical_stretch", *s0);
      }
      if (auto ratio = r.number("propagation_toughness_ratio")) {
        if (!m.fracture_energy) r.fail("propagation_toughness_ratio", "only with fracture_energy (it scales the critical stretch that G0 gives)");
        m.propagation_toughness_ratio = r.positive("propagation_toughness_ratio", *ratio);
      }
      m.alpha = r.non_negative("alpha", r.number("alpha", 0.0));
      if (auto f = r.choice("bond_failure", {"stretch", "normal_stress"}))
        m.bond_failure = *f == "normal_stress" ? BondFailure::normal_stress : BondFailure::stretch;
      if (auto T = r.number("tensile_strength")) {
        if (m.bond_failure != BondFailure::normal_stress) r.fail("tensile_strength", "only with bond_failure = \"normal_stress\"");
        m.tensile_strength = r.positive("tensile_strength", *T);
      }
      if (m.bond_failure == BondFailure::normal_stress) {
        if (m.model == ModelKind::pmb)
          r.fail("bond_failure", "\"normal_stress\" needs model \"lps\" or \"ves\" (a PMB bond's force is its stretch: use \"stretch\")");
        if (!m.tensile_strength) throw SceneError(r.where(), r.key("tensile_strength"), "missing required key (bond_failure = \"normal_stress\"), Pa");
        if (m.fracture_energy) r.fail("fracture_energy", "not with bond_failure = \"normal_stress\" (give tensile_strength)");
        if (m.critical_stretch) r.fail("critical_stretch", "not with bond_failure = \"normal_stress\" (give tensile_strength)");
        if (m.alpha != 0.0) r.fail("alpha", "not with bond_failure = \"normal_stress\" (compression cannot break a bond on its tension)");
      }
      if (auto sc = r.boolean("surface_correction")) m.surface_correction = *sc;
      allowed.insert(allowed.end(),
                     {"influence", "fracture_energy", "propagation_toughness_ratio", "critical_stretch", "alpha", "bond_failure",
                      "tensile_strength", "surface_correction"});
      if (m.model == ModelKind::ves) {
        // Mitchell (2011) viscoelastic state-based model, as LAMMPS peri/ves (lambda, tau)
        const double lambda = r.required_number("viscous_fraction", "lambda in [0, 1], the share of the deviatoric response that relaxes");
        if (!(lambda >= 0.0 && lambda <= 1.0)) r.fail("viscous_fraction", "must lie in [0, 1], got " + R::fmt_double(lambda));
        m.viscous_fraction = lambda;
        m.relaxation_time = r.positive("relaxation_time", r.required_number("relaxation_time", "tau, s"));
        allowed.insert(allowed.end(), {"viscous_fraction", "relaxation_time"});
      }
      if (m.model == ModelKind::eps) {
        // Mitchell (2011) elastic-plastic state-based model, as LAMMPS peri/eps
        m.yield_stress = r.positive("yield_stress", r.required_number("yield_stress", "uniaxial yield stress, Pa"));
        allowed.insert(allowed.end(), {"yield_stress"});
      }
    } else {
      if (m.model != ModelKind::linear_elastic && s.dimension == 2 && s.plane == PlaneCondition::stress)
        r.fail("model", "\"" + *model + "\" needs plane strain or 3D (plane stress is for linear_elastic)");
      if (m.model == ModelKind::j2_plasticity) {
        m.yield_stress = r.positive("yield_stress", r.required_number("yield_stress", "initial yield stress, Pa"));
        m.hardening_modulus = r.non_negative("hardening_modulus", r.number("hardening_modulus", 0.0));
        allowed.insert(allowed.end(), {"yield_stress", "hardening_modulus"});
      }
    }
    r.finish(allowed);
    s.materials.push_back(m);
  });
}

void parse_regions(R& root, Scene& s) {
  const int D = s.dimension;
  for_each_named(root, "regions", "plate", s.file, [&](R& r, const std::string& name) {
    RegionDef g;
    g.name = name;
    g.where = r.where();
    auto shape = r.choice("shape", {"box", "cylinder", "sphere", "polygon", "half_space", "union", "difference", "intersection"});
    if (!shape) throw SceneError(r.where(), r.key("shape"), "missing required key (box, cylinder, sphere, polygon, half_space, union, difference or intersection)");
    const std::string& sh = *shape;
    if (sh == "box") {
      g.shape = Shape::box;
      g.min = point(r, "min", D, true);
      g.max = point(r, "max", D, true);
      for (int k = 0; k < D; ++k)
        if (!(g.max[k] > g.min[k])) r.fail("max", "each coordinate must exceed min");
      if (D == 2) g.min[2] = -1e300, g.max[2] = 1e300;
      r.finish({"shape", "min", "max"});
    } else if (sh == "sphere") {
      g.shape = Shape::sphere;
      g.center = point(r, "center", D, true);
      g.radius = r.positive("radius", r.required_number("radius", "m"));
      r.finish({"shape", "center", "radius"});
    } else if (sh == "cylinder") {
      g.shape = Shape::cylinder;
      g.center = point(r, "center", D, true);
      g.radius = r.positive("radius", r.required_number("radius", "m"));
      if (D == 3) {
        g.axis = point(r, "axis", 3, true);
        if (norm<3>(g.axis) == 0.0) r.fail("axis", "must be a non-zero vector from the base centre to the top centre");
        r.finish({"shape", "center", "radius", "axis"});
      } else {
        r.finish({"shape", "center", "radius"});
      }
    } else if (sh == "polygon") {
      g.shape = Shape::polygon;
      for (const auto& p : point_list(r, "vertices", 2, 3)) g.vertices.push_back({p[0], p[1]});
      if (D == 3) {
        g.z_min = r.required_number("z_min", "bottom of the prism, m");
        g.z_max = r.required_number("z_max", "top of the prism, m");
        if (!(g.z_max > g.z_min)) r.fail("z_max", "must exceed z_min");
        r.finish({"shape", "vertices", "z_min", "z_max"});
      } else {
        r.finish({"shape", "vertices"});
      }
    } else if (sh == "half_space") {
      g.shape = Shape::half_space;
      g.center = point(r, "point", D, true);
      g.normal = point(r, "normal", D, true);
      if (norm<3>(g.normal) == 0.0) r.fail("normal", "must be a non-zero vector (outward normal)");
      r.finish({"shape", "point", "normal"});
    } else {
      g.shape = sh == "union" ? Shape::union_of : sh == "difference" ? Shape::difference_of : Shape::intersection_of;
      auto of = r.strings("of");
      if (!of) throw SceneError(r.where(), r.key("of"), "missing required key (list of region names)");
      if (g.shape == Shape::difference_of && of->size() < 2u) r.fail("of", "needs at least two regions (the first minus the others)");
      if (of->empty()) r.fail("of", "needs at least one region");
      g.of = *of;
      r.finish({"shape", "of"});
    }
    s.regions.push_back(g);
  });
  // children must exist and not form cycles
  for (const auto& g : s.regions)
    for (const auto& c : g.of)
      if (!s.find_region(c)) throw SceneError(g.where, "regions." + g.name + ".of", "unknown region \"" + c + "\"");
  for (const auto& g : s.regions) {
    // depth-first walk; a region reached again through its own children is a cycle
    std::function<void(const RegionDef&, int)> walk = [&](const RegionDef& cur, int depth) {
      if (depth > static_cast<int>(s.regions.size()))
        throw SceneError(g.where, "regions." + g.name + ".of", "regions refer to each other in a cycle");
      for (const auto& c : cur.of) walk(*s.find_region(c), depth + 1);
    };
    walk(g, 0);
  }
}

std::size_t material_index(const Scene& s, const std::string& name, R& r, const std::string& k) {
  for (std::size_t i = 0; i < s.materials.size(); ++i)
    if (s.materials[i].name == name) return i;
  std::vector<std::string> names;
  for (const auto& m : s.materials) names.push_back(m.name);
  r.fail(k, "unknown material \"" + name + "\"; defined: " + R::join(names));
}

void require_region(const Scene& s, R& r, const std::string& k, const std::string& name) {
  if (s.find_region(name)) return;
  std::vector<std::string> names;
  for (const auto& g : s.regions) names.push_back(g.name);
  r.fail(k, "unknown region \"" + name + "\"; defined: " + R::join(names));
}

/// A load no solid of the scene holds, or a speed no wave of it reaches, by three orders: a unit or an
/// exponent is wrong (a crack pressure of 1e30 Pa flings the particles past what the contact grid
/// numbers). Stresses against 1000 times the stiffest bulk modulus, speeds against 1000 times the
/// fastest dilatational wave speed sqrt((K + 4G/3) / rho).
double plausible_stress(R& r, const Scene& s, const std::string& k, double value) {
  double stiffest = 0.0;
  for (const auto& m : s.materials) stiffest = std::max(stiffest, m.bulk_modulus);
  if (std::abs(value) > 1e3 * stiffest)
    r.fail(k, R::fmt_double(value) + " Pa is more than 1000 times the stiffest material's bulk modulus (" + R::fmt_double(stiffest) +
                  " Pa): no solid of the scene holds it; check its unit");
  return value;
}
double plausible_speed(R& r, const Scene& s, const std::string& k, double value) {
  double fastest = 0.0;
  for (const auto& m : s.materials) fastest = std::max(fastest, std::sqrt((m.bulk_modulus + 4.0 / 3.0 * m.shear_modulus) / m.density));
  if (std::abs(value) > 1e3 * fastest)
    r.fail(k, R::fmt_double(value) + " m/s is more than 1000 times the fastest wave speed of the scene's materials (" + R::fmt_double(fastest) +
                  " m/s); check its unit");
  return value;
}

std::string required_string(R& r, const std::string& k, const std::string& meaning) {
  auto v = r.string(k);
  if (!v) throw SceneError(r.where(), r.key(k), "missing required key (" + meaning + ")");
  return *v;
}

void parse_bodies(R& root, Scene& s) {
  for_each_named(root, "bodies", "plate", s.file, [&](R& r, const std::string& name) {
    Body b;
    b.name = name;
    b.where = r.where();
    b.material = material_index(s, required_string(r, "material", "name of a material"), r, "material");
    b.region = required_string(r, "region", "name of a region");
    require_region(s, r, "region", b.region);
    if (s.method == Method::mpm) {
      if (auto n = r.integer("particles_per_cell")) {
        if (*n < 1 || *n > 8) r.fail("particles_per_cell", "must be 1 to 8 (material points per cell along each axis)");
        b.particles_per_cell = static_cast<int>(*n);
      }
      r.finish({"material", "region", "particles_per_cell"});
      s.bodies.push_back(b);
      return;
    }
    b.spacing = r.positive("spacing", r.required_number("spacing", "lattice spacing, m"));
    auto h = r.number("horizon");
    auto hl = r.number("horizon_length");
    if (h && hl) r.fail("horizon_length", "give horizon (in spacings) or horizon_length (in m), not both");
    if (!h && !hl) throw SceneError(r.where(), r.key("horizon"), "missing required key (horizon in lattice spacings, e.g. 3.015, or horizon_length in m)");
    b.horizon = h ? r.positive("horizon", *h) * b.spacing : r.positive("horizon_length", *hl);
    if (b.horizon < b.spacing)
      r.fail(h ? "horizon" : "horizon_length", "horizon must be at least one lattice spacing (" + R::fmt_double(b.spacing) + " m); 3 spacings is usual");
    if (r.has("lattice_origin")) b.lattice_origin = point(r, "lattice_origin", s.dimension, true);
    if (auto pv = r.choice("partial_volume", {"exact", "lammps"}))
      b.partial_volume = *pv == "exact" ? Body::PartialVolume::exact : Body::PartialVolume::lammps;
    r.finish({"material", "region", "spacing", "horizon", "horizon_length", "lattice_origin", "partial_volume"});
    s.bodies.push_back(b);
  });
}

/// Calls f(reader, index) for each table of the array of tables [[key]] (absent: none).
template <class F>
void for_each_entry(R& root, const std::string& key, const std::string& file, F&& f) {
  const toml::node* n = root.node(key);
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables()) root.fail(key, "expected an array of tables, written [[" + key + "]]");
  for (std::size_t i = 0; i < a->size(); ++i) {
    R r(*a->get(i)->as_table(), key + "[" + std::to_string(i) + "]", file);
    f(r, i);
  }
}

/// A crack's or interface's points: in 2D no segment of zero length, in 3D a polygon of some area.
void require_extent(R& r, const std::string& k, const std::vector<Point3>& points, int dimension) {
  if (dimension == 2) {
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      if (points[i][0] == points[i + 1][0] && points[i][1] == points[i + 1][1])
        r.fail(k, "points " + std::to_string(i) + " and " + std::to_string(i + 1) + " are the same: a segment of zero length");
    return;
  }
  Point3 area{0, 0, 0};  // twice the vector area of the polygon (a fan from its first point)
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    Point3 a, b;
    for (int q = 0; q < 3; ++q) a[q] = points[i][q] - points[0][q], b[q] = points[i + 1][q] - points[0][q];
    area[0] += a[1] * b[2] - a[2] * b[1], area[1] += a[2] * b[0] - a[0] * b[2], area[2] += a[0] * b[1] - a[1] * b[0];
  }
  if (norm<3>(area) == 0.0) r.fail(k, "the polygon has no area: its points lie on one line or coincide");
}

void parse_cracks(R& root, Scene& s) {
  for_each_entry(root, "cracks", s.file, [&](R& r, std::size_t) {
    Crack c;
    c.where = r.where();
    c.points = point_list(r, "points", s.dimension, s.dimension == 2 ? 2 : 3);  // 2D: a polyline; 3D: a planar polygon
    c.points_where = r.where("points");
    require_extent(r, "points", c.points, s.dimension);
    std::vector<std::string> allowed{"points"};
    if (s.method == Method::peridynamics) {
      c.pressure = plausible_stress(r, s, "pressure", r.non_negative("pressure", r.number("pressure", 0.0)));
      c.pressure_time = time_function(r, "time");
      allowed.insert(allowed.end(), {"pressure", "time"});
    }
    r.finish(allowed);
    s.cracks.push_back(c);
  });
}

void parse_interfaces(R& root, Scene& s) {
  for_each_entry(root, "interfaces", s.file, [&](R& r, std::size_t) {
    if (s.method != Method::peridynamics) r.fail("points", "interfaces (pre-existing fractures) are for peridynamics (method = \"peridynamics\")");
    Interface f;
    f.where = r.where();
    f.points = point_list(r, "points", s.dimension, s.dimension == 2 ? 2 : 3);
    f.points_where = r.where("points");
    require_extent(r, "points", f.points, s.dimension);
    if (s.dimension == 2 && f.points.size() != 2)
      r.fail("points", "a 2D interface is one straight segment: give its two end points");
    f.tensile_strength = r.non_negative("tensile_strength", r.required_number("tensile_strength", "normal tension at which the interface parts, Pa (below the rock's)"));
    f.cohesion = r.non_negative("cohesion", r.number("cohesion", 0.0));
    f.friction_coefficient = r.non_negative("friction_coefficient", r.required_number("friction_coefficient", "Coulomb friction coefficient mu of the interface (0.89 in Zhou et al. 2008)"));
    r.finish({"points", "tensile_strength", "cohesion", "friction_coefficient"});
    s.interfaces.push_back(f);
  });
}

void parse_boreholes(R& root, Scene& s) {
  for_each_entry(root, "boreholes", s.file, [&](R& r, std::size_t) {
    if (s.method != Method::peridynamics) r.fail("region", "boreholes are for peridynamics (method = \"peridynamics\")");
    Borehole b;
    b.where = r.where();
    b.region = required_string(r, "region", "name of the region the borehole occupies (a cylinder, a disk in 2D)");
    require_region(s, r, "region", b.region);
    b.pressure = plausible_stress(r, s, "pressure", r.non_negative("pressure", r.number("pressure", 0.0)));
    b.pressure_time = time_function(r, "time");
    if (auto p = r.number("breakdown_pressure"))
      b.breakdown_pressure = plausible_stress(r, s, "breakdown_pressure", r.non_negative("breakdown_pressure", *p));
    if (auto q = r.number("injection_rate")) {
      b.injection_rate = r.non_negative("injection_rate", *q);
      b.fluid_bulk_modulus = r.positive("fluid_bulk_modulus", r.required_number("fluid_bulk_modulus", "bulk modulus of the injected fluid, Pa"));
      b.fluid_viscosity = r.non_negative("fluid_viscosity", r.number("fluid_viscosity", 0.0));
      b.injection_system_volume = r.non_negative("injection_system_volume", r.number("injection_system_volume", 0.0));
      if (r.has("time"))
        r.fail("time", "with injection_rate the pressure follows from the injected volume; `pressure` is its value at t = 0 and takes no time function");
    } else {
      for (const char* key : {"fluid_bulk_modulus", "fluid_viscosity", "injection_system_volume"})
        if (r.has(key)) r.fail(key, "only with injection_rate (the pressure is prescribed otherwise)");
    }
    r.finish({"region", "pressure", "time", "injection_rate", "fluid_bulk_modulus", "fluid_viscosity", "injection_system_volume",
              "breakdown_pressure"});
    s.boreholes.push_back(b);
  });
}

void parse_boundaries(R& root, Scene& s) {
  const char* comp[3] = {"x", "y", "z"};
  for_each_entry(root, "boundaries", s.file, [&](R& r, std::size_t) {
    Boundary b;
    b.where = r.where();
    b.region = required_string(r, "region", "name of a region");
    require_region(s, r, "region", b.region);
    auto type = r.choice("type", {"fixed", "velocity", "displacement", "traction", "body_force"});
    if (!type) throw SceneError(r.where(), r.key("type"), "missing required key (fixed, velocity, displacement, traction or body_force)");
    const std::map<std::string, BoundaryKind> kinds{{"fixed", BoundaryKind::fixed}, {"velocity", BoundaryKind::velocity},
        {"displacement", BoundaryKind::displacement}, {"traction", BoundaryKind::traction}, {"body_force", BoundaryKind::body_force}};
    b.kind = kinds.at(*type);
    std::vector<std::string> allowed{"region", "type"};
    if (b.kind != BoundaryKind::fixed) {
      bool any = false;
      for (int k = 0; k < 3; ++k) {
        if (k >= s.dimension) continue;
        b.value[k] = r.number(comp[k]);
        if (b.value[k] && b.kind == BoundaryKind::traction) plausible_stress(r, s, comp[k], *b.value[k]);
        if (b.value[k] && b.kind == BoundaryKind::velocity) plausible_speed(r, s, comp[k], *b.value[k]);
        any = any || b.value[k].has_value();
        allowed.push_back(comp[k]);
      }
      if (!any) throw SceneError(r.where(), r.key("x"), "give at least one component (x, y" + std::string(s.dimension == 3 ? ", z" : "") + ")");
      b.time = time_function(r, "time");
      allowed.push_back("time");
    }
    if (b.kind == BoundaryKind::traction) {
      if (auto d = r.number("layer_depth")) b.layer_depth = r.positive("layer_depth", *d);
      allowed.push_back("layer_depth");
    }
    r.finish(allowed);
    s.boundaries.push_back(b);
  });
}

void parse_in_situ_stress(R& root, Scene& s) {
  const toml::table* t = root.table("in_situ_stress");
  if (!t) return;
  R r(*t, "in_situ_stress", s.file);
  if (s.method != Method::peridynamics) r.fail("sigma_H", "in-situ stress is for peridynamics (method = \"peridynamics\")");
  InSituStress& v = s.in_situ;
  v.enabled = true;
  v.where = r.where();
  const std::string unit = "far-field principal stress, Pa, compression negative";
  v.sigma_H = plausible_stress(r, s, "sigma_H", r.required_number("sigma_H", "maximum horizontal " + unit));
  v.sigma_h = plausible_stress(r, s, "sigma_h", r.required_number("sigma_h", "minimum horizontal " + unit));
  if (s.dimension == 3) v.sigma_v = plausible_stress(r, s, "sigma_v", r.required_number("sigma_v", "vertical (z) " + unit));
  else v.sigma_v = plausible_stress(r, s, "sigma_v", r.number("sigma_v", 0.0));  // out of the horizontal section: recorded, not applied
  if (auto axis = r.choice("sigma_H_axis", {"x", "y"})) v.sigma_H_axis = *axis == "x" ? 0 : 1;
  if (auto faces = r.choice("faces", {"tractions", "platens"})) v.faces = *faces == "platens" ? InSituStress::Faces::platens : InSituStress::Faces::tractions;
  if (auto n = r.count("max_iterations", 1, limits::iterations, "force evaluations of the in-situ stage"))
    v.max_iterations = static_cast<int>(*n);
  if (auto tol = r.number("tolerance")) v.tolerance = r.positive("tolerance", *tol);
  if (auto start = r.choice("start", {"reference", "uniform_strain"}))
    v.start = *start == "uniform_strain" ? InSituStress::Start::uniform_strain : InSituStress::Start::reference;
  if (auto solver = r.choice("solver", {"automatic", "conjugate_gradient", "dynamic_relaxation"}))
    v.solver = *solver == "dynamic_relaxation"   ? InSituStress::Solver::dynamic_relaxation
               : *solver == "conjugate_gradient" ? InSituStress::Solver::conjugate_gradient
                                                 : InSituStress::Solver::automatic;
  r.finish({"sigma_H", "sigma_h", "sigma_v", "sigma_H_axis", "faces", "max_iterations", "tolerance", "start", "solver"});
}

void parse_initial_velocity(R& root, Scene& s) {
  for_each_entry(root, "initial_velocity", s.file, [&](R& r, std::size_t) {
    InitialVelocity v;
    v.where = r.where();
    v.region = required_string(r, "region", "name of a region");
    require_region(s, r, "region", v.region);
    v.velocity = point(r, "velocity", s.dimension, true);
    for (int k = 0; k < s.dimension; ++k) plausible_speed(r, s, "velocity", v.velocity[k]);
    r.finish({"region", "velocity"});
    s.initial_velocities.push_back(v);
  });
}

void parse_solver(R& root, Scene& s) {
  const toml::table* t = root.table("solver");
  if (!t) throw SceneError(root.where(), "solver", "missing required table [solver] (type and end_time)");
  R r(*t, "solver", s.file);
  Solver& v = s.solver;
  auto type = r.choice("type", {"explicit", "dynamic_relaxation", "static"});
  v.kind = !type || *type == "explicit"      ? SolverKind::explicit_dynamics
           : *type == "dynamic_relaxation" ? SolverKind::dynamic_relaxation
                                           : SolverKind::static_equilibrium;
  std::vector<std::string> allowed{"type", "end_time"};
  if (v.kind == SolverKind::explicit_dynamics) {
    v.end_time = r.positive("end_time", r.required_number("end_time", "simulated time, s"));
    v.end_time_where = r.where("end_time");
    if (auto dt = r.number("time_step")) {
      v.time_step = r.positive("time_step", *dt);
      v.time_step_where = r.where("time_step");
    }
    if (auto sf = r.number("safety_factor")) {
      if (v.time_step) r.fail("safety_factor", "give time_step or safety_factor, not both");
      v.safety_factor = r.positive("safety_factor", *sf);
      if (v.safety_factor > 1.0) r.fail("safety_factor", "must be in (0, 1]; the stable time step is the limit");
    }
    allowed.insert(allowed.end(), {"time_step", "safety_factor"});
  } else {
    v.end_time = r.positive("end_time", r.number("end_time", 1.0));
    if (auto n = r.count("load_steps", 1, limits::load_steps, "load steps, each an equilibrium and a snapshot file"))
      v.load_steps = static_cast<int>(*n);
    const bool static_solver = v.kind == SolverKind::static_equilibrium;
    if (auto n = r.count("max_iterations", 1, limits::iterations,
                         static_solver ? "force evaluations of each equilibrium" : "iterations of each load step"))
      v.max_iterations = static_cast<int>(*n);
    if (auto tol = r.number("tolerance")) v.tolerance = r.positive("tolerance", *tol);
    if (static_solver) v.breaking = Solver::Breaking::at_equilibrium;
    if (auto b = r.choice("breaking", {"during", "at_equilibrium"})) {
      if (static_solver && *b == "during")
        r.fail("breaking", "the static solver breaks bonds at equilibrium only (\"at_equilibrium\", its default); "
                           "breaking during the iterations is dynamic relaxation's (type = \"dynamic_relaxation\")");
      v.breaking = *b == "at_equilibrium" ? Solver::Breaking::at_equilibrium : Solver::Breaking::during;
    }
    if (auto n = r.count("max_breaking_passes", 1, limits::iterations, "equilibria of each load step")) {
      if (v.breaking != Solver::Breaking::at_equilibrium) r.fail("max_breaking_passes", "only with breaking = \"at_equilibrium\"");
      v.max_breaking_passes = static_cast<int>(*n);
    }
    allowed.insert(allowed.end(), {"load_steps", "max_iterations", "tolerance", "breaking", "max_breaking_passes"});
  }
  if (s.method == Method::mpm && v.load_stepped())
    r.fail("type", "the material point method runs explicit dynamics; use [mpm] damping to reach a static answer");
  r.finish(allowed);
}

void parse_mpm(R& root, Scene& s) {
  const toml::table* t = root.table("mpm");
  if (s.method != Method::mpm) {
    if (t) root.fail("mpm", "only for [scene] method = \"mpm\"");
    return;
  }
  if (!t) throw SceneError(root.where(), "mpm", "missing required table [mpm] (cell_size, shape, scheme)");
  R r(*t, "mpm", s.file);
  Mpm& m = s.mpm;
  m.cell_size = r.positive("cell_size", r.required_number("cell_size", "background grid cell size, m"));
  m.cell_size_where = r.where("cell_size");
  if (auto v = r.choice("shape", {"linear", "gimp", "bspline2", "bspline3"}))
    m.shape = *v == "linear" ? Mpm::Shape::linear : *v == "gimp" ? Mpm::Shape::gimp : *v == "bspline2" ? Mpm::Shape::bspline2 : Mpm::Shape::bspline3;
  if (auto v = r.choice("scheme", {"usl", "usf", "musl"})) m.scheme = *v == "usl" ? Mpm::Scheme::usl : *v == "usf" ? Mpm::Scheme::usf : Mpm::Scheme::musl;
  if (auto v = r.choice("transfer", {"flip", "apic"})) m.transfer = *v == "flip" ? Mpm::Transfer::flip : Mpm::Transfer::apic;
  if (auto v = r.number("flip_fraction")) {
    if (m.transfer == Mpm::Transfer::apic) r.fail("flip_fraction", "only with transfer = \"flip\"");
    if (!(*v >= 0.0 && *v <= 1.0)) r.fail("flip_fraction", "must lie in [0, 1] (0 = PIC, 1 = FLIP)");
    m.flip_fraction = *v;
  }
  m.damping = r.non_negative("damping", r.number("damping", 0.0));
  if (auto v = r.choice("contact", {"none", "frictionless", "friction", "stick"}))
    m.contact = *v == "none" ? Mpm::Contact::none : *v == "frictionless" ? Mpm::Contact::frictionless
              : *v == "friction" ? Mpm::Contact::friction : Mpm::Contact::stick;
  if (auto v = r.choice("crack_contact", {"none", "frictionless", "friction"}))
    m.crack_contact = *v == "none" ? Mpm::Contact::none : *v == "frictionless" ? Mpm::Contact::frictionless : Mpm::Contact::friction;
  const bool frictional = m.contact == Mpm::Contact::friction || m.crack_contact == Mpm::Contact::friction;
  if (auto v = r.number("friction")) {
    if (!frictional) r.fail("friction", "only with contact or crack_contact = \"friction\"");
    m.friction = r.non_negative("friction", *v);
  } else if (frictional) {
    throw SceneError(r.where(), r.key("friction"), "missing required key (Coulomb coefficient) for \"friction\" contact");
  }
  if (r.has("grid_min")) m.grid_min = point(r, "grid_min", s.dimension, true);
  if (r.has("grid_max")) m.grid_max = point(r, "grid_max", s.dimension, true), m.grid_max_where = r.where("grid_max");
  if (m.grid_min.has_value() != m.grid_max.has_value()) r.fail(m.grid_min ? "grid_min" : "grid_max", "give both grid_min and grid_max");
  if (auto n = r.integer("j_contour")) {
    if (*n < 1 || *n > 50) r.fail("j_contour", "must be an integer in [1, 50] (cells from the node nearest the crack tip)");
    m.j_contour = static_cast<int>(*n);
  }
  if (auto b = r.boolean("j_area_term")) m.j_area_term = *b;
  if (auto v = r.choice("mode_partition", {"interaction_integral", "cod"}))
    m.mode_partition = *v == "cod" ? Mpm::ModePartition::cod : Mpm::ModePartition::interaction_integral;
  r.finish({"cell_size", "shape", "scheme", "transfer", "flip_fraction", "damping", "contact", "crack_contact", "friction", "grid_min",
             "grid_max", "j_contour", "j_area_term", "mode_partition"});
}

void parse_crack_growth(R& root, Scene& s) {
  const toml::table* t = root.table("crack_growth");
  if (!t) return;
  if (s.method != Method::mpm || s.dimension != 2 || s.cracks.empty())
    root.fail("crack_growth", "only for 2D method = \"mpm\" scenes with [[cracks]] (explicit crack propagation)");
  R r(*t, "crack_growth", s.file);
  CrackGrowth& g = s.crack_growth;
  g.enabled = true;
  using C = CrackGrowth::Criterion;
  if (auto v = r.choice("criterion", {"max_hoop_stress", "energy_release_rate"}))
    g.criterion = *v == "max_hoop_stress" ? C::max_hoop_stress : C::energy_release_rate;
  if (g.criterion == C::max_hoop_stress) {
    g.toughness = r.positive("toughness", r.required_number("toughness", "fracture toughness K_Ic, Pa m^0.5"));
    if (r.has("critical_energy_release_rate")) r.fail("critical_energy_release_rate", "only with criterion = \"energy_release_rate\"");
  } else {
    g.critical_energy_release_rate =
        r.positive("critical_energy_release_rate", r.required_number("critical_energy_release_rate", "critical energy release rate G_c, J/m^2"));
    if (r.has("toughness")) r.fail("toughness", "only with criterion = \"max_hoop_stress\"");
  }
  if (auto v = r.number("increment")) g.increment = r.positive("increment", *v);
  if (auto n = r.count("check_every", 1, limits::iterations, "steps between growth checks")) g.check_every = static_cast<int>(*n);
  r.finish({"criterion", "toughness", "critical_energy_release_rate", "increment", "check_every"});
}

void parse_contact(R& root, Scene& s) {
  const toml::table* t = root.table("contact");
  if (!t) return;
  if (s.method == Method::mpm) root.fail("contact", "[contact] is the peridynamic short-range contact; not for method = \"mpm\"");
  R r(*t, "contact", s.file);
  if (auto e = r.boolean("enabled")) s.contact.enabled = *e;
  if (auto d = r.number("distance")) s.contact.distance = r.positive("distance", *d);
  if (auto k = r.number("stiffness")) s.contact.stiffness = r.positive("stiffness", *k);
  r.finish({"enabled", "distance", "stiffness"});
}

const std::vector<std::string>& field_names(Method method) {
  static const std::vector<std::string> pd{"displacement", "velocity", "damage", "dilatation", "stress", "strain_energy_density",
                                            "weighted_volume", "volume", "body", "fluid_pressure"};
  static const std::vector<std::string> mpm{"displacement", "velocity", "stress", "strain_energy_density",
                                             "equivalent_plastic_strain", "volume", "body"};
  return method == Method::mpm ? mpm : pd;
}

const std::vector<std::string>& history_names(Method method) {
  static const std::vector<std::string> pd{"kinetic_energy", "strain_energy", "total_energy", "broken_bonds", "max_damage"};
  static const std::vector<std::string> mpm{"kinetic_energy", "strain_energy", "total_energy"};
  return method == Method::mpm ? mpm : pd;
}

void parse_output(R& root, Scene& s) {
  Output& o = s.output;
  if (s.method == Method::mpm) o.fields = {"displacement", "velocity", "stress"};
  else o.fields = {"displacement", "velocity", "damage", "dilatation"};
  o.history = history_names(s.method);
  const toml::table* t = root.table("output");
  if (!t) return;
  R r(*t, "output", s.file);
  if (auto n = r.count("snapshots", 1, limits::snapshots, "field snapshots, a file each")) {
    o.count = static_cast<int>(*n);
    o.count_where = r.where("snapshots");
  }
  if (auto n = r.count("history_rows", 1, limits::history_rows, "rows of history.csv")) o.history_count = static_cast<int>(*n);
  if (auto f = r.strings("fields")) {
    for (const auto& name : *f) {
      bool ok = false;
      for (const auto& a : field_names(s.method)) ok = ok || a == name;
      if (!ok) r.fail("fields", "unknown field \"" + name + "\"; allowed: " + R::join(field_names(s.method)));
    }
    o.fields = *f;
  }
  if (auto h = r.strings("history")) {
    for (const auto& name : *h) {
      bool ok = false;
      for (const auto& a : history_names(s.method)) ok = ok || a == name;
      if (!ok) r.fail("history", "unknown history quantity \"" + name + "\"; allowed: " + R::join(history_names(s.method)));
    }
    o.history = *h;
  }
  if (auto rx = r.strings("reactions")) {
    for (const auto& name : *rx) require_region(s, r, "reactions", name);
    o.reactions = *rx;
  }
  if (auto d = r.boolean("damage_image")) o.damage_image = *d;
  if (auto d = r.boolean("damage_histogram")) {
    if (s.method != Method::peridynamics) r.fail("damage_histogram", "only for peridynamics (damage is a peridynamic field)");
    o.damage_histogram = *d;
  }
  if (r.has("probes")) {
    if (s.method != Method::peridynamics) r.fail("probes", "only for peridynamics (they record damage)");
    o.probes = point_list(r, "probes", s.dimension, 1);
    o.probes_where = r.where("probes");
  }
  if (auto d = r.boolean("crack_tip_plot")) {
    if (s.method != Method::mpm) r.fail("crack_tip_plot", "only for [scene] method = \"mpm\" (explicit cracks)");
    o.crack_tip_plot = *d;
  }
  r.finish({"snapshots", "history_rows", "fields", "history", "reactions", "damage_image", "damage_histogram", "probes", "crack_tip_plot"});
}

void parse_checkpoint(R& root, Scene& s) {
  const toml::table* t = root.table("checkpoint");
  if (!t) return;
  R r(*t, "checkpoint", s.file);
  if (auto n = r.count("every_steps", 1, limits::steps, "steps, or load steps of relaxation, between checkpoints"))
    s.checkpoint.every_steps = static_cast<long>(*n);
  if (auto t = r.number("every_seconds")) s.checkpoint.every_seconds = r.positive("every_seconds", *t);
  if (auto f = r.string("file")) {
    if (f->empty()) r.fail("file", "must not be empty");
    s.checkpoint.file = *f;
    s.checkpoint.file_where = r.where("file");
  }
  r.finish({"every_steps", "every_seconds", "file"});
}

Scene parse_table(const toml::table& tbl, const std::string& file) {
  Scene s;
  s.file = file;
  R root(tbl, "", file);
  parse_scene_table(root, s);
  if (s.name.empty()) {
    auto slash = file.find_last_of('/');
    std::string base = slash == std::string::npos ? file : file.substr(slash + 1);
    s.name = base.substr(0, base.find_last_of('.'));
  }
  parse_materials(root, s);
  parse_regions(root, s);
  parse_bodies(root, s);
  parse_cracks(root, s);
  parse_boreholes(root, s);
  parse_interfaces(root, s);
  parse_boundaries(root, s);
  parse_in_situ_stress(root, s);
  parse_initial_velocity(root, s);
  parse_solver(root, s);
  parse_contact(root, s);
  parse_mpm(root, s);
  parse_crack_growth(root, s);
  parse_output(root, s);
  parse_checkpoint(root, s);
  root.finish({"scene", "materials", "regions", "bodies", "cracks", "boreholes", "interfaces", "boundaries", "in_situ_stress", "initial_velocity",
               "solver", "contact", "mpm", "crack_growth", "output", "checkpoint"});
  return s;
}

Scene parse_text(const std::string& text, const std::string& name) {
  toml::table tbl;
  try {
    tbl = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    throw SceneError({name, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column)}, "",
                     "TOML syntax: " + std::string(e.description()));
  }
  Scene s = parse_table(tbl, name);
  s.fingerprint = fnv1a(fnv_offset, text.data(), text.size());
  return s;
}

}  // namespace

Scene parse_string(const std::string& text, const std::string& name) { return parse_text(text, name); }

Scene parse_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError({path, 0, 0}, "", "is a directory; give a scene file (TOML)");
  errno = 0;
  std::ifstream in(path);
  if (!in) throw SceneError({path, 0, 0}, "", std::string("cannot open the scene file: ") + std::strerror(errno ? errno : ENOENT));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_text(ss.str(), path);
}

}  // namespace rift::scene
