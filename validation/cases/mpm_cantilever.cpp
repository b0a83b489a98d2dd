// MPM check of the whole static chain (grid clamp, body force, damping): the tip deflection of the
// cantilever of examples/mpm_cantilever.toml against Timoshenko beam theory,
//   w = q L^4 / (8 E I) + q L^2 / (2 kappa G A),  kappa = 5/6, within 3%.
// The quick version uses 2 mm cells (5 across the beam) instead of 1 mm.
#include <cstdio>

#include "case.hpp"
#include "rift/mpm/discretize.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

Result mpm_cantilever(const Settings& settings) {
  auto s = scene::parse_file(source_path("examples/mpm_cantilever.toml"));
  if (settings.quick) s.mpm.cell_size = 0.002;
  auto m = mpm::discretize<2>(s);
  mpm::Solver<2> solver(s, m);
  const double dt = s.solver.safety_factor * solver.stable_time_step(m);
  const long steps = static_cast<long>(std::ceil(s.solver.end_time / dt));
  for (long k = 0; k < steps; ++k) solver.step(m, dt);
  const auto* beam = s.find_region("beam");
  const double L = beam->max[0] - beam->min[0], H = beam->max[1] - beam->min[1], t = s.thickness;
  const auto& mat = s.materials[0];
  const double q = -*s.boundaries[1].value[1] * H * t, I = t * H * H * H / 12.0;
  const double expected = q * std::pow(L, 4) / (8 * mat.youngs_modulus() * I) + q * L * L / (2 * 5.0 / 6.0 * mat.shear_modulus * H * t);
  // mean deflection of the points in the last cell of the beam
  double sum = 0.0;
  int count = 0;
  for (std::size_t p = 0; p < m.particles.size(); ++p)
    if (m.particles.reference_position[p][0] > beam->max[0] - s.mpm.cell_size)
      sum += m.particles.reference_position[p][1] - m.particles.position[p][1], ++count;
  Result r;
  r.name = "mpm_cantilever";
  r.measured = sum / count / expected;
  r.reference = 1.0;
  r.tolerance = 0.03;
  r.unit = "tip deflection / Timoshenko beam theory";
  char buf[200];
  std::snprintf(buf, sizeof buf, "tip %.4g m vs %.4g m; cells %g m, %zu points, %ld steps with damping %g 1/s", sum / count, expected,
                s.mpm.cell_size, m.particles.size(), steps, s.mpm.damping);
  r.details = buf;
  r.source = "Timoshenko beam theory (shear coefficient 5/6)";
  r.decide();
  return r;
}

}  // namespace rift::validation
