// The viscous fluid coupled with the rock (pd/viscous_fluid.hpp): a borehole with a dry pre-crack
// through it, fed at a constant rate, relaxed to equilibrium at a few load steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "rift/hf/viscous_fluid.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

// A 60 x 40 mm plane strain block of the test rock (E = 10 GPa, nu = 0.25, no breaking: the
// pressures stay far below its strength), 1 mm spacing, a borehole of radius 2.5 mm and a 24 mm
// pre-crack through it between two rows; K_f = 200 MPa; Q = 2e-10 m^3/s into the 1 mm slab.
std::string borehole_with_pre_crack(const std::string& viscosity_key) {
  return rift::test::plane_strain_rock() + R"([regions.block]
shape = "box"
min = [-0.03, -0.02]
max = [0.03, 0.02]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.0025
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
lattice_origin = [-0.0005, -0.0005]
[[cracks]]
points = [[-0.012, 0.0005], [0.012, 0.0005]]
[[boreholes]]
region = "hole"
injection_rate = 2e-10
fluid_bulk_modulus = 2e8
)" + viscosity_key + R"(
[solver]
type = "dynamic_relaxation"
)";
}

struct Injected {
  double pressure = 0.0, volume = 0.0, held = 0.0;
  std::vector<double> step_pressures;          // the borehole's pressure at each load step's equilibrium
  double wall_volume = 0.0, reference = 0.0;  // the borehole's own cavity (its wall alone), and V0
  bool sealed = false;                        // the wall not yet broken down (breakdown_pressure)
};

// Relaxes at t = 0.25, 0.5, 0.75, 1 s; the borehole's pressure, the cavity volume and (viscous) the
// fluid the nodes hold at the end.
Injected inject(const std::string& viscosity_key) {
  auto scene = rift::scene::parse_string(borehole_with_pre_crack(viscosity_key), "viscous.toml");
  rift::run::Simulation<2> sim(scene);
  auto& m = sim.model;
  rift::pd::DynamicRelaxation<2> dr(m);
  Injected out;
  for (double t : {0.25, 0.5, 0.75, 1.0}) {
    const auto r = dr.relax(m, sim.loads, sim.contact_ptr(), t, 50000, 1e-7);
    EXPECT_TRUE(r.converged) << "t = " << t << ": residual " << r.residual;
    out.step_pressures.push_back(m.fluid_network.pressure[1]);
  }
  sim.loads.apply_body_forces(m, 1.0);
  const auto& f = m.fluid_network;
  out.pressure = f.pressure[1], out.volume = f.cavity_volume[1];
  out.reference = f.reference_volume[1];
  out.wall_volume = f.reference_volume[1] + rift::hf::cavity_volume_change<2>(m, 1, true);
  out.sealed = f.sealed[1] != 0;
  if (!f.viscous.empty() && f.viscous[1].viscosity > 0.0) {
    out.held = f.viscous[1].trial_inlet;
    for (double x : f.viscous[1].trial) out.held += x;
  }
  return out;
}

// Where the fluid flows freely (mu = 1e-9 Pa s: the pressure drop along the pre-crack is nothing)
// the viscous fluid is the lumped one: one pressure p = K_f (V_fluid / V - 1). Its nodes' volumes
// share out the lumped fluid's cavity volume (the work conjugate of the pressure forces,
// hf/fluid_network.hpp) by the openings, so the pressures agree to the relaxation's tolerance
// (measured 1.00000; 1e-4). And every load step conserves the fluid: the nodes hold
// V0 (1 + p0 / K_f) + Q t, to round-off (1e-9).
TEST(ViscousFluid, FreelyFlowingFluidIsTheLumpedFluid) {
  const Injected lumped = inject(""), free_flowing = inject("fluid_viscosity = 1e-9");
  auto scene = rift::scene::parse_string(borehole_with_pre_crack(""), "viscous.toml");
  std::printf("lumped p = %.5g MPa, V = %.5g m^3; mu = 1e-9 Pa s: p = %.5g MPa, V = %.5g m^3, ratio %.6f\n", lumped.pressure / 1e6,
              lumped.volume, free_flowing.pressure / 1e6, free_flowing.volume, free_flowing.pressure / lumped.pressure);
  EXPECT_GT(lumped.pressure, 1e5);
  EXPECT_NEAR(free_flowing.pressure / lumped.pressure, 1.0, 1e-4);
  rift::run::Simulation<2> sim(scene);
  const double expected = sim.model.fluid_network.reference_volume[1] + 2e-10 * 1.0;
  EXPECT_NEAR(free_flowing.held / expected, 1.0, 1e-9);
}

// The injection system's fluid (injection_system_volume = V_s, here 1.5e-8 m^3, about the cavity's
// own volume) at the borehole's pressure stores V_s p / K_f of what was pumped, in both fluids: the
// viscous fluid flowing freely is still the lumped one (1e-4), its nodes hold (V0 + V_s) + Q t (1e-9),
// and the lumped pressure falls as the mass balance says, K_f (V0 + V_s + Q t) / (V + V_s) - K_f with
// V the cavity of the run (1e-9 of p), below the pressure without the system.
TEST(ViscousFluid, InjectionSystemVolumeStoresItsShareInBothFluids) {
  const double system = 1.5e-8, K_f = 2e8, Q_t = 2e-10;
  const std::string key = "injection_system_volume = 1.5e-8\n";
  const Injected lumped = inject(key), free_flowing = inject(key + "fluid_viscosity = 1e-9"), without = inject("");
  auto scene = rift::scene::parse_string(borehole_with_pre_crack(key), "viscous.toml");
  rift::run::Simulation<2> sim(scene);
  const double V0 = sim.model.fluid_network.reference_volume[1];
  std::printf("V0 = %.4g m^3; with V_s = %.3g m^3: lumped p = %.5g MPa, free-flowing %.5g MPa; without: %.5g MPa\n", V0, system,
              lumped.pressure / 1e6, free_flowing.pressure / 1e6, without.pressure / 1e6);
  EXPECT_NEAR(free_flowing.pressure / lumped.pressure, 1.0, 1e-4);
  EXPECT_NEAR(free_flowing.held / (V0 + system + Q_t), 1.0, 1e-9);
  const double expected = K_f * ((V0 + system + Q_t) / (lumped.volume + system) - 1.0);
  EXPECT_NEAR(lumped.pressure / expected, 1.0, 1e-9);
  EXPECT_LT(lumped.pressure, 0.8 * without.pressure);
}

// A borehole with a breakdown pressure keeps its fluid out of the dry pre-crack through it until
// its pressure first reaches that (FluidNetwork::sealed, pd/fluid_network.hpp). Sealed (a breakdown
// pressure never reached): the cavity is the borehole's own, the pre-crack's faces take none of the
// fluid (its volume equals the wall's alone to round-off, 1e-12), and the lumped fluid's pressure
// follows the closed mass balance K_f (V0 + Q t) / V - K_f with V that cavity (1e-9), above the
// unsealed run's. Broken down at the second load step (a breakdown pressure between the sealed
// run's pressures at t = 0.25 and 0.5 s): the fluid then fills the pre-crack, and since the lumped
// fluid's mass balance and the elastic rock keep no memory of the path, the state at t = 1 s is the
// unsealed run's to the relaxation's tolerance (1e-4 of p).
TEST(ViscousFluid, BreakdownPressureKeepsThePreCrackDryUntilReached) {
  const double K_f = 2e8, Q_t = 2e-10;
  const auto open = inject(""), sealed = inject("breakdown_pressure = 1e9\n");
  const double breakdown = 0.5 * (sealed.step_pressures[0] + sealed.step_pressures[1]);
  char key[80];
  std::snprintf(key, sizeof key, "breakdown_pressure = %.17g\n", breakdown);
  const auto broken_down = inject(key);
  std::printf("unsealed p = %.5g MPa; sealed p = %.5g MPa (cavity %.6g, wall %.6g m^3); broken down at %.4g MPa: p = %.5g MPa\n",
              open.pressure / 1e6, sealed.pressure / 1e6, sealed.volume, sealed.wall_volume, breakdown / 1e6,
              broken_down.pressure / 1e6);
  EXPECT_TRUE(sealed.sealed);
  EXPECT_NEAR(sealed.volume / sealed.wall_volume, 1.0, 1e-12);
  EXPECT_NEAR(sealed.pressure / (K_f * ((sealed.reference + Q_t) / sealed.volume - 1.0)), 1.0, 1e-9);
  EXPECT_GT(sealed.pressure, 1.05 * open.pressure);
  EXPECT_FALSE(broken_down.sealed);
  EXPECT_NEAR(broken_down.pressure / open.pressure, 1.0, 1e-4);
}

// A node whose bonds have all shut (no volume) gives what it held to its open neighbour of largest
// volume, or to the borehole's node (0) where none is open; the fluid held in all is unchanged.
TEST(ViscousFluid, AShutNodeSqueezesItsFluidIntoItsOpenNeighbour) {
  // nodes 0..4; bonds 1-2, 1-3 (3 the larger), 4-1 (both shut: 4 has no open neighbour)
  const std::vector<rift::hf::FlowBond> bonds{{1, 2, 0.0, 0.0, 0.0}, {1, 3, 0.0, 0.0, 0.0}, {4, 1, 0.0, 0.0, 0.0}};
  const std::vector<double> volume{5.0, 0.0, 1.0, 2.0, 0.0};
  std::vector<double> held{4.0, 3.0, 1.0, 2.0, 0.5};
  rift::hf::squeeze_out_closed_nodes(bonds, volume, held);
  EXPECT_DOUBLE_EQ(held[0], 4.5);  // node 4's, through no open neighbour
  EXPECT_DOUBLE_EQ(held[1], 0.0);
  EXPECT_DOUBLE_EQ(held[2], 1.0);
  EXPECT_DOUBLE_EQ(held[3], 5.0);  // node 1's
  EXPECT_DOUBLE_EQ(held[4], 0.0);
}

}  // namespace
