// Dynamic relaxation with bonds breaking only at equilibrium ([solver] breaking = "at_equilibrium",
// pd/dynamic_relaxation.hpp): quasi-static growth with no bond broken in the transients of a load step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/forces.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

constexpr double critical_stretch = 1e-4;

// A 50 mm square of LPS rock (E = 10 GPa, nu = 0.25, plane strain) with a 5 mm borehole whose wall
// pressure ramps from 0 at t = 0 to `pressure` at t = 1, in `steps` load steps, bonds breaking at
// equilibrium (at most two equilibria per load step: the test needs the first break only).
std::string pressurized_borehole(double pressure, int steps) {
  char text[900];
  std::snprintf(text, sizeof text,
                "[regions.block]\nshape = \"box\"\nmin = [-0.025, -0.025]\nmax = [0.025, 0.025]\n"
                "[regions.hole]\nshape = \"cylinder\"\ncenter = [0.0, 0.0]\nradius = 0.005\n"
                "[bodies.block]\nmaterial = \"rock\"\nregion = \"block\"\nspacing = 0.001\nhorizon = 3.015\n"
                "lattice_origin = [-0.0005, -0.0005]\n"
                "[[boreholes]]\nregion = \"hole\"\npressure = %.17g\ntime = { function = \"ramp\", start = 0.0, end = 1.0 }\n"
                "[solver]\ntype = \"dynamic_relaxation\"\nload_steps = %d\nmax_iterations = 20000\ntolerance = 1e-7\nbreaking = \"at_equilibrium\"\nmax_breaking_passes = 2\n",
                pressure, steps);
  char material[64];
  std::snprintf(material, sizeof material, "critical_stretch = %g\n", critical_stretch);
  return rift::test::plane_strain_rock(material) + text;
}

// Largest bond stretch |y| / |xi| - 1 over the intact bonds.
double largest_stretch(const rift::pd::Model<2>& m) {
  double largest = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) {
      if (m.bonds.intact[k] != rift::pd::bond_intact) continue;
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[k]);
      const double dx = m.position[j][0] - m.position[i][0], dy = m.position[j][1] - m.position[i][1];
      largest = std::max(largest, std::hypot(dx, dy) / m.bonds.length(k) - 1.0);
    }
  return largest;
}

std::int64_t broken_bonds(const rift::pd::Model<2>& m) { return rift::pd::summarize<2>(m).broken_bonds; }

// Until the first bond breaks the problem is linear elastic, so the wall pressure at which the most
// stretched bond reaches s0 is p_c = p1 s0 / s_max(p1), from one unbroken equilibrium at p1. With the
// ramp set so that p_c falls in the middle of load step 6 of 8, breaking at equilibrium must leave
// every bond intact through step 5 and break some in step 6 (and say so with more than one pass):
// the first break comes at the load the elastic solution gives, not earlier in a transient.
TEST(QuasiStaticBreaking, FirstBondBreaksAtTheLoadOfTheElasticSolution) {
  const double probe_pressure = 1e6;
  double p_c = 0.0;
  {
    auto scene = rift::scene::parse_string(pressurized_borehole(probe_pressure, 1), "probe.toml");
    rift::run::Simulation<2> sim(scene);
    rift::pd::HeldBreaking<2> held(sim.model);
    rift::pd::DynamicRelaxation<2> dr(sim.model);
    const auto r = dr.relax(sim.model, sim.loads, sim.contact_ptr(), 1.0, 20000, 1e-8);
    ASSERT_TRUE(r.converged) << r.residual;
    p_c = probe_pressure * critical_stretch / largest_stretch(sim.model);
  }
  const int steps = 8;
  const double final_pressure = p_c * steps / 5.5;
  auto scene = rift::scene::parse_string(pressurized_borehole(final_pressure, steps), "ramp.toml");
  rift::run::Simulation<2> sim(scene);
  rift::pd::DynamicRelaxation<2> dr(sim.model);
  for (int step = 1; step <= 6; ++step) {
    const auto r = sim.relax(dr, scene.solver, double(step) / steps);
    const auto broken = broken_bonds(sim.model);
    std::printf("step %d: wall pressure %.3f p_c, broken bonds %lld, equilibria %d\n", step, double(step) / 5.5, static_cast<long long>(broken),
                r.breaking_passes);
    if (step <= 5) {
      EXPECT_EQ(broken, 0) << "step " << step;
      EXPECT_EQ(r.breaking_passes, 1);
      EXPECT_LT(largest_stretch(sim.model), critical_stretch);
    } else {
      EXPECT_GT(broken, 0);
      EXPECT_GT(r.breaking_passes, 1);
    }
  }
}

}  // namespace
