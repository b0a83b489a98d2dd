// Momentum drift of a free body given random velocities that break bonds (validation 3).
#pragma once
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "homogeneous.hpp"
#include "rift/load/boundary.hpp"
#include "rift/pd/velocity_verlet.hpp"

namespace rift::validation {

/// Largest change of a momentum component over `steps` velocity-Verlet steps, relative to
/// sum m |v| (angular momentum divided by the body size too); 1 if no bond broke. `material_extra`:
/// the lines a law needs in its material beyond the elastic constants.
template <int D>
double momentum_drift(const std::string& model, int steps, const std::string& material_extra = "") {
  auto s = scene::parse_string(box_scene(D, model, 0.25, "", "", 3.015, "strain", "critical_stretch = 0.002\n" + material_extra), "m.toml");
  auto m = pd::discretize<D>(s);
  load::Boundaries<D> loads(s, m);
  pd::Contact<D> contact(s.contact, m);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 5.0);
  for (auto& v : m.velocity)
    for (auto& c : v) c = g(rng);
  auto totals = [&](std::array<double, 6>& out, double& scale) {
    out.fill(0.0);
    scale = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const double mass = m.constants_of(i).density * m.volume[i];
      std::array<double, 3> x{0, 0, 0}, v{0, 0, 0};
      for (int k = 0; k < D; ++k) x[k] = m.position[i][k], v[k] = m.velocity[i][k];
      for (int k = 0; k < 3; ++k) out[k] += mass * v[k];
      out[3] += mass * (x[1] * v[2] - x[2] * v[1]);
      out[4] += mass * (x[2] * v[0] - x[0] * v[2]);
      out[5] += mass * (x[0] * v[1] - x[1] * v[0]);
      scale += mass * std::sqrt(dot<D>(m.velocity[i], m.velocity[i]));
    }
  };
  std::array<double, 6> before, after;
  double scale;
  totals(before, scale);
  const double dt = 0.5 * pd::stable_time_step<D>(m);
  pd::compute_forces<D>(m, &contact);
  for (int step = 0; step < steps; ++step) pd::velocity_verlet_step<D>(m, loads, &contact, dt);
  totals(after, scale);
  const double length = 0.02;
  double drift = 0.0;
  for (int k = 0; k < 6; ++k) drift = std::max(drift, std::abs(after[k] - before[k]) / (scale * (k < 3 ? 1.0 : length)));
  if (pd::summarize<D>(m).broken_bonds == 0) drift = 1.0;  // the case must exercise bond breaking
  return drift;
}

}  // namespace rift::validation
