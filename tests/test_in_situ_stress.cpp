// In-situ stress ([in_situ_stress]): the far-field principal stresses as tractions sigma . n on the
// faces of the block, brought to equilibrium before the run with no bond allowed to break.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rift/pd/forces.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/geomech/in_situ_strain.hpp"
#include "rift/pd/stress.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "dense_stiffness.hpp"
#include "rock_scene.hpp"

namespace {

// The 40 x 40 mm block (or 2 half_size across), 1 mm spacing, under sigma_H = -10 MPa and
// sigma_h = -2 MPa, relaxed to 1e-9; material_keys go to the rock, in_situ_keys to [in_situ_stress].
std::string block_scene(const std::string& material_keys, const std::string& in_situ_keys, double half_size = 0.02) {
  const std::string h = std::to_string(half_size);
  return rift::test::plane_strain_rock(material_keys) + "[regions.block]\nshape = \"box\"\nmin = [-" + h + ", -" + h + "]\nmax = [" + h +
         ", " + h + "]\n" + R"([bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = -2e6
tolerance = 1e-9
)" + in_situ_keys + R"([solver]
type = "dynamic_relaxation"
)";
}

// A 40 x 40 mm block, plane strain LPS (E = 10 GPa, nu = 0.25), under sigma_H = -10 MPa and
// sigma_h = -2 MPa. Hooke's law in plane strain gives the strain along sigma_h
//   eps_h = ((1 - nu^2) sigma_h - nu (1 + nu) sigma_H) / E = +1.25e-4,
// a tensile strain above the critical stretch 1e-4 of the material: the in-situ stage must not break
// a bond. In the middle of the block (families whole) the PD stress (pd/stress.hpp) must be the
// applied one and the strain Hooke's, within 1% of the larger principal value; sigma_H_axis = "y" turns the field by 90 degrees.
TEST(InSituStress, EquilibriumUnderTheFarFieldStressesBreaksNoBond) {
  const double E = 10e9, nu = 0.25, sigma_H = -10e6, sigma_h = -2e6;
  for (const char* axis : {"x", "y"}) {
    const std::string text = block_scene("critical_stretch = 1e-4\n", std::string("sigma_H_axis = \"") + axis + "\"\n");
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

// A block held by tractions alone has its equilibrium only up to a rigid motion, and a compressed
// free body's rotation has a negative geometric stiffness under dead loads (a face's force keeps its
// direction while its point turns): turned by 0.02 rad before the stage, the loads leave a torque no
// deformation can carry, and dynamic relaxation must move the block with the forces less their
// rigid part (pd/dynamic_relaxation.cpp, rigid_acceleration). It converges, keeps the turn (no rigid
// motion added: the block's centre stays put to 1e-9 m, the turn to 1e-5 rad, a hundredth of the
// strain), and the strain along the turned axes is Hooke's within 1% of the larger one, as in the
// unturned block above.
TEST(InSituStress, AFreeBlockTurnedBeforeTheStageReachesTheSameEquilibrium) {
  const double E = 10e9, nu = 0.25, sigma_H = -10e6, sigma_h = -2e6, turn = 0.02;
  const std::string text = block_scene("", "");
  auto s = rift::scene::parse_string(text, "in_situ_turned.toml");
  rift::run::Simulation<2> sim(s);
  auto& m = sim.model;
  const double c = std::cos(turn), sn = std::sin(turn);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto X = m.reference_position[i];
    m.position[i] = {c * X[0] - sn * X[1], sn * X[0] + c * X[1]};
  }
  const auto relaxed = sim.equilibrate_in_situ(s.in_situ);
  ASSERT_TRUE(relaxed.converged) << relaxed.residual << " after " << relaxed.iterations << " iterations";
  // the turn of the particles at (+-5.5 mm, 0.5 mm) and (0.5 mm, +-5.5 mm), the strain
  // from their distance, and the centre of the block
  auto near = [&](double x, double y) {
    for (std::size_t i = 0; i < m.size(); ++i)
      if (std::abs(m.reference_position[i][0] - x) < 1e-6 && std::abs(m.reference_position[i][1] - y) < 1e-6) return i;
    return m.size();
  };
  const std::size_t east = near(0.0055, 0.0005), west = near(-0.0055, 0.0005), north = near(0.0005, 0.0055), south = near(0.0005, -0.0055);
  ASSERT_LT(std::max({east, west, north, south}), m.size());
  using rift::operator-;
  const auto along_x = m.position[east] - m.position[west], along_y = m.position[north] - m.position[south];
  const double eps_H = ((1 - nu * nu) * sigma_H - nu * (1 + nu) * sigma_h) / E;
  const double eps_h = ((1 - nu * nu) * sigma_h - nu * (1 + nu) * sigma_H) / E;
  EXPECT_NEAR(rift::norm<2>(along_x) / 0.011 - 1.0, eps_H, 0.01 * std::abs(eps_H));
  EXPECT_NEAR(rift::norm<2>(along_y) / 0.011 - 1.0, eps_h, 0.01 * std::abs(eps_H));
  EXPECT_NEAR(std::atan2(along_x[1], along_x[0]), turn, 1e-5);
  double centre[2] = {0, 0};
  for (const auto& x : m.position)
    for (int k = 0; k < 2; ++k) centre[k] += x[k] / double(m.size());
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(centre[k], 0.0, 1e-9);
}

// start = "uniform_strain" (pd/in_situ_strain.hpp) starts the relaxation from Hooke's strain of the
// far-field stresses: for the block above (plane strain, E = 10 GPa, nu = 0.25) the strains of the
// formulas above to 1e-12, and the stage reaches the equilibrium it reaches from the reference
// lattice (the strain between the particles at +-5.5 mm the same within 1e-3 of eps_H, both relaxed
// to 1e-9) in fewer iterations.
TEST(InSituStress, UniformStrainStartReachesTheSameEquilibriumSooner) {
  const double E = 10e9, nu = 0.25, sigma_H = -10e6, sigma_h = -2e6;
  const double eps_H = ((1 - nu * nu) * sigma_H - nu * (1 + nu) * sigma_h) / E;
  const double eps_h = ((1 - nu * nu) * sigma_h - nu * (1 + nu) * sigma_H) / E;
  double strain[2][2] = {};
  int iterations[2] = {};
  for (int start = 0; start < 2; ++start) {
    auto s = rift::scene::parse_string(block_scene("", start ? "start = \"uniform_strain\"\n" : ""), "in_situ_start.toml");
    rift::run::Simulation<2> sim(s);
    auto& m = sim.model;
    if (start) {
      const auto eps = rift::geomech::in_situ_strain<2>(m.bodies[0].constants, s.in_situ);
      EXPECT_NEAR(eps[0], eps_H, 1e-12 * std::abs(eps_H));
      EXPECT_NEAR(eps[1], eps_h, 1e-12 * std::abs(eps_H));
    }
    const auto relaxed = sim.equilibrate_in_situ(s.in_situ);
    ASSERT_TRUE(relaxed.converged) << relaxed.residual;
    iterations[start] = relaxed.iterations;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto& X = m.reference_position[i];
      for (int k = 0; k < 2; ++k)
        if (std::abs(std::abs(X[k]) - 0.0055) < 1e-6 && std::abs(X[1 - k]) < 0.001)
          strain[start][k] += (m.position[i][k] - X[k]) / (X[k] > 0 ? 0.011 : -0.011) / 2.0;
    }
  }
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(strain[1][k], strain[0][k], 1e-3 * std::abs(eps_H)) << k;
  EXPECT_NEAR(strain[1][0], eps_H, 0.01 * std::abs(eps_H));
  EXPECT_LT(iterations[1], iterations[0]);
  std::printf("in-situ stage of the 40 mm block: %d iterations from the reference, %d from the uniform strain\n", iterations[0], iterations[1]);
}

// The in-situ stage measures its fictitious density (pd/dynamic_relaxation.cpp): the largest
// eigenvalue mu of the stiffness over the row-sum bound of Kilic and Madenci's eq. 10, by power
// iteration on the forces, and 1.25 mu / 4 times that bound. Here mu is checked against the dense
// generalized eigenproblem K v = mu B v, K the stiffness (volume times the force density's
// derivative, by central differences of the forces) and B the bound times the volume, within 1%,
// on a 2D LPS block (12 x 12 mm) and a 3D VES cube (6^3, the thesis example's material) at
// their in-situ strain.
template <int D>
void check_measured_density(const std::string& text) {
  auto s = rift::scene::parse_string(text, "density.toml");
  rift::run::Simulation<D> sim(s);
  auto& m = sim.model;
  rift::pd::HeldBreaking<D> held(m);
  rift::geomech::apply_in_situ_strain<D>(m, s.in_situ);
  rift::pd::DynamicRelaxation<D> dr(m);
  const std::size_t n = m.size(), N = n * D;
  std::vector<double> bound(n);
  for (std::size_t i = 0; i < n; ++i) bound[i] = dr.fictitious_density()[i] / rift::pd::row_sum_factor;
  const auto start = m.position;
  const Eigen::MatrixXd K = rift::test::dense_stiffness<D>(m, 1e-9);  // a millionth of the spacing
  const double asymmetry = (K - K.transpose()).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
  EXPECT_LT(asymmetry, 1e-5);  // a hyperelastic model's stiffness is symmetric
  const Eigen::MatrixXd A = 0.5 * (K + K.transpose());
  Eigen::VectorXd B(static_cast<Eigen::Index>(N));
  for (std::size_t r = 0; r < N; ++r) B[static_cast<Eigen::Index>(r)] = m.volume[r / D] * bound[r / D];
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(A, Eigen::MatrixXd(B.asDiagonal()));
  const double dense = eigen.eigenvalues().maxCoeff();
  const double factor = dr.measure_fictitious_density(m, sim.loads, nullptr, 0.0);
  const double measured = 4.0 * factor / 1.25;
  std::printf("%dD: mu %.5g by power iteration, %.5g dense; fictitious density %.3g times the bound (%.3g before)\n", D, measured, dense,
              factor, rift::pd::row_sum_factor);
  EXPECT_NEAR(measured, dense, 0.01 * dense);
  EXPECT_LE(measured, dense * (1 + 1e-6));  // power iteration approaches it from below
  for (std::size_t i = 0; i < n; ++i) EXPECT_DOUBLE_EQ(dr.fictitious_density()[i], factor * bound[i]);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(m.position[i], start[i]);
}

TEST(InSituStress, MeasuredFictitiousDensityIsTheStiffnessLargestEigenvalue) {
  check_measured_density<2>(block_scene("", "", 0.006));
  check_measured_density<3>(R"([scene]
dimension = 3
[materials.shale]
model = "ves"
density = 2500.0
bulk_modulus = 10.6e9
shear_modulus = 1.0e9
critical_stretch = 5e-4
viscous_fraction = 0.5
relaxation_time = 1e-4
surface_correction = false
[regions.cube]
shape = "box"
min = [-0.003, -0.003, -0.003]
max = [0.003, 0.003, 0.003]
[bodies.cube]
material = "shale"
region = "cube"
spacing = 0.001
horizon = 3.0
partial_volume = "lammps"
[in_situ_stress]
sigma_v = -1.5e6
sigma_H = -1.0e6
sigma_h = -0.75e6
[solver]
type = "dynamic_relaxation"
)");
}

}  // namespace
