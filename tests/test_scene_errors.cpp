// Every user mistake is a SceneError naming file:line:column and the key (exit status 2 in the CLI).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "rift/run/runner.hpp"
#include "rift/scene/parse.hpp"

namespace {

const char* base = R"(
[scene]
dimension = 2
plane = "stress"
thickness = 0.001

[materials.glass]
model = "pmb"
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.33
fracture_energy = 3.8

[regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.01, 0.01]

[regions.left]
shape = "box"
min = [0.0, 0.0]
max = [0.001, 0.01]

[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.001
horizon = 3.015

[[boundaries]]
region = "left"
type = "velocity"
x = 1.0

[solver]
type = "explicit"
end_time = 1e-6
)";

struct Case {
  const char* name;
  const char* find;     // text in the base scene to replace ("" = append)
  const char* replace;
  const char* key;      // key named in the message
  const char* at;       // the error points at the line holding this text ("" = not checked)
};

std::string mutate(const Case& c) {
  std::string s = base;
  if (std::string(c.find).empty()) return s + c.replace;
  auto p = s.find(c.find);
  EXPECT_NE(p, std::string::npos) << c.name;
  return s.replace(p, std::string(c.find).size(), c.replace);
}

const Case cases[] = {
    {"unknown top-level key", "", "\n[solvr]\nx = 1\n", "solvr", "[solvr]"},
    {"unknown material key", "density = 2440.0", "density = 2440.0\ndensty = 1", "materials.glass.densty", "densty"},
    {"wrong type", "density = 2440.0", "density = \"heavy\"", "materials.glass.density", "\"heavy\""},
    {"negative density", "density = 2440.0", "density = -1.0", "materials.glass.density", "density = -1.0"},
    {"unknown model", "model = \"pmb\"", "model = \"bond\"", "materials.glass.model", "\"bond\""},
    {"poisson ratio out of range", "poisson_ratio = 0.33", "poisson_ratio = 0.5", "materials.glass.poisson_ratio", "poisson_ratio = 0.5"},
    {"missing modulus", "youngs_modulus = 72e9\n", "", "materials.glass.youngs_modulus", ""},
    {"both G0 and s0", "fracture_energy = 3.8", "fracture_energy = 3.8\ncritical_stretch = 0.001", "materials.glass.critical_stretch", "critical_stretch"},
    {"propagation ratio without G0", "fracture_energy = 3.8", "critical_stretch = 0.001\npropagation_toughness_ratio = 1.2", "materials.glass.propagation_toughness_ratio", "propagation_toughness_ratio"},
    {"tensile strength without normal stress failure", "fracture_energy = 3.8", "tensile_strength = 3e6", "materials.glass.tensile_strength", "tensile_strength"},
    {"normal stress failure on a PMB", "fracture_energy = 3.8", "bond_failure = \"normal_stress\"\ntensile_strength = 3e6", "materials.glass.bond_failure", "\"normal_stress\""},
    {"normal stress failure without its strength", "model = \"pmb\"", "model = \"lps\"\nbond_failure = \"normal_stress\"", "materials.glass.tensile_strength", ""},
    {"normal stress failure with G0", "model = \"pmb\"", "model = \"lps\"\nbond_failure = \"normal_stress\"\ntensile_strength = 3e6", "materials.glass.fracture_energy", "fracture_energy"},
    {"propagation ratio not positive", "fracture_energy = 3.8", "fracture_energy = 3.8\npropagation_toughness_ratio = 0.0", "materials.glass.propagation_toughness_ratio", "propagation_toughness_ratio = 0.0"},
    {"missing material", "material = \"glass\"", "material = \"steel\"", "bodies.plate.material", "\"steel\""},
    {"negative spacing", "spacing = 0.001", "spacing = -0.001", "bodies.plate.spacing", "spacing = -"},
    {"horizon below spacing", "horizon = 3.015", "horizon = 0.5", "bodies.plate.horizon", "horizon = 0.5"},
    {"horizon twice", "horizon = 3.015", "horizon = 3.015\nhorizon_length = 0.003", "bodies.plate.horizon_length", "horizon_length"},
    {"unknown region in body", "region = \"plate\"\nspacing", "region = \"disk\"\nspacing", "bodies.plate.region", "\"disk\""},
    {"box max below min", "max = [0.01, 0.01]", "max = [-0.01, 0.01]", "regions.plate.max", "max = [-0.01"},
    {"point with wrong length", "max = [0.01, 0.01]", "max = [0.01, 0.01, 0.01]", "regions.plate.max", "max = [0.01, 0.01, 0.01]"},
    {"unknown shape", "shape = \"box\"\nmin = [0.0, 0.0]\nmax = [0.01, 0.01]", "shape = \"blob\"", "regions.plate.shape", "\"blob\""},
    {"difference of unknown region", "", "\n[regions.holed]\nshape = \"difference\"\nof = [\"plate\", \"hole\"]\n", "regions.holed.of", ""},
    {"region that selects no particle", "max = [0.001, 0.01]", "max = [0.0001, 0.0001]", "boundaries[0].region", "[[boundaries]]"},
    {"unknown boundary type", "type = \"velocity\"", "type = \"push\"", "boundaries[0].type", "\"push\""},
    {"boundary without components", "x = 1.0\n", "", "boundaries[0].x", ""},
    {"bad time function", "x = 1.0", "x = 1.0\ntime = { function = \"ramp\", start = 1e-6, end = 0.0 }", "boundaries[0].time.end", ""},
    {"table not increasing", "x = 1.0", "x = 1.0\ntime = { function = \"table\", points = [[0.0, 0.0], [0.0, 1.0]] }", "boundaries[0].time.points", ""},
    {"negative end time", "end_time = 1e-6", "end_time = -1e-6", "solver.end_time", "end_time = -"},
    {"time step above stable limit", "end_time = 1e-6", "end_time = 1e-6\ntime_step = 1.0", "solver.time_step", "time_step = 1.0"},
    {"unknown solver type", "type = \"explicit\"", "type = \"implicit\"", "solver.type", "\"implicit\""},
    {"plane missing in 2D", "plane = \"stress\"\n", "", "scene.plane", ""},
    {"dimension 4", "dimension = 2", "dimension = 4", "scene.dimension", "dimension = 4"},
    {"unknown output field", "", "\n[output]\nfields = [\"temperature\"]\n", "output.fields", ""},
    {"TOML syntax error", "density = 2440.0", "density = = 2440.0", "", "= = 2440"},
    {"crack with one point", "", "\n[[cracks]]\npoints = [[0.0, 0.0]]\n", "cracks[0].points", ""},
    {"initial velocity region empty", "", "\n[regions.far]\nshape = \"sphere\"\ncenter = [1.0, 1.0]\nradius = 0.001\n[[initial_velocity]]\nregion = \"far\"\nvelocity = [1.0, 0.0]\n", "initial_velocity.region", ""},
    {"safety factor above 1", "end_time = 1e-6", "end_time = 1e-6\nsafety_factor = 1.5", "solver.safety_factor", "safety_factor"},
    {"ves without relaxation time", "model = \"pmb\"", "model = \"ves\"\nviscous_fraction = 0.5", "materials.glass.relaxation_time", ""},
    {"ves viscous fraction above one", "model = \"pmb\"", "model = \"ves\"\nviscous_fraction = 1.5\nrelaxation_time = 1e-3",
     "materials.glass.viscous_fraction", "viscous_fraction = 1.5"},
    {"relaxation time on an elastic model", "model = \"pmb\"", "model = \"lps\"\nrelaxation_time = 1e-3", "materials.glass.relaxation_time",
     "relaxation_time"},
    {"negative crack pressure", "", "\n[[cracks]]\npoints = [[0.0, 0.005], [0.005, 0.005]]\npressure = -1e6\n", "cracks[0].pressure", "pressure = -1e6"},
    {"borehole in an unknown region", "", "\n[[boreholes]]\nregion = \"well\"\npressure = 1e6\n", "boreholes[0].region", "\"well\""},
    {"traction layer thinner than a row", "x = 1.0\n", "x = 1.0\n[[boundaries]]\nregion = \"left\"\ntype = \"traction\"\nx = 1e6\nlayer_depth = 0.0005\n",
     "boundaries[1].layer_depth", "[[boundaries]]\nregion = \"left\"\ntype = \"traction\""},
    {"in-situ stress without sigma_h", "", "\n[in_situ_stress]\nsigma_H = -10e6\n", "in_situ_stress.sigma_h", "[in_situ_stress]"},
    {"in-situ sigma_H along z", "", "\n[in_situ_stress]\nsigma_H = -10e6\nsigma_h = -5e6\nsigma_H_axis = \"z\"\n",
     "in_situ_stress.sigma_H_axis", "sigma_H_axis"},
    {"in-situ stage by an unknown solver", "", "\n[in_situ_stress]\nsigma_H = -10e6\nsigma_h = -5e6\nsolver = \"newton\"\n",
     "in_situ_stress.solver", "solver = \"newton\""},
    {"injection without the fluid's bulk modulus", "", "\n[regions.well]\nshape = \"cylinder\"\ncenter = [0.005, 0.005]\nradius = 0.002\n[[boreholes]]\nregion = \"well\"\ninjection_rate = 1e-9\n",
     "boreholes[0].fluid_bulk_modulus", "[[boreholes]]"},
    {"injection with a pressure time function", "", "\n[regions.well]\nshape = \"cylinder\"\ncenter = [0.005, 0.005]\nradius = 0.002\n[[boreholes]]\nregion = \"well\"\ninjection_rate = 1e-9\nfluid_bulk_modulus = 2e9\ntime = { function = \"ramp\", end = 1.0 }\n",
     "boreholes[0].time", "time = { function"},
    {"viscosity of a prescribed-pressure fluid", "", "\n[regions.well]\nshape = \"cylinder\"\ncenter = [0.005, 0.005]\nradius = 0.002\n[[boreholes]]\nregion = \"well\"\npressure = 1e6\nfluid_viscosity = 0.1\n",
     "boreholes[0].fluid_viscosity", "fluid_viscosity = 0.1"},
    {"negative breakdown pressure", "", "\n[regions.well]\nshape = \"cylinder\"\ncenter = [0.005, 0.005]\nradius = 0.002\n[[boreholes]]\nregion = \"well\"\ninjection_rate = 1e-9\nfluid_bulk_modulus = 2e9\nbreakdown_pressure = -1e6\n",
     "boreholes[0].breakdown_pressure", "breakdown_pressure = -1e6"},
    {"negative fluid viscosity", "", "\n[regions.well]\nshape = \"cylinder\"\ncenter = [0.005, 0.005]\nradius = 0.002\n[[boreholes]]\nregion = \"well\"\ninjection_rate = 1e-9\nfluid_bulk_modulus = 2e9\nfluid_viscosity = -1.0\n",
     "boreholes[0].fluid_viscosity", "fluid_viscosity = -1.0"},
    {"borehole that touches no material", "", "\n[regions.far]\nshape = \"box\"\nmin = [1.0, 1.0]\nmax = [1.1, 1.1]\n[[boreholes]]\nregion = \"far\"\npressure = 1e6\n",
     "boreholes[0].region", "[[boreholes]]"},
    {"interface bent in 2D", "", "\n[[interfaces]]\npoints = [[0.0, 0.005], [0.005, 0.006], [0.01, 0.005]]\ntensile_strength = 1e6\nfriction_coefficient = 0.89\n",
     "interfaces[0].points", "points = [[0.0, 0.005]"},
    {"interface without a friction coefficient", "", "\n[[interfaces]]\npoints = [[0.0, 0.005], [0.01, 0.005]]\ntensile_strength = 1e6\n",
     "interfaces[0].friction_coefficient", ""},
    {"interface with negative cohesion", "", "\n[[interfaces]]\npoints = [[0.0, 0.005], [0.01, 0.005]]\ntensile_strength = 1e6\ncohesion = -1.0\nfriction_coefficient = 0.5\n",
     "interfaces[0].cohesion", "cohesion = -1.0"},
    {"unknown breaking mode", "type = \"explicit\"\nend_time = 1e-6", "type = \"dynamic_relaxation\"\nbreaking = \"after\"", "solver.breaking",
     "breaking = \"after\""},
    {"breaking passes while bonds break during the iterations", "type = \"explicit\"\nend_time = 1e-6",
     "type = \"dynamic_relaxation\"\nmax_breaking_passes = 3", "solver.max_breaking_passes", "max_breaking_passes = 3"},
    {"the static solver breaking during its iterations", "type = \"explicit\"\nend_time = 1e-6",
     "type = \"static\"\nbreaking = \"during\"", "solver.breaking", "breaking = \"during\""},
    {"checkpoints every zero steps", "", "\n[checkpoint]\nevery_steps = 0\n", "checkpoint.every_steps", "every_steps = 0"},
    {"checkpoint every negative second", "", "\n[checkpoint]\nevery_seconds = -60.0\n", "checkpoint.every_seconds", "every_seconds = -60.0"},
    {"unknown checkpoint key", "", "\n[checkpoint]\nevery = 10\n", "checkpoint.every", "every = 10"},
};

class SceneErrors : public ::testing::TestWithParam<Case> {};

TEST_P(SceneErrors, NamesFileLineColumnAndKey) {
  const Case& c = GetParam();
  const std::string text = mutate(c);
  try {
    auto s = rift::scene::parse_string(text, "bad.toml");
    std::ostringstream out;
    rift::run::check(s, out);  // mistakes found while discretizing
    FAIL() << c.name << ": no error raised";
  } catch (const rift::SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("bad.toml:", 0), 0u) << msg;
    EXPECT_GT(e.where().line, 0) << msg;
    EXPECT_GT(e.where().column, 0) << msg;
    if (std::string(c.at).size()) {
      auto p = text.find(c.at);
      ASSERT_NE(p, std::string::npos) << c.name;
      const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(p), '\n'));
      EXPECT_EQ(e.where().line, line) << msg;
    }
    if (std::string(c.key).size()) {
      EXPECT_EQ(e.key(), c.key) << msg;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AtLeast25Mistakes, SceneErrors, ::testing::ValuesIn(cases),
                         [](const auto& info) {
                           std::string n = info.param.name;
                           for (auto& ch : n)
                             if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

TEST(SceneErrors, CoverAtLeast25Mistakes) { EXPECT_GE(sizeof(cases) / sizeof(cases[0]), 25u); }

TEST(SceneErrors, BaseSceneIsValid) {
  auto s = rift::scene::parse_string(base, "good.toml");
  std::ostringstream out;
  auto plan = rift::run::check(s, out);
  EXPECT_EQ(plan.particles, 100u);
}

}  // namespace

namespace {

const char* mpm_base = R"(
[scene]
method = "mpm"
dimension = 2
plane = "strain"
thickness = 0.001

[materials.steel]
model = "linear_elastic"
density = 7800.0
youngs_modulus = 200e9
poisson_ratio = 0.3

[regions.beam]
shape = "box"
min = [0.0, 0.0]
max = [0.02, 0.004]

[regions.clamp]
shape = "box"
min = [-0.01, -0.01]
max = [0.0, 0.02]

[bodies.beam]
material = "steel"
region = "beam"
particles_per_cell = 2

[[boundaries]]
region = "clamp"
type = "fixed"

[mpm]
cell_size = 0.001

[solver]
end_time = 1e-6
)";

struct MpmCase {
  const char* name;
  const char* find;
  const char* replace;
  const char* key;
};

const MpmCase mpm_cases[] = {
    {"peridynamic model in mpm", "model = \"linear_elastic\"", "model = \"pmb\"", "materials.steel.model"},
    {"missing mpm table", "[mpm]\ncell_size = 0.001\n", "", "mpm"},
    {"negative cell size", "cell_size = 0.001", "cell_size = -0.001", "mpm.cell_size"},
    {"unknown shape function", "cell_size = 0.001", "cell_size = 0.001\nshape = \"sinc\"", "mpm.shape"},
    {"flip fraction above one", "cell_size = 0.001", "cell_size = 0.001\nflip_fraction = 1.5", "mpm.flip_fraction"},
    {"zero particles per cell", "particles_per_cell = 2", "particles_per_cell = 0", "bodies.beam.particles_per_cell"},
    {"horizon in an mpm body", "particles_per_cell = 2", "horizon = 3.0", "bodies.beam.horizon"},
    {"dynamic relaxation in mpm", "end_time = 1e-6", "type = \"dynamic_relaxation\"", "solver.type"},
    {"the static solver in mpm", "end_time = 1e-6", "type = \"static\"", "solver.type"},
    {"displacement condition on the grid", "type = \"fixed\"", "type = \"displacement\"\nx = 0.001", "boundaries[0].type"},
    {"neo-Hookean in plane stress", "plane = \"strain\"", "plane = \"stress\"\n", ""},
    {"j2 without yield stress", "model = \"linear_elastic\"", "model = \"j2_plasticity\"", "materials.steel.yield_stress"},
    {"fixed region without grid nodes", "max = [0.0, 0.02]", "max = [-0.0095, -0.0095]", "boundaries[0].region"},
    {"mpm table in a peridynamic scene", "method = \"mpm\"", "method = \"peridynamics\"", ""},
    {"J contour of zero cells", "cell_size = 0.001", "cell_size = 0.001\nj_contour = 0", "mpm.j_contour"},
    {"crack growth without cracks", "[solver]", "[crack_growth]\ntoughness = 1e6\n[solver]", "crack_growth"},
    {"crack growth without toughness", "[solver]",
     "[[cracks]]\npoints = [[0.0205, 0.0025], [0.01, 0.0025]]\n[crack_growth]\ncriterion = \"max_hoop_stress\"\n[solver]",
     "crack_growth.toughness"},
    {"J area term not a boolean", "cell_size = 0.001", "cell_size = 0.001\nj_area_term = \"yes\"", "mpm.j_area_term"},
    {"pressure on an MPM crack", "[solver]", "[[cracks]]\npoints = [[0.0205, 0.0025], [0.01, 0.0025]]\npressure = 1e6\n[solver]", "cracks[0].pressure"},
    {"borehole in mpm", "[solver]", "[[boreholes]]\nregion = \"clamp\"\n[solver]", "boreholes[0].region"},
    {"interface in mpm", "[solver]", "[[interfaces]]\npoints = [[0.0, 0.0025], [0.01, 0.0025]]\ntensile_strength = 1e6\nfriction_coefficient = 0.5\n[solver]", "interfaces[0].points"},
    {"in-situ stress in mpm", "[solver]", "[in_situ_stress]\nsigma_H = -1e6\nsigma_h = -1e6\n[solver]", "in_situ_stress.sigma_H"},
    {"unknown mode partition", "cell_size = 0.001", "cell_size = 0.001\nmode_partition = \"displacement\"", "mpm.mode_partition"},
    {"traction layer thinner than a row of points", "type = \"fixed\"",
     "type = \"fixed\"\n[[boundaries]]\nregion = \"beam\"\ntype = \"traction\"\ny = 1e6\nlayer_depth = 0.0002", "boundaries[1].layer_depth"},
};

class MpmSceneErrors : public ::testing::TestWithParam<MpmCase> {};

TEST_P(MpmSceneErrors, NamesFileLineColumnAndKey) {
  const auto& c = GetParam();
  std::string text = mpm_base;
  auto p = text.find(c.find);
  ASSERT_NE(p, std::string::npos) << c.name;
  text.replace(p, std::string(c.find).size(), c.replace);
  if (std::string(c.name) == "neo-Hookean in plane stress") {
    auto q = text.find("model = \"linear_elastic\"");
    text.replace(q, 24, "model = \"neo_hookean\"");
  }
  try {
    auto s = rift::scene::parse_string(text, "bad.toml");
    std::ostringstream out;
    rift::run::check(s, out);
    FAIL() << c.name << ": no error raised";
  } catch (const rift::SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("bad.toml:", 0), 0u) << msg;
    EXPECT_GT(e.where().line, 0) << msg;
    if (std::string(c.key).size()) {
      EXPECT_EQ(e.key(), c.key) << msg;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Mpm, MpmSceneErrors, ::testing::ValuesIn(mpm_cases), [](const auto& info) {
  std::string n = info.param.name;
  for (auto& ch : n)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
});

TEST(MpmSceneErrors, BaseSceneIsValid) {
  auto s = rift::scene::parse_string(mpm_base, "good.toml");
  std::ostringstream out;
  auto plan = rift::run::check(s, out);
  EXPECT_EQ(plan.particles, 20u * 4u * 4u);
}

}  // namespace
