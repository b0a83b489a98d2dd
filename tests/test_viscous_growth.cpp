// The viscous fluid (pd/viscous_fluid.hpp) driving a crack: minutes, so labelled slow.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

// A crack grown by the fluid out of a notch (a 10 mm dry pre-crack through the borehole, which
// shares the borehole's pressure) in a rock that breaks (G0 = 50 J/m^2, K_Ic = 0.73 MPa m^0.5),
// Q = 1.5e-9 m^3/s (1.5e-6 m^2/s), K_f = 2.2 GPa, 1 mm spacing, relaxed at 0.1 s steps to 0.4 s, breaking at
// equilibrium. With mu = 1 Pa s the grown crack fills behind its tip through its own opening, so the
// notch holds a higher pressure than the lumped fluid's once the crack grows. Mass balance: the
// nodes hold V0 + Q t to round-off, every load step (1e-9).
TEST(ViscousFluid, GrownCrackFillsThroughItsOpeningAndConservesMass) {
  auto run = [](const std::string& viscosity_key, std::vector<double>& pressures) {
    const std::string text = rift::test::plane_strain_rock("fracture_energy = 50.0\npropagation_toughness_ratio = 1.21\n") + R"([regions.block]
shape = "box"
min = [-0.04, -0.03]
max = [0.04, 0.03]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.0015
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
lattice_origin = [-0.0005, -0.0005]
[[cracks]]
points = [[-0.005, 0.0005], [0.005, 0.0005]]
[[boreholes]]
region = "hole"
injection_rate = 1.5e-9
fluid_bulk_modulus = 2.2e9
)" + viscosity_key + R"(
[solver]
type = "dynamic_relaxation"
breaking = "at_equilibrium"
)";
    auto scene = rift::scene::parse_string(text, "grown.toml");
    rift::run::Simulation<2> sim(scene);
    auto& m = sim.model;
    rift::pd::DynamicRelaxation<2> dr(m);
    const double V0 = m.fluid_network.reference_volume[1];
    for (int step = 1; step <= 4; ++step) {
      const double t = 0.1 * step;
      dr.relax_breaking_at_equilibrium(m, sim.loads, sim.contact_ptr(), t, 50000, 1e-5, 20);
      pressures.push_back(m.fluid_network.pressure[1]);
      const auto& v = m.fluid_network.viscous[1];
      if (v.viscosity > 0.0) {
        double held = v.trial_inlet;
        for (double x : v.trial) held += x;
        EXPECT_NEAR(held / (V0 + 1.5e-9 * t), 1.0, 1e-9) << "t = " << t;
      }
    }
    std::int64_t broken = 0;
    for (auto state : m.bonds.intact) broken += state != rift::pd::bond_intact;
    return broken;
  };
  std::vector<double> lumped, viscous;
  const auto broken_lumped = run("", lumped), broken_viscous = run("fluid_viscosity = 1.0", viscous);
  for (std::size_t k = 0; k < lumped.size(); ++k)
    std::printf("t = %.1f s: lumped p = %.4g MPa, viscous p = %.4g MPa\n", 0.1 * double(k + 1), lumped[k] / 1e6, viscous[k] / 1e6);
  std::printf("broken bonds: lumped %ld, viscous %ld\n", long(broken_lumped), long(broken_viscous));
  EXPECT_GT(broken_viscous, 0);
  EXPECT_GT(viscous.back(), lumped.back());
}

}  // namespace
