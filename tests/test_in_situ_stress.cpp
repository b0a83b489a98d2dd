// In-situ stress ([in_situ_stress]): the far-field principal stresses as tractions sigma . n on the
// faces of the block, brought to equilibrium before the run with no bond allowed to break.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rift/pd/stress.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

// A 40 x 40 mm block, plane strain LPS (E = 10 GPa, nu = 0.25), under sigma_H = -10 MPa and
// sigma_h = -2 MPa. Hooke's law in plane strain gives the strain along sigma_h
//   eps_h = ((1 - nu^2) sigma_h - nu (1 + nu) sigma_H) / E = +1.25e-4,
// a tensile strain above the critical stretch 1e-4 of the material: the in-situ stage must not break
// a bond. In the middle of the block (families whole) the PD stress (pd/stress.hpp) must be the
// applied one and the strain Hooke's, within 1% of the larger principal value; sigma_H_axis = "y" turns the field by 90 degrees.
TEST(InSituStress, EquilibriumUnderTheFarFieldStressesBreaksNoBond) {
  const double E = 10e9, nu = 0.25, sigma_H = -10e6, sigma_h = -2e6;
  for (const char* axis : {"x", "y"}) {
    const std::string text = rift::test::plane_strain_rock("critical_stretch = 1e-4\n") + std::string(R"([regions.block]
shape = "box"
min = [-0.02, -0.02]
max = [0.02, 0.02]
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = -2e6
tolerance = 1e-9
sigma_H_axis = ")") + axis + R"("
[solver]
type = "dynamic_relaxation"
)";
    auto s = rift::scene::parse_string(text, "in_situ.toml");
    rift::run::Simulation<2> sim(s);
    auto& m = sim.model;
    const auto relaxed = sim.equilibrate_in_situ(s.in_situ);
    EXPECT_TRUE(relaxed.converged) << relaxed.residual;
    EXPECT_EQ(rift::pd::summarize<2>(m).broken_bonds, 0) << axis;
    EXPECT_TRUE(m.bodies[0].constants.breakable) << "the stage must give breaking back";
    const int H = std::string(axis) == "x" ? 0 : 1, h = 1 - H;
    const double eps_H = ((1 - nu * nu) * sigma_H - nu * (1 + nu) * sigma_h) / E;
    const double eps_h = ((1 - nu * nu) * sigma_h - nu * (1 + nu) * sigma_H) / E;
    ASSERT_GT(eps_h, 1e-4);
    const auto stress = rift::pd::particle_stress<2>(m);
    // strain from the displacements of the particles at +-5.5 mm, stress at the four middle ones
    double middle[2] = {0, 0}, strain[2] = {0, 0};
    int count = 0;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto& X = m.reference_position[i];
      if (std::abs(X[0]) < 0.001 && std::abs(X[1]) < 0.001) {
        middle[0] += stress[6 * i], middle[1] += stress[6 * i + 1];
        ++count;
      }
      for (int k = 0; k < 2; ++k)
        if (std::abs(std::abs(X[k]) - 0.0055) < 1e-6 && std::abs(X[1 - k]) < 0.001)
          strain[k] += (m.position[i][k] - X[k]) / (X[k] > 0 ? 0.011 : -0.011) / 2.0;
    }
    ASSERT_EQ(count, 4);
    // within 1% of the larger principal value (sigma_h and eps_h are small differences of large terms)
    EXPECT_NEAR(middle[H] / count, sigma_H, 0.01 * std::abs(sigma_H)) << axis;
    EXPECT_NEAR(middle[h] / count, sigma_h, 0.01 * std::abs(sigma_H)) << axis;
    EXPECT_NEAR(strain[H], eps_H, 0.01 * std::abs(eps_H)) << axis;
    EXPECT_NEAR(strain[h], eps_h, 0.01 * std::abs(eps_H)) << axis;
  }
}

}  // namespace
