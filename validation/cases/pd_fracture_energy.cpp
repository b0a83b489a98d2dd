// Validation 4: numerical fracture energy. A bar is cut in two halves by the plane x = 0 and the
// right half is pulled away rigidly in small increments until every bond across the plane has
// broken. The work done, integral of the force between the halves over the opening, divided by
// the new crack area must be G0 within 10% (the critical stretch is derived from G0 for the
// continuum; the discrete lattice, partial volumes and the surface correction make the rest).
// PMB and LPS, 2D (plane stress) and 3D.
#include <cstdio>

#include "case.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

template <int D>
double separation_work_ratio(const char* model, bool quick) {
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
  text += std::string("[materials.m]\nmodel = \"") + model + "\"\ndensity = 2440.0\nyoungs_modulus = 72e9\npoisson_ratio = " +
          (D == 2 && std::string(model) == "pmb" ? "0.3333333333" : "0.25") + "\nfracture_energy = " + std::to_string(G0) +
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

}  // namespace

Result pd_fracture_energy(const Settings& settings) {
  double worst = 0.0, worst_ratio = 1.0;
  std::string details;
  for (const char* model : {"pmb", "lps"})
    for (int dim : {2, 3}) {
      const double ratio = dim == 2 ? separation_work_ratio<2>(model, settings.quick) : separation_work_ratio<3>(model, settings.quick);
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s%s%dD %.3f", details.empty() ? "" : ", ", model, dim, ratio);
      details += buf;
      if (std::abs(ratio - 1.0) > worst) worst = std::abs(ratio - 1.0), worst_ratio = ratio;
    }
  Result r;
  r.name = "pd_fracture_energy";
  r.measured = worst_ratio;
  r.reference = 1.0;
  r.tolerance = 0.1;
  r.unit = "work / (area G0), worst case";
  r.details = "G/G0: " + details;
  r.source = "G0 (Silling and Askari 2005, eq. 24)";
  r.decide();
  return r;
}

}  // namespace rift::validation
