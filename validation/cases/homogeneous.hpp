// Strain energy density of every particle under a homogeneous strain against linear elasticity.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

using Strain = std::array<std::array<double, 3>, 3>;

struct EnergyErrors {
  double bulk = 0.0, surface = 0.0;  // largest |W_pd / W_classical - 1|
  int bulk_count = 0, surface_count = 0;
};

/// Moves every particle to x = X + eps X.
template <int D>
void deform(pd::Model<D>& m, const Strain& eps) {
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int a = 0; a < D; ++a) {
      double u = 0;
      for (int b = 0; b < D; ++b) u += eps[a][b] * m.reference_position[i][b];
      m.position[i][a] = m.reference_position[i][a] + u;
    }
}

/// Linear elasticity's W = kappa/2 (tr eps)^2 + G |dev eps|^2, kappa the dimension's bulk modulus.
template <int D>
double classical_energy_density(const pd::MaterialConstants& c, const Strain& eps) {
  double tr = 0;
  for (int a = 0; a < D; ++a) tr += eps[a][a];
  double dev2 = 0;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      const double d = eps[a][b] - (a == b ? tr / D : 0.0);
      dev2 += d * d;
    }
  return 0.5 * c.kappa * tr * tr + c.shear_modulus * dev2;
}

/// Bulk = farther than one horizon from every face of the body's bounding box.
template <int D>
EnergyErrors energy_errors(const std::string& scene_text, const Strain& eps) {
  auto s = scene::parse_string(scene_text, "homogeneous.toml");
  auto m = pd::discretize<D>(s);
  const auto& c = m.bodies[0].constants;
  deform<D>(m, eps);
  pd::compute_forces<D>(m, nullptr);
  const double classical = classical_energy_density<D>(c, eps);
  std::array<double, 3> lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const auto& x : m.reference_position)
    for (int a = 0; a < D; ++a) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
  EnergyErrors e;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double depth = 1e9;
    for (int a = 0; a < D; ++a) depth = std::min({depth, m.reference_position[i][a] - lo[a], hi[a] - m.reference_position[i][a]});
    const double err = std::abs(pd::strain_energy_density<D>(m, i) / classical - 1.0);
    if (depth > c.horizon) {
      e.bulk = std::max(e.bulk, err);
      ++e.bulk_count;
    } else {
      e.surface = std::max(e.surface, err);
      ++e.surface_count;
    }
  }
  return e;
}

inline const Strain uniaxial_strain{{{1e-4, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
inline const Strain shear_strain{{{0, 1e-4, 0}, {1e-4, 0, 0}, {0, 0, 0}}};
inline const Strain volumetric_strain{{{1e-4, 0, 0}, {0, 1e-4, 0}, {0, 0, 1e-4}}};

/// A box of one material (spacing 1 mm; 12 mm cube in 3D, 20 mm square in 2D); `extra` is appended.
inline std::string box_scene(int dim, const std::string& model, double nu, const std::string& extra = "",
                             const std::string& size = "", double horizon = 3.015, const std::string& plane = "stress",
                             const std::string& material_extra = "", const std::string& body_extra = "") {
  std::string s = "[scene]\ndimension = " + std::to_string(dim) + "\n";
  if (dim == 2) s += "plane = \"" + plane + "\"\nthickness = 0.001\n";
  s += "[materials.m]\nmodel = \"" + model + "\"\ndensity = 2000.0\nyoungs_modulus = 1.0e9\npoisson_ratio = " + std::to_string(nu) +
       "\n" + material_extra + "\n";
  const std::string box = size.empty() ? (dim == 2 ? "max = [0.02, 0.02]" : "max = [0.012, 0.012, 0.012]") : size;
  s += "[regions.all]\nshape = \"box\"\nmin = " + std::string(dim == 2 ? "[0.0, 0.0]" : "[0.0, 0.0, 0.0]") + "\n" + box + "\n";
  s += "[bodies.b]\nmaterial = \"m\"\nregion = \"all\"\nspacing = 0.001\nhorizon = " + std::to_string(horizon) + "\n" + body_extra + "\n";
  s += extra;
  if (extra.find("[solver]") == std::string::npos) s += "\n[solver]\nend_time = 1e-6\n";
  return s;
}

}  // namespace rift::validation
