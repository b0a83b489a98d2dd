// Validation 2: longitudinal wave in a long bar. A 2D plane-stress strip (LPS, nu = 0.25, horizon
// 3.015 spacings) is pushed at one end with a constant velocity v0. Behind the front the bar moves at
// v0, ahead it is at rest, so the front position is x_f(t) = (1/(v0 A)) sum v_x V, whatever the
// dispersion does to the shape of the front; its speed must be the bar speed sqrt(E/rho) within 2%.
#include <cstdio>

#include "case.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

Result pd_wave_speed(const Settings& settings) {
  const double E = 72e9, rho = 2440.0, v0 = 1.0, length = 0.2, width = 0.006;
  const double spacing = settings.quick ? 0.001 : 0.0005;
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"([scene]
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = "lps"
density = %g
youngs_modulus = %g
poisson_ratio = 0.25
[regions.bar]
shape = "box"
min = [0.0, 0.0]
max = [%g, %g]
[regions.pushed]
shape = "box"
min = [0.0, 0.0]
max = [%g, %g]
[bodies.bar]
material = "glass"
region = "bar"
spacing = %g
horizon = 3.015
[[boundaries]]
region = "pushed"
type = "velocity"
x = %g
[solver]
end_time = 3.0e-5
)",
                rho, E, length, width, spacing, width, spacing, v0);
  auto s = scene::parse_string(scene, "wave_speed.toml");
  run::Simulation<2> sim(s);
  sim.start();
  auto& m = sim.model;
  const double area = width * s.thickness;
  std::vector<std::pair<double, double>> front;  // (t, x_f)
  for (long step = 1; step <= sim.steps; ++step) {
    sim.step();
    double p = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i) p += m.velocity[i][0] * m.volume[i];
    front.emplace_back(m.time, p / (v0 * area));
  }
  // speed from a straight-line fit of x_f(t) over the second half of the run
  double st = 0, sx = 0, stt = 0, stx = 0;
  int n = 0;
  for (const auto& [t, x] : front)
    if (t >= 0.5 * s.solver.end_time) st += t, sx += x, stt += t * t, stx += t * x, ++n;
  const double speed = (n * stx - st * sx) / (n * stt - st * st);
  if (!settings.output_dir.empty()) {
    if (std::FILE* f = std::fopen((settings.output_dir + "/pd_wave_speed.csv").c_str(), "w")) {
      std::fprintf(f, "time,front_position\n");
      for (const auto& [t, x] : front) std::fprintf(f, "%.6e,%.6e\n", t, x);
      std::fclose(f);
    }
  }
  Result r;
  r.name = "pd_wave_speed";
  r.measured = speed;
  r.reference = std::sqrt(E / rho);
  r.tolerance = 0.02 * r.reference;
  r.unit = "m/s";
  char buf[160];
  std::snprintf(buf, sizeof buf, "ratio %.4f; LPS plane stress strip %g x %g m, spacing %g m, horizon 3.015 spacings",
                speed / r.reference, length, width, spacing);
  r.details = buf;
  r.source = "bar speed sqrt(E/rho)";
  r.decide();
  return r;
}

}  // namespace rift::validation
