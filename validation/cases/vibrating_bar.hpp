// A free elastic bar (0.1 x 0.02 m, plane strain, E = 1e8 Pa, nu = 0.3, rho = 1000 kg/m^3, MPM cells of
// 2.5 mm) set vibrating in its first longitudinal mode, v = v0 cos(pi x / L), v0 = 0.05 m/s, and run
// undamped: the drift of its total energy. Used by validation/cases/mpm_energy.cpp and, with a crack
// cutting it, by tests/test_mpm.cpp.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "rift/mpm/discretize.hpp"
#include "rift/mpm/energy.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

struct BarEnergy {
  double drift = 0.0;        // max |E(t)/E(0) - 1| of the time-centred energy (Solver::measure_energy)
  double plain_drift = 0.0;  // the same of the end-of-step sum
  std::size_t particles = 0;
  double time = 0.0, period = 0.0;  // run time, period of the mode 2 L / c
};

/// `tables`: more scene tables (e.g. [[cracks]]); `mpm_keys`: more [mpm] keys. Samples every 50
/// steps; `data`, when given, gets a CSV line per sample (time, kinetic, strain, total).
inline BarEnergy vibrating_bar(const std::string& tables, const std::string& mpm_keys, double step_fraction, int steps,
                               std::FILE* data = nullptr) {
  const double length = 0.1, v0 = 0.05;
  std::string scene = R"([scene]
method = "mpm"
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rubberlike]
model = "linear_elastic"
density = 1000.0
youngs_modulus = 1e8
poisson_ratio = 0.3
[regions.bar]
shape = "box"
min = [0.0, 0.0]
max = [0.1, 0.02]
[bodies.bar]
material = "rubberlike"
region = "bar"
)";
  scene += tables;
  scene += "[mpm]\ncell_size = 0.0025\n";
  scene += mpm_keys;
  scene += "[solver]\nend_time = 1.0\n";
  auto s = scene::parse_string(scene, "vibrating_bar.toml");
  auto m = mpm::discretize<2>(s);
  mpm::Solver<2> solver(s, m);
  for (std::size_t p = 0; p < m.particles.size(); ++p)
    m.particles.velocity[p] = {v0 * std::cos(3.14159265358979323846 * m.particles.position[p][0] / length), 0.0};
  const double dt = step_fraction * solver.stable_time_step(m);
  BarEnergy r;
  double total0 = 0.0;
  for (int step = 1; step <= steps; ++step) {
    const bool sample = step == 1 || step % 50 == 0;
    if (sample) solver.measure_energy();
    solver.step(m, dt);
    if (!sample) continue;
    const auto& e = solver.measured_energy();
    if (step == 1) total0 = e.kinetic + e.strain;
    r.drift = std::max(r.drift, std::abs((e.kinetic + e.strain) / total0 - 1.0));
    const auto plain = mpm::summarize<2>(m);
    r.plain_drift = std::max(r.plain_drift, std::abs((plain.kinetic + plain.strain) / total0 - 1.0));
    if (data) std::fprintf(data, "%.6e,%.6e,%.6e,%.6e\n", e.time, e.kinetic, e.strain, e.kinetic + e.strain);
  }
  r.particles = m.particles.size();
  r.time = m.time;
  r.period = 2 * length / m.bodies[0].constants.wave_speed();
  return r;
}

}  // namespace rift::validation
