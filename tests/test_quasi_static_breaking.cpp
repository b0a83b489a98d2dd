// Load steps with bonds breaking only at equilibrium: dynamic relaxation with [solver] breaking =
// "at_equilibrium" (pd/dynamic_relaxation.hpp), and the static solver, [solver] type = "static"
// (conjugate gradients, run/simulation.hpp solve_static): quasi-static growth with no bond broken in
// the transients of a load step.
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
// equilibrium (at most two equilibria per load step: the test needs the first break only), solved by
// `type` ("dynamic_relaxation" or "static").
std::string pressurized_borehole(double pressure, int steps, const char* type = "dynamic_relaxation") {
  char text[900];
  std::snprintf(text, sizeof text,
                "[regions.block]\nshape = \"box\"\nmin = [-0.025, -0.025]\nmax = [0.025, 0.025]\n"
                "[regions.hole]\nshape = \"cylinder\"\ncenter = [0.0, 0.0]\nradius = 0.005\n"
                "[bodies.block]\nmaterial = \"rock\"\nregion = \"block\"\nspacing = 0.001\nhorizon = 3.015\n"
                "lattice_origin = [-0.0005, -0.0005]\n"
                "[[boreholes]]\nregion = \"hole\"\npressure = %.17g\ntime = { function = \"ramp\", start = 0.0, end = 1.0 }\n"
                "[solver]\ntype = \"%s\"\nload_steps = %d\nmax_iterations = 20000\ntolerance = 1e-7\nbreaking = \"at_equilibrium\"\nmax_breaking_passes = 2\n",
                pressure, type, steps);
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
double first_break_pressure() {
  const double probe_pressure = 1e6;
  double p_c = 0.0;
  {
    auto scene = rift::scene::parse_string(pressurized_borehole(probe_pressure, 1), "probe.toml");
    rift::run::Simulation<2> sim(scene);
    rift::pd::HeldBreaking<2> held(sim.model);
    rift::pd::DynamicRelaxation<2> dr(sim.model);
    const auto r = dr.relax(sim.model, sim.loads, sim.contact_ptr(), 1.0, 20000, 1e-8);
    EXPECT_TRUE(r.converged) << r.residual;
    p_c = probe_pressure * critical_stretch / largest_stretch(sim.model);
  }
  return p_c;
}

/// What a ramp of 8 load steps to 8 / 5.5 p_c gave by `type`: the largest stretch at step 5 and the
/// force evaluations of steps 1 to 5 (each iteration of relaxation evaluates the forces once).
struct Ramp {
  double stretch_at_5 = 0.0;
  long evaluations_to_5 = 0;
};

Ramp ramp_breaks_at_the_elastic_load(double p_c, const char* type) {
  const int steps = 8;
  const double final_pressure = p_c * steps / 5.5;
  auto scene = rift::scene::parse_string(pressurized_borehole(final_pressure, steps, type), "ramp.toml");
  rift::run::Simulation<2> sim(scene);
  rift::pd::DynamicRelaxation<2> dr(sim.model);
  Ramp ramp;
  for (int step = 1; step <= 6; ++step) {
    const auto r = sim.relax(dr, scene.solver, double(step) / steps);
    const auto broken = broken_bonds(sim.model);
    std::printf("%s step %d: wall pressure %.3f p_c, broken bonds %lld, equilibria %d, force evaluations %d\n", type, step, double(step) / 5.5,
                static_cast<long long>(broken), r.breaking_passes, r.iterations);
    if (step <= 5) {
      EXPECT_TRUE(r.converged) << type << " step " << step << ": residual " << r.residual;
      EXPECT_EQ(broken, 0) << type << " step " << step;
      EXPECT_EQ(r.breaking_passes, 1);
      EXPECT_LT(largest_stretch(sim.model), critical_stretch);
      ramp.evaluations_to_5 += r.iterations;
      if (step == 5) ramp.stretch_at_5 = largest_stretch(sim.model);
    } else {
      EXPECT_GT(broken, 0) << type;
      EXPECT_GT(r.breaking_passes, 1) << type;
    }
  }
  return ramp;
}

// The static solver on the same ramp: the first break at the elastic solution's load too, and up to
// it relaxation's equilibria: at step 5 (5 / 5.5 p_c) the largest stretch is 5 / 5.5 s0 (the problem
// is linear), both within 1e-3 of it (the solves' tolerance is 1e-7 of the load), the static solver
// in fewer force evaluations than relaxation's iterations.
TEST(QuasiStaticBreaking, FirstBondBreaksAtTheLoadOfTheElasticSolutionByRelaxationAndByTheStaticSolver) {
  const double p_c = first_break_pressure();
  const Ramp relaxed = ramp_breaks_at_the_elastic_load(p_c, "dynamic_relaxation");
  const Ramp solved = ramp_breaks_at_the_elastic_load(p_c, "static");
  const double expected = critical_stretch * 5.0 / 5.5;
  std::printf("step 5: largest stretch / (5/5.5 s0): relaxation %.7f, static %.7f; force evaluations of steps 1-5: %ld and %ld\n",
              relaxed.stretch_at_5 / expected, solved.stretch_at_5 / expected, relaxed.evaluations_to_5, solved.evaluations_to_5);
  EXPECT_NEAR(relaxed.stretch_at_5 / expected, 1.0, 1e-3);
  EXPECT_NEAR(solved.stretch_at_5 / expected, 1.0, 1e-3);
  EXPECT_LT(solved.evaluations_to_5, relaxed.evaluations_to_5);
}

// A stop in a later breaking pass of the static solver (a signal between its equilibria' iterations;
// here the second equilibrium of load step 6 reports a stop before it starts) leaves the load step
// unfinished in that pass (DynamicRelaxation::passes_unfinished, which its checkpoint holds): the next
// call goes on with that pass and ends where the uninterrupted load step ends, the same equilibria
// counted and the same bonds broken.
TEST(QuasiStaticBreaking, TheStaticSolverStoppedInALaterPassGoesOnWithThatPass) {
  const double p_c = first_break_pressure();
  auto scene = rift::scene::parse_string(pressurized_borehole(p_c * 8.0 / 5.5, 8, "static"), "ramp.toml");
  const double t = 6.0 / 8.0;  // the load step whose first equilibrium breaks bonds (above)
  rift::run::Simulation<2> whole(scene);
  rift::pd::DynamicRelaxation<2> whole_dr(whole.model);
  const auto uninterrupted = whole.relax(whole_dr, scene.solver, t);
  ASSERT_GT(uninterrupted.breaking_passes, 1);
  rift::run::Simulation<2> sim(scene);
  rift::pd::DynamicRelaxation<2> dr(sim.model);
  int calls = 0;
  auto equilibrium = [&] {
    if (++calls == 2) {
      rift::pd::RelaxationResult stopped;
      stopped.stopped = true;
      return stopped;
    }
    return sim.solve_static(dr, scene.solver, t);
  };
  const auto first = dr.breaking_at_equilibrium(sim.model, sim.loads, sim.contact_ptr(), scene.solver.max_breaking_passes, equilibrium);
  ASSERT_TRUE(first.stopped);
  EXPECT_TRUE(dr.passes_unfinished());
  const auto second = dr.breaking_at_equilibrium(sim.model, sim.loads, sim.contact_ptr(), scene.solver.max_breaking_passes, equilibrium);
  EXPECT_FALSE(second.stopped);
  EXPECT_FALSE(dr.passes_unfinished());
  EXPECT_EQ(second.breaking_passes, uninterrupted.breaking_passes);
  EXPECT_EQ(broken_bonds(sim.model), broken_bonds(whole.model));
  EXPECT_EQ(second.iterations, uninterrupted.iterations);
}

}  // namespace
