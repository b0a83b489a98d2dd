// Validation 6: Kalthoff-Winkler (examples/kalthoff_winkler.toml). Cracks start at the two notch
// tips and run at 65-72 degrees to the notch direction; the experiment gives about 70 degrees
// (Kalthoff and Winkler 1988; Kalthoff 2000). The angle is the direction, in the reference
// configuration, of the crack path: the damaged particles (damage >= 0.3) 3 to 30 mm from each tip
// (the first 3 mm are the tip's process zone), principal axis through the tip, averaged over both
// cracks. The angle grows with resolution (spacing 1 mm: 59, 0.5 mm: 64, 0.3125 mm: 66, 0.25 mm:
// 70.5 degrees); the quick version uses 0.3125 mm, the example 0.25 mm.
#include <cstdio>

#include "case.hpp"
#include "rift/fracture/crack_path.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

Result kalthoff_winkler(const Settings& settings) {
  auto s = scene::parse_file(source_path("examples/kalthoff_winkler.toml"));
  if (settings.quick) {
    for (auto& b : s.bodies) {
      b.horizon *= 0.0003125 / b.spacing;
      b.spacing = 0.0003125;
    }
  }
  run::Simulation<2> sim(s);
  sim.start();
  for (long step = 1; step <= sim.steps; ++step) sim.step();
  auto& m = sim.model;
  pd::update_damage<2>(m);
  std::vector<fracture::DamagePoint> field(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) field[i] = {m.reference_position[i][0], m.reference_position[i][1], m.damage[i]};
  // notch tips: the inner ends of the two pre-crack segments
  const auto& lower = s.cracks[0].points[1];
  const auto& upper = s.cracks[1].points[1];
  const double up = fracture::crack_direction_degrees(field, upper[0], upper[1], 0.003, 0.03, 0.3, +1);
  const double down = fracture::crack_direction_degrees(field, lower[0], lower[1], 0.003, 0.03, 0.3, -1);
  if (!settings.output_dir.empty()) {
    if (std::FILE* f = std::fopen((settings.output_dir + "/kalthoff_winkler_damage.csv").c_str(), "w")) {
      std::fprintf(f, "x,y,damage\n");
      for (const auto& p : field) std::fprintf(f, "%.6e,%.6e,%.4f\n", p.x, p.y, p.damage);
      std::fclose(f);
    }
  }
  Result r;
  r.name = "kalthoff_winkler";
  r.measured = 0.5 * (std::abs(up) + std::abs(down));
  r.reference = 68.5;
  r.tolerance = 3.5;
  r.unit = "degrees from the notch direction";
  char buf[200];
  std::snprintf(buf, sizeof buf, "upper crack %.1f, lower crack %.1f deg; spacing %g m, %zu particles, struck edge at 16.5 m/s",
                std::abs(up), std::abs(down), m.bodies[0].constants.spacing, m.size());
  r.details = buf;
  r.source = "experiment about 70 deg (Kalthoff 2000); accepted 65-72";
  r.decide();
  r.pass = r.pass && std::abs(std::abs(up) - std::abs(down)) < 5.0;
  return r;
}

}  // namespace rift::validation
