// The cracked beams of Guo and Nairn 2006 (seed 002; ../shared/reference/guo_nairn_specimens.md):
// 100 x 24 mm, arms h = 12 mm, crack from the loaded (right) end to x = tip, left edge clamped, end
// loads on the last 2 mm of each arm, damped to rest. One run at a given cell size and crack length.
#pragma once
#include <cmath>

#include "case.hpp"
#include "rift/mpm/discretize.hpp"
#include "rift/mpm/j_integral.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

struct CrackedBeam {
  mpm::CrackTipParameters tip;
  double upper_deflection = 0.0, lower_deflection = 0.0;  // mean y-displacement of the loaded arm ends, m
  double P_upper = 0.0, P_lower = 0.0;                     // end loads per unit thickness, N/m (signed)
  std::size_t particles = 0;
  long steps = 0;
};

/// Cells of `cell` for the beam scenes: the crack (y = h) midway between grid lines, room for the
/// arms' deflection (ENF: several mm) and its overshoot.
inline void place_beam_grid(scene::Scene& s, double cell) {
  const double h = 0.012, margin = 0.015;
  s.mpm.cell_size = cell;
  const double below = std::ceil((h + margin) / cell);
  s.mpm.grid_min = Point3{-3.0 * cell, h - (below + 0.5) * cell, 0.0};
  s.mpm.grid_max = Point3{0.1 + 4.0 * cell, 2.0 * h + margin, 0.0};
}

/// Runs `scene_file` (examples/mpm_dcb.toml or a variant) with `cell` cells and the crack tip at
/// x = tip_x for `settle` seconds. The crack stays midway between grid lines.
inline CrackedBeam run_cracked_beam(const std::string& scene_file, double cell, double tip_x, double settle) {
  auto s = scene::parse_file(source_path(scene_file));
  const double h = 0.012;
  place_beam_grid(s, cell);
  s.cracks[0].points.back()[0] = tip_x;
  auto m = mpm::discretize<2>(s);
  mpm::Solver<2> solver(s, m);
  const double dt = s.solver.safety_factor * solver.stable_time_step(m);
  CrackedBeam out;
  out.steps = static_cast<long>(std::ceil(settle / dt));
  for (long k = 0; k < out.steps; ++k) solver.step(m, dt);
  const auto* upper = s.find_region("upper_arm_end");
  double up = 0, down = 0;
  int nu = 0, nd = 0;
  for (std::size_t p = 0; p < m.particles.size(); ++p) {
    const auto& x0 = m.particles.reference_position[p];
    if (x0[0] < upper->min[0]) continue;
    const double v = m.particles.position[p][1] - x0[1];
    if (x0[1] > h) up += v, ++nu;
    else down += v, ++nd;
  }
  out.upper_deflection = up / nu;
  out.lower_deflection = down / nd;
  for (const auto& b : s.boundaries) {
    if (b.region == "upper_arm_end") out.P_upper = b.value[1].value_or(0.0) * h;
    if (b.region == "lower_arm_end") out.P_lower = b.value[1].value_or(0.0) * h;
  }
  out.tip = mpm::crack_tip_parameters(m, solver, {0, mpm::TipEnd::end}, mpm::contour_of(s.mpm));
  out.particles = m.particles.size();
  return out;
}

}  // namespace rift::validation
