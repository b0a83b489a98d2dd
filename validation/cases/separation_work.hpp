// The numerical fracture energy of a peridynamic body (validation 4, pd_fracture_energy.cpp; the
// law conformance test). A bar is cut in two halves by the plane x = 0 and the right half is pulled
// away rigidly in small increments until every bond across the plane has broken; the work done,
// the integral of the force between the halves over the opening, over the new crack area and G0.
#pragma once
#include <cstdio>
#include <string>

#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

/// Work / (area G0) of the bar of `model` (2D plane stress, 3D), with `material_extra` lines in its material.
template <int D>
double separation_work_ratio(const std::string& model, bool quick, const std::string& material_extra = "") {
  const double G0 = 100.0, spacing = 0.001;
  const int across = D == 3 ? (quick ? 10 : 16) : (quick ? 30 : 60);  // particles across the section
  const double half_length = 8 * spacing, section = across * spacing, thickness = 0.001;
  char scene[1024];
  if (D == 2)
    std::snprintf(scene, sizeof scene,
                  "[scene]\ndimension = 2\nplane = \"stress\"\nthickness = %g\n"
                  "[regions.bar]\nshape = \"box\"\nmin = [%g, 0.0]\nmax = [%g, %g]\n",
                  thickness, -half_length, half_length, section);
  else
    std::snprintf(scene, sizeof scene,
                  "[scene]\ndimension = 3\n[regions.bar]\nshape = \"box\"\nmin = [%g, 0.0, 0.0]\nmax = [%g, %g, %g]\n",
                  -half_length, half_length, section, section);
  std::string text = scene;
  text += "[materials.m]\nmodel = \"" + model + "\"\ndensity = 2440.0\nyoungs_modulus = 72e9\npoisson_ratio = " +
          (D == 2 && model == "pmb" ? "0.3333333333" : "0.25") + "\nfracture_energy = " + std::to_string(G0) + "\n" + material_extra +
          "\n[bodies.bar]\nmaterial = \"m\"\nregion = \"bar\"\nspacing = 0.001\nhorizon = 3.015\n"
          "[contact]\nenabled = false\n[solver]\nend_time = 1e-6\n";
  auto s = scene::parse_string(text, "fracture_energy.toml");
  auto m = pd::discretize<D>(s);
  const double s0 = m.bodies[0].constants.critical_stretch, horizon = m.bodies[0].constants.horizon;
  const double du = s0 * spacing / 40.0;
  double work = 0.0, previous_force = 0.0;
  for (int step = 1;; ++step) {
    const double u = step * du;
    for (std::size_t i = 0; i < m.size(); ++i)
      m.position[i][0] = m.reference_position[i][0] + (m.reference_position[i][0] > 0 ? u : 0.0);
    pd::compute_forces<D>(m, nullptr);
    double force = 0.0;  // pull needed to hold the right half: minus the bond force on it
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.reference_position[i][0] > 0) force -= m.force[i][0] * m.volume[i];
    work += 0.5 * (force + previous_force) * du;
    previous_force = force;
    if (force <= 0.0 && step > 1) break;
    if (u > 50 * s0 * horizon) break;
  }
  const double area = D == 2 ? section * thickness : section * section;
  return work / area / G0;
}

}  // namespace rift::validation
