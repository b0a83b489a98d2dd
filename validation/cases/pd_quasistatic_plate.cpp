// Validation 5: quasi-static plate in tension by adaptive dynamic relaxation (Kilic and Madenci
// 2010). A free 2D plane-stress plate (LPS, nu = 0.3) is pulled by equal tractions sigma on its two
// ends. In the interior the stress is uniaxial: the stretch between two points on the centre line
// is sigma L / E and the contraction between two points across is -nu sigma H / E; both within 2%.
#include <cstdio>

#include "case.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

Result pd_quasistatic_plate(const Settings& settings) {
  const double E = 70e9, nu = 0.3, sigma = 20e6, length = 0.1, height = 0.05;
  const double spacing = settings.quick ? 0.001 : 0.0005;
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"([scene]
dimension = 2
plane = "stress"
thickness = 0.002
[materials.aluminium]
model = "lps"
density = 2700.0
youngs_modulus = %g
poisson_ratio = %g
[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [%g, %g]
[regions.left]
shape = "box"
min = [0.0, 0.0]
max = [%g, %g]
[regions.right]
shape = "box"
min = [%g, 0.0]
max = [%g, %g]
[bodies.plate]
material = "aluminium"
region = "plate"
spacing = %g
horizon = 3.015
[[boundaries]]
region = "left"
type = "traction"
x = %g
[[boundaries]]
region = "right"
type = "traction"
x = %g
[solver]
type = "dynamic_relaxation"
tolerance = 1e-7
max_iterations = 100000
)",
                E, nu, length, height, spacing, height, length - spacing, length, height, spacing, -sigma, sigma);
  auto s = scene::parse_string(scene, "quasistatic_plate.toml");
  run::Simulation<2> sim(s);
  auto& m = sim.model;
  pd::DynamicRelaxation<2> dr(m);
  auto relax = dr.relax(m, sim.loads, sim.contact_ptr(), s.solver.end_time, s.solver.max_iterations, s.solver.tolerance);
  // displacement at the particle nearest a point
  auto u_at = [&](double x, double y, int k) {
    std::size_t best = 0;
    double d2 = 1e300;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const double d = std::pow(m.reference_position[i][0] - x, 2) + std::pow(m.reference_position[i][1] - y, 2);
      if (d < d2) d2 = d, best = i;
    }
    return std::pair{m.position[best][k] - m.reference_position[best][k], m.reference_position[best][k]};
  };
  auto [ua, xa] = u_at(0.25 * length, 0.5 * height, 0);
  auto [ub, xb] = u_at(0.75 * length, 0.5 * height, 0);
  auto [va, ya] = u_at(0.5 * length, 0.2 * height, 1);
  auto [vb, yb] = u_at(0.5 * length, 0.8 * height, 1);
  const double stretch_error = (ub - ua) / (sigma * (xb - xa) / E) - 1.0;
  const double contraction_error = (vb - va) / (-nu * sigma * (yb - ya) / E) - 1.0;
  Result r;
  r.name = "pd_quasistatic_plate";
  r.measured = std::abs(stretch_error) > std::abs(contraction_error) ? stretch_error : contraction_error;
  r.reference = 0.0;
  r.tolerance = 0.02;
  r.unit = "relative displacement error (worst)";
  char buf[200];
  std::snprintf(buf, sizeof buf, "axial %+.4f, lateral %+.4f; %d ADR iterations, residual %.1e%s", stretch_error, contraction_error,
                relax.iterations, relax.residual, relax.converged ? "" : " (NOT converged)");
  r.details = buf;
  r.source = "uniaxial stress: u = sigma x / E, v = -nu sigma y / E";
  r.decide();
  r.pass = r.pass && relax.converged;
  return r;
}

}  // namespace rift::validation
