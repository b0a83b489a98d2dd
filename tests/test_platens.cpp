// Rigid loading platens ([in_situ_stress] faces = "platens", pd/platens.hpp): the lubricated steel
// plates of a true tri-axial frame keep each face flat, the low face on each axis held and the high
// one pushed with the in-situ stress times its area.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

constexpr double nu = 0.25, soft = 10e9, stiff = 30e9, sigma = -10e6;  // soft: rock_scene.hpp's rock

// Two unbonded 20 x 40 mm columns side by side, plane strain LPS: the tests' rock (E = 10 GPa)
// and one three times as stiff (separate bodies: no bond joins them), under sigma = -10 MPa along y
// and nothing along x.
rift::scene::Scene two_columns(const std::string& faces, const std::string& solver = "type = \"dynamic_relaxation\"\n") {
  std::string text = rift::test::plane_strain_rock() +
                     "[materials.stiff]\nmodel = \"lps\"\ndensity = 2500.0\nyoungs_modulus = 30e9\npoisson_ratio = 0.25\n";
  text += R"([regions.left]
shape = "box"
min = [-0.02, -0.02]
max = [0.0, 0.02]
[regions.right]
shape = "box"
min = [0.0, -0.02]
max = [0.02, 0.02]
[bodies.left]
material = "rock"
region = "left"
spacing = 0.001
horizon = 3.015
[bodies.right]
material = "stiff"
region = "right"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = 0.0
sigma_H_axis = "y"
tolerance = 1e-9
max_iterations = 200000
faces = ")" + faces + "\"\n[solver]\n" + solver;
  return rift::scene::parse_string(text, "platens.toml");
}

// strain eps_yy in the middle of the column about x = centre, from the displacements at y = +-5.5 mm
double column_strain(const rift::pd::Model<2>& m, double centre) {
  double strain = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& X = m.reference_position[i];
    if (std::abs(X[0] - centre) < 0.001 && std::abs(std::abs(X[1]) - 0.0055) < 1e-6) {
      strain += (m.position[i][1] - X[1]) / (X[1] > 0 ? 0.011 : -0.011);
      ++count;
    }
  }
  return strain / (count / 2);  // each pair above and below gives the strain
}

// the faces: the largest |u_y| of the bottom row (held) and the spread of u_y along the top row
// (one plate), and the top row's mean u_y
struct Faces {
  double bottom = 0.0, top_spread = 0.0, top = 0.0;
};
Faces faces_of(const rift::pd::Model<2>& m) {
  Faces f;
  double top_min = 1.0, top_max = -1.0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double u = m.position[i][1] - m.reference_position[i][1];
    if (m.reference_position[i][1] < -0.019) f.bottom = std::max(f.bottom, std::abs(u));
    if (m.reference_position[i][1] > 0.019) top_min = std::min(top_min, u), top_max = std::max(top_max, u);
  }
  f.top_spread = top_max - top_min, f.top = 0.5 * (top_min + top_max);
  return f;
}

// Columns in parallel between rigid plates share one strain, and the plate's force sigma W t
// splits as their stiffnesses: eps = sigma (1 - nu^2) W / (E1 W1 + E2 W2) = -4.6875e-4 (plane
// strain, each column free across: sigma_xx = 0), the soft column carrying sigma / 2 and the stiff
// one 3 sigma / 2 (under a uniform traction each has its own strain and the top face steps: the
// Bodies test below). Within 2% (the columns' free sides are surfaces of the PD model).
TEST(Platens, ColumnsInParallelShareTheStrainThePlatesImpose) {
  const double W = 0.04, Wi = 0.02;
  const double shared = sigma * (1 - nu * nu) * W / (soft * Wi + stiff * Wi);
  auto s = two_columns("platens");
  rift::run::Simulation<2> sim(s);
  const auto relaxed = sim.equilibrate_in_situ(s.in_situ);
  EXPECT_TRUE(relaxed.converged) << relaxed.residual;
  const auto& m = sim.model;
  EXPECT_NEAR(column_strain(m, -0.01), shared, 0.02 * std::abs(shared));
  EXPECT_NEAR(column_strain(m, 0.01), shared, 0.02 * std::abs(shared));
  // the bottom row held, the top row flat across both columns
  const Faces f = faces_of(m);
  EXPECT_EQ(f.bottom, 0.0);
  EXPECT_LT(f.top_spread, 1e-15);
  EXPECT_LT(f.top, 0.0);
}

// The same columns under a uniform traction (faces = "tractions"): each has its own strain, sigma
// (1 - nu^2) / E_i = -9.375e-4 and -3.125e-4, within 2%. Each body keeps its particles and its
// material: every body's particle range started at 0 before (discretize.cpp read the particle count
// off the positions, filled only after the loop), so the last body's kernels ran over every
// particle with its constants and both columns took the right one's strain.
TEST(Bodies, EachBodyKeepsItsParticlesAndItsMaterial) {
  auto s = two_columns("tractions");
  rift::run::Simulation<2> sim(s);
  ASSERT_EQ(sim.model.bodies.size(), 2u);
  EXPECT_EQ(sim.model.bodies[1].first, sim.model.bodies[0].last);
  EXPECT_TRUE(sim.equilibrate_in_situ(s.in_situ).converged);
  const double soft_strain = sigma * (1 - nu * nu) / soft, stiff_strain = sigma * (1 - nu * nu) / stiff;
  EXPECT_NEAR(column_strain(sim.model, -0.01), soft_strain, 0.02 * std::abs(soft_strain));
  EXPECT_NEAR(column_strain(sim.model, 0.01), stiff_strain, 0.02 * std::abs(stiff_strain));
}

// In explicit dynamics a plate moves its face as one body too: from the platen equilibrium, a few
// hundred velocity-Verlet steps keep the top row flat and the bottom row still, and the columns
// (at rest in equilibrium) keep their shared strain to 0.1%.
TEST(Platens, ExplicitStepsMoveTheFaceAsOne) {
  auto s = two_columns("platens", "type = \"explicit\"\nend_time = 1e-5\n");
  rift::run::Simulation<2> sim(s);
  ASSERT_TRUE(sim.equilibrate_in_situ(s.in_situ).converged);
  auto& m = sim.model;
  const double before = column_strain(m, -0.01);
  for (int step = 0; step < 300; ++step) sim.step();
  const Faces f = faces_of(m);
  EXPECT_EQ(f.bottom, 0.0);
  EXPECT_LT(f.top_spread, 1e-15);
  EXPECT_NEAR(column_strain(m, -0.01), before, 1e-3 * std::abs(before));
}

}  // namespace
