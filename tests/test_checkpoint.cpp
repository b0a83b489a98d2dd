// Checkpoint and restart (io/checkpoint.hpp, pd/checkpoint_state.hpp, `rift run --restart`): a run
// stopped after a step and continued from its checkpoint ends in the same state, bit for bit, as
// the run that was never stopped (issue 6: "the continued run is bit-identical to an uninterrupted
// one, including bond state, VES history, crack geometry and fluid state"). The proof is the final
// checkpoint itself, which holds every member of the model, the contact lists and the relaxation's
// state: the two runs' files must be equal byte for byte, and so must their history and fields.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "rift/core/error.hpp"
#include "rift/core/stop_signal.hpp"
#include "rift/io/checkpoint.hpp"
#include "rift/run/runner.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  EXPECT_TRUE(in.good()) << p;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The first record (io/checkpoint.hpp: after the 40-byte header, each a name's length and name,
/// element size, count and payload) in which two checkpoint files differ, or "" where they are equal.
std::string first_different_record(const std::string& a, const std::string& b) {
  if (a == b) return "";
  std::size_t at = 40;
  if (a.compare(0, at, b, 0, at) != 0) return "(header)";
  auto u32 = [](const std::string& s, std::size_t k) { std::uint32_t v = 0; std::memcpy(&v, s.data() + k, sizeof v); return v; };
  auto u64 = [](const std::string& s, std::size_t k) { std::uint64_t v = 0; std::memcpy(&v, s.data() + k, sizeof v); return v; };
  while (at + 4 <= a.size() && at + 4 <= b.size()) {
    const std::uint32_t length = u32(a, at);
    const std::string name = a.substr(at + 4, length);
    if (name.rfind("ENDCKPT", 0) == 0) return "(trailer)";
    const std::size_t payload = at + 4 + length + 16;
    if (payload > a.size()) return "(cut short)";
    const std::size_t bytes = static_cast<std::size_t>(u64(a, at + 4 + length) * u64(a, at + 4 + length + 8));
    if (a.compare(at, payload - at + bytes, b, at, payload - at + bytes) != 0) return name;
    at = payload + bytes;
  }
  return "(length)";
}

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rift_checkpoint_" + name);
  fs::remove_all(dir);
  return dir;
}

rift::run::Options quiet_in(const fs::path& dir) {
  rift::run::Options o;
  o.output_dir = dir.string();
  o.quiet = true;
  return o;
}

/// Every output of the whole run's directory that the continued run's must equal: its checkpoints
/// (compared record by record, to name the first that differs), CSV files, fields and their index.
void expect_same_outputs(const fs::path& whole, const fs::path& parts) {
  for (const auto& f : fs::directory_iterator(whole)) {
    const auto ext = f.path().extension();
    const fs::path other = parts / f.path().filename();
    if (ext == ".rift") {
      EXPECT_EQ(first_different_record(bytes_of(f.path()), bytes_of(other)), "") << f.path() << ": the states differ in this record";
    } else if (ext == ".csv" || ext == ".xdmf" || ext == ".h5") {
      EXPECT_TRUE(bytes_of(f.path()) == bytes_of(other)) << f.path();
    }
  }
}

/// Runs the scene whole, and again stopped after `stop` steps and continued from that stop's
/// checkpoint; expects the same final checkpoint, history and fields from both. Returns the whole
/// run's result.
rift::run::Result expect_restart_bit_identical(const std::string& name, const std::string& text, long stop) {
  const auto scene = rift::scene::parse_string(text, name + ".toml");
  const fs::path whole = fresh_directory(name + "_whole"), parts = fresh_directory(name + "_parts");
  const auto r = rift::run::run(scene, quiet_in(whole));
  EXPECT_FALSE(r.stopped);

  auto first = quiet_in(parts);
  first.stop_after_step = stop;
  const auto stopped = rift::run::run(scene, first);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.steps, stop);
  EXPECT_EQ(stopped.checkpoint, (parts / ("ck_" + std::to_string(stop) + ".rift")).string());

  auto second = quiet_in(parts);
  second.restart = stopped.checkpoint;
  const auto continued = rift::run::run(scene, second);
  EXPECT_FALSE(continued.stopped);
  EXPECT_EQ(continued.first_step, stop + 1);
  EXPECT_EQ(continued.steps, r.steps);

  EXPECT_TRUE(fs::exists(whole / ("ck_" + std::to_string(r.steps) + ".rift"))) << "the scene writes a checkpoint after its last step";
  expect_same_outputs(whole, parts);
  return r;
}

// A 2D glass plate (LPS, 0.5 mm spacing) with a pre-crack, pulled at its left edge: bonds break,
// the crack grows and its faces meet through the short-range contact.
std::string cracked_plate(const std::string& model) {
  return R"([scene]
dimension = 2
plane = "stress"
thickness = 0.001
[materials.glass]
model = ")" + model + R"("
density = 2440.0
youngs_modulus = 72e9
poisson_ratio = 0.25
fracture_energy = 3.8
)" + (model == "ves" ? "viscous_fraction = 0.5\nrelaxation_time = 1e-7\n" : model == "eps" ? "yield_stress = 5e7\n" : std::string()) +
         R"([regions.plate]
shape = "box"
min = [0.0, 0.0]
max = [0.02, 0.01]
[regions.left]
shape = "box"
min = [0.0, 0.0]
max = [0.001, 0.01]
[bodies.plate]
material = "glass"
region = "plate"
spacing = 0.0005
horizon = 3.015
[[cracks]]
points = [[0.01, 0.0], [0.01, 0.004]]
[[boundaries]]
region = "left"
type = "velocity"
x = -5.0
time = { function = "ramp", start = 0.0, end = 1e-6 }
[solver]
end_time = 4e-6
[output]
snapshots = 5
history_rows = 11
[checkpoint]
every_steps = 11
file = "ck_*.rift"
)";
}

// Quasi-static hydraulic fracture in a 2D rock block: in-situ stage, a borehole fed at a rate with a
// viscous fluid (cubic law), a pre-crack, a pre-existing interface, bonds breaking at each
// equilibrium; four load steps, a checkpoint after each.
std::string injection_with_interface() {
  return rift::test::plane_strain_rock("fracture_energy = 50.0\n") + R"([regions.block]
shape = "box"
min = [-0.03, -0.03]
max = [0.03, 0.03]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.003
[bodies.rock]
material = "rock"
region = "block"
spacing = 0.002
horizon = 3.015
lattice_origin = [-0.001, -0.001]
[[cracks]]
points = [[-0.008, 0.001], [0.008, 0.001]]
[[boreholes]]
region = "hole"
injection_rate = 3e-9
fluid_bulk_modulus = 2.2e9
fluid_viscosity = 0.1
[[interfaces]]
points = [[0.013, -0.03], [0.013, 0.03]]
tensile_strength = 1.0e6
friction_coefficient = 0.89
[in_situ_stress]
sigma_H = -6e6
sigma_h = -3e6
[solver]
type = "dynamic_relaxation"
breaking = "at_equilibrium"
end_time = 1.0
load_steps = 4
tolerance = 1e-4
[output]
snapshots = 4
history = ["broken_bonds", "max_damage"]
[checkpoint]
every_steps = 1
file = "ck_*.rift"
)";
}

/// The `column` of each row of a history file.
std::vector<double> history_column(const fs::path& csv, const std::string& column) {
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::stringstream h(header);
  std::string name;
  int at = -1;
  for (int k = 0; std::getline(h, name, ','); ++k)
    if (name == column) at = k;
  EXPECT_GE(at, 0) << "no column " << column << " in " << csv;
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::stringstream v(line);
    std::string value;
    for (int k = 0; std::getline(v, value, ','); ++k)
      if (k == at) out.push_back(std::stod(value));
  }
  return out;
}

double last_history_value(const fs::path& csv, const std::string& column) {
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::stringstream h(header), v(last);
  std::string name, value;
  while (std::getline(h, name, ',') && std::getline(v, value, ','))
    if (name == column) return std::stod(value);
  ADD_FAILURE() << "no column " << column << " in " << csv;
  return 0.0;
}

}  // namespace

TEST(Checkpoint, RecordsComeBackAsWrittenAndADamagedFileIsRefused) {
  const fs::path dir = fresh_directory("records");
  fs::create_directories(dir);
  const std::string path = (dir / "c.rift").string();
  std::vector<double> x{1.0 / 3.0, -0.0, 6.02214076e23};
  std::vector<std::vector<int>> rows{{1, 2}, {}, {3}};
  std::string text = "rock";
  {
    rift::io::CheckpointWriter w(path, {42, 7, 0.5});
    w("x", x), w("rows", rows), w("text", text);
    EXPECT_FALSE(fs::exists(path)) << "nothing under the name before commit";
    w.commit();
  }
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  {
    rift::io::CheckpointReader r(path);
    EXPECT_EQ(r.header().scene_fingerprint, 42u);
    EXPECT_EQ(r.header().step, 7);
    std::vector<double> x2;
    std::vector<std::vector<int>> rows2;
    std::string text2;
    r("x", x2), r("rows", rows2), r("text", text2);
    r.finish();
    EXPECT_EQ(std::memcmp(x.data(), x2.data(), sizeof(double) * x.size()), 0);  // -0.0 and all bits
    EXPECT_EQ(rows2, rows);
    EXPECT_EQ(text2, text);
  }
  {  // a record read under another name: refused with both names
    rift::io::CheckpointReader r(path);
    std::vector<double> y;
    try {
      r("y", y);
      ADD_FAILURE() << "a wrong name was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("is \"x\""), std::string::npos) << e.what();
    }
  }
  const std::string whole = bytes_of(path);
  {  // one flipped bit anywhere: the checksum refuses the file
    std::string damaged = whole;
    damaged[damaged.size() / 2] ^= 0x10;
    std::ofstream(path, std::ios::binary) << damaged;
    EXPECT_THROW(rift::io::CheckpointReader{path}, std::runtime_error);
  }
  {  // cut short (a copy interrupted): refused
    std::ofstream(path, std::ios::binary) << whole.substr(0, whole.size() - 5);
    EXPECT_THROW(rift::io::CheckpointReader{path}, std::runtime_error);
  }
}

// Explicit dynamics, LPS: the bond states, the contact's Verlet lists and the crack grow on after
// the stop (step 22 of 55).
TEST(Checkpoint, ExplicitLpsRunContinuesBitForBit) {
  const auto r = expect_restart_bit_identical("plate_lps", cracked_plate("lps"), 22);
  EXPECT_GT(r.final_energy.broken_bonds, 100);
}

// Explicit dynamics, viscoelastic state-based (VES, Mitchell 2011): each bond's back extension,
// the history the checkpoint must carry, relaxes on over the stop (tau = 0.1 us, steps of 73 ns).
TEST(Checkpoint, ExplicitVesRunContinuesBitForBit) {
  const auto r = expect_restart_bit_identical("plate_ves", cracked_plate("ves"), 33);
  EXPECT_GT(r.final_energy.broken_bonds, 100);
}

// Explicit dynamics, elastic-plastic state-based (EPS, Mitchell 2011): each direction's plastic
// extension, committed after every step, is the history the checkpoint must carry; the pulled edge
// yields (about 66 MPa of wave stress against sigma_Y = 50 MPa) before the crack runs.
TEST(Checkpoint, ExplicitEpsRunContinuesBitForBit) {
  const auto r = expect_restart_bit_identical("plate_eps", cracked_plate("eps"), 33);
  EXPECT_GT(r.final_energy.broken_bonds, 100);
}

// Quasi-static hydraulic fracture: in-situ stage, a borehole fed at a rate with a viscous fluid
// (cubic law), a pre-existing interface, bonds breaking at each equilibrium. The stop comes after
// load step 2 of 4, and the fracture and its fluid go on growing after it; the in-situ stage is
// not run again.
TEST(Checkpoint, InjectionWithInterfaceContinuesBitForBit) {
  const std::string text = injection_with_interface();
  const auto r = expect_restart_bit_identical("injection", text, 2);
  const fs::path whole = fs::temp_directory_path() / "rift_checkpoint_injection_whole";
  EXPECT_GT(last_history_value(whole / "history.csv", "broken_bonds"), 0.0) << "the fracture grew";
  EXPECT_GT(last_history_value(whole / "history.csv", "pressure_borehole_0"), 0.0);
  (void)r;
}

// A stop within a load step of relaxation (issue 81: SIGTERM inside a solve), in a breaking pass
// after the first of load step 3: the checkpoint holds the two load steps done and load step 3's
// pass, iterations, velocities and previous forces, and the restart goes on from that iteration to
// the whole run's bits (its checkpoints, history and fields). The stop is the runner's, after a
// given count of iterations, through the same stop flag SIGTERM sets.
TEST(Checkpoint, RelaxationStoppedWithinALoadStepContinuesBitForBit) {
  const auto scene = rift::scene::parse_string(injection_with_interface(), "injection.toml");
  const fs::path whole = fresh_directory("within_whole"), parts = fresh_directory("within_parts");
  const auto r = rift::run::run(scene, quiet_in(whole));
  ASSERT_FALSE(r.stopped);
  // the iterations and breaking passes of each load step (rows 1 to 4: the history's first row is the in-situ state)
  const auto iterations = history_column(whole / "history.csv", "iterations");
  const auto passes = history_column(whole / "history.csv", "breaking_passes");
  ASSERT_EQ(iterations.size(), 4u);
  ASSERT_GT(passes[2], 1.0) << "load step 3 breaks bonds at an equilibrium and relaxes again";
  auto first = quiet_in(parts);
  first.stop_after_iterations = static_cast<long>(iterations[0] + iterations[1] + iterations[2] - 10);
  const auto stopped = rift::run::run(scene, first);
  ASSERT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.steps, 2);
  EXPECT_NE(stopped.stopped_in.find("in load step 3 at iteration"), std::string::npos) << stopped.stopped_in;
  EXPECT_EQ(stopped.checkpoint, (parts / "ck_3.rift").string()) << "named after the load step it holds part of";
  {
    rift::io::CheckpointReader checkpoint(stopped.checkpoint);
    EXPECT_EQ(checkpoint.header().step, 2) << "as after load step 2";
  }
  auto second = quiet_in(parts);
  second.restart = stopped.checkpoint;
  const auto continued = rift::run::run(scene, second);
  EXPECT_FALSE(continued.stopped);
  EXPECT_EQ(continued.first_step, 3);
  expect_same_outputs(whole, parts);
}

// A stop in the in-situ stage (its conjugate gradients): the checkpoint holds no state, and the
// restart runs the scene from its start to the whole run's bits.
TEST(Checkpoint, StopInTheInSituStageStartsTheRunAgain) {
  const auto scene = rift::scene::parse_string(injection_with_interface(), "injection.toml");
  const fs::path whole = fresh_directory("in_situ_whole"), parts = fresh_directory("in_situ_parts");
  const auto r = rift::run::run(scene, quiet_in(whole));
  rift::set_stop_signal(SIGTERM);  // as the handler would: the stage reads it at its first iteration
  const auto stopped = rift::run::run(scene, quiet_in(parts));
  rift::set_stop_signal(0);
  ASSERT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.steps, 0);
  EXPECT_EQ(stopped.stop_signal, SIGTERM);
  EXPECT_NE(stopped.stopped_in.find("in-situ stage"), std::string::npos) << stopped.stopped_in;
  auto second = quiet_in(parts);
  second.restart = stopped.checkpoint;
  const auto continued = rift::run::run(scene, second);
  EXPECT_FALSE(continued.stopped);
  EXPECT_EQ(continued.first_step, 1);
  EXPECT_EQ(continued.steps, r.steps);
  fs::remove(parts / "ck_0.rift");  // the stop's, which the whole run never wrote
  expect_same_outputs(whole, parts);
}

// The static solver ([solver] type = "static"): a borehole's wall pressure ramped in three load
// steps in a 30 mm plane strain block. A stop in a load step's conjugate gradients checkpoints the
// positions it held; the restart solves that load step again from them, so the run ends at the
// uninterrupted run's equilibrium within the solve's tolerance (not bit for bit): the final strain
// energy within 1e-6, and the same as dynamic relaxation's within 1e-6 (the energy's error goes as
// the square of the residual, 1e-9 of the load here).
TEST(Checkpoint, StaticSolverStoppedWithinALoadStepSolvesItAgain) {
  auto text = [](const char* type) {
    return rift::test::plane_strain_rock("critical_stretch = 0.01\n") + R"([regions.block]
shape = "box"
min = [-0.015, -0.015]
max = [0.015, 0.015]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.003
[bodies.rock]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
lattice_origin = [-0.0005, -0.0005]
[[boreholes]]
region = "hole"
pressure = 5e6
time = { function = "ramp", start = 0.0, end = 1.0 }
[solver]
type = ")" + std::string(type) + R"("
load_steps = 3
tolerance = 1e-9
[output]
snapshots = 3
history = ["strain_energy"]
[checkpoint]
every_steps = 1
file = "ck_*.rift"
)";
  };
  const auto scene = rift::scene::parse_string(text("static"), "static.toml");
  const fs::path whole = fresh_directory("static_whole"), parts = fresh_directory("static_parts"), relaxed = fresh_directory("static_relaxed");
  const auto r = rift::run::run(scene, quiet_in(whole));
  ASSERT_FALSE(r.stopped);
  const auto evaluations = history_column(whole / "history.csv", "iterations");
  ASSERT_EQ(evaluations.size(), 3u);
  auto first = quiet_in(parts);
  first.stop_after_iterations = 10;  // iterations of the conjugate gradients, of the first load step's ~100 force evaluations
  const auto stopped = rift::run::run(scene, first);
  ASSERT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.steps, 0);
  EXPECT_NE(stopped.stopped_in.find("in load step 1 (its checkpoint solves it again"), std::string::npos) << stopped.stopped_in;
  auto second = quiet_in(parts);
  second.restart = stopped.checkpoint;
  const auto continued = rift::run::run(scene, second);
  EXPECT_FALSE(continued.stopped);
  EXPECT_EQ(continued.first_step, 1);
  const double energy = last_history_value(whole / "history.csv", "strain_energy");
  ASSERT_GT(energy, 0.0);
  EXPECT_NEAR(last_history_value(parts / "history.csv", "strain_energy") / energy, 1.0, 1e-6);
  const auto by_relaxation = rift::run::run(rift::scene::parse_string(text("dynamic_relaxation"), "relaxed.toml"), quiet_in(relaxed));
  ASSERT_FALSE(by_relaxation.stopped);
  EXPECT_NEAR(last_history_value(relaxed / "history.csv", "strain_energy") / energy, 1.0, 1e-6);
}

// MPM with an explicit crack that grows (CRAMP, maximum hoop stress): the material points and
// their stresses, the crack particles and surfaces, the tips that stopped, and the crack_tips.csv
// rows continue over the stop. A coarse DCB (2 mm cells), its arms pulled apart at once, with a
// toughness its K_I passes early.
TEST(Checkpoint, MpmCrackGrowthContinuesBitForBit) {
  const std::string text = R"([scene]
method = "mpm"
dimension = 2
plane = "stress"
thickness = 0.001
[materials.epoxy]
model = "linear_elastic"
density = 1500.0
youngs_modulus = 2.3e9
poisson_ratio = 0.33
[regions.beam]
shape = "box"
min = [0.0, 0.0]
max = [0.1, 0.024]
[regions.clamp]
shape = "box"
min = [-1.0, -1.0]
max = [0.0, 1.0]
[regions.upper_arm_end]
shape = "box"
min = [0.096, 0.012]
max = [0.1, 0.024]
[regions.lower_arm_end]
shape = "box"
min = [0.096, 0.0]
max = [0.1, 0.012]
[bodies.beam]
material = "epoxy"
region = "beam"
particles_per_cell = 2
[[cracks]]
points = [[0.1005, 0.012], [0.05, 0.012]]
[[boundaries]]
region = "clamp"
type = "fixed"
[[boundaries]]
region = "upper_arm_end"
type = "traction"
y = 83333.333
layer_depth = 0.004
[[boundaries]]
region = "lower_arm_end"
type = "traction"
y = -83333.333
layer_depth = 0.004
[mpm]
cell_size = 0.002
shape = "bspline2"
damping = 1000.0
grid_min = [-0.008, -0.011]
grid_max = [0.108, 0.035]
[crack_growth]
criterion = "max_hoop_stress"
toughness = 0.5e5
increment = 0.001
check_every = 10
[solver]
end_time = 0.002
safety_factor = 0.5
[output]
snapshots = 4
history_rows = 40
crack_tip_plot = false
[checkpoint]
every_steps = 400
file = "ck_*.rift"
)";
  const auto scene = rift::scene::parse_string(text, "dcb.toml");
  const fs::path whole = fresh_directory("dcb_whole"), parts = fresh_directory("dcb_parts");
  const auto r = rift::run::run(scene, quiet_in(whole));
  auto first = quiet_in(parts);
  first.stop_after_step = r.steps / 2;
  const auto stopped = rift::run::run(scene, first);
  ASSERT_TRUE(stopped.stopped);
  auto second = quiet_in(parts);
  second.restart = stopped.checkpoint;
  const auto continued = rift::run::run(scene, second);
  EXPECT_EQ(continued.first_step, r.steps / 2 + 1);
  EXPECT_GT(r.crack_growth_events, stopped.crack_growth_events) << "the crack grows after the stop too";
  EXPECT_EQ(continued.crack_growth_events, r.crack_growth_events);
  EXPECT_TRUE(fs::exists(whole / ("ck_" + std::to_string(r.steps - r.steps % 400) + ".rift")));
  expect_same_outputs(whole, parts);  // crack_tips.csv too
}

// A checkpoint of another scene, or of this scene's file since edited, is refused before any
// output is touched (exit status 2 on the command line).
TEST(Checkpoint, AnotherScenesCheckpointIsRefusedAndNothingChanges) {
  const auto scene = rift::scene::parse_string(cracked_plate("lps"), "plate.toml");
  const fs::path dir = fresh_directory("refused");
  auto first = quiet_in(dir);
  first.stop_after_step = 11;
  const auto stopped = rift::run::run(scene, first);
  const std::string history = bytes_of(dir / "history.csv");
  const auto edited = rift::scene::parse_string(cracked_plate("lps") + "# edited\n", "plate.toml");
  auto again = quiet_in(dir);
  again.restart = stopped.checkpoint;
  try {
    rift::run::run(edited, again);
    ADD_FAILURE() << "an edited scene took the checkpoint";
  } catch (const rift::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(bytes_of(dir / "history.csv") == history);
}

// kill -9 at any moment (issue 6): the newest checkpoint on the disk is whole (its checksum holds)
// and continues the run to the end an uninterrupted run reaches, and every snapshot the fields'
// index lists opens with all its particles. The run writes a snapshot every step, so that most
// kills land in the middle of writing one; it is killed at three moments, each after a given
// checkpoint is on the disk (a kill timed by the clock fell before the first checkpoint or after
// the end when the machine's load changed during the test).
TEST(Checkpoint, KillNineLeavesWholeFilesAndARunThatContinues) {
  std::string scene_text = cracked_plate("lps");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = scene_text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene_text.replace(at, from.size(), to);
  };
  replace("end_time = 4e-6", "end_time = 4e-5");  // 546 steps
  replace("snapshots = 5", "snapshots = 546");
  replace("history_rows = 11", "history_rows = 546");
  replace("every_steps = 11", "every_steps = 20");
  const fs::path dir = fresh_directory("kill");
  fs::create_directories(dir);
  const std::string scene_file = (dir / "plate.toml").string();
  std::ofstream(scene_file) << scene_text;
  const auto scene = rift::scene::parse_file(scene_file);
  const auto whole = rift::run::run(scene, quiet_in(dir / "whole"));
  // the newest checkpoint in a run's directory (-1: none yet)
  const auto newest_checkpoint = [](const fs::path& out) {
    long newest = -1;
    std::error_code error;
    for (const auto& e : fs::directory_iterator(out, error)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("ck_", 0) == 0 && e.path().extension() == ".rift") newest = std::max(newest, std::stol(name.substr(3)));
    }
    return newest;
  };

  // the kills: once the run has written the checkpoint of step 20, 200 or 400 (watched every
  // millisecond), and a few milliseconds later, so that each lands somewhere in the steps and
  // snapshots after it, whatever the machine's speed and load
  int continued_runs = 0;
  for (const auto& [after_step, delay_ms] : {std::pair{20L, 0}, std::pair{200L, 3}, std::pair{400L, 7}}) {
    const fs::path out = dir / ("killed_after_" + std::to_string(after_step));
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      execl(RIFT_EXE, RIFT_EXE, "run", scene_file.c_str(), "-o", out.c_str(), "--threads", "1", "-q", static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    bool finished = false;
    while (!(finished = waitpid(child, &status, WNOHANG) == child) && newest_checkpoint(out) < after_step)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (!finished) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
    }
    if (!WIFSIGNALED(status)) continue;  // it had finished: nothing to see at this moment

    // every snapshot the index lists is whole
    std::ifstream xdmf(out / "fields.xdmf");
    std::string line;
    int listed = 0;
    while (std::getline(xdmf, line)) {
      const auto end = line.find(".h5:/position");
      if (end == std::string::npos) continue;
      const auto begin = line.rfind('>', end) + 1;
      const std::string file = (out / line.substr(begin, end + 3 - begin)).string();
      const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      ASSERT_GE(f, 0) << file << " (listed in the index) does not open";
      const hid_t set = H5Dopen2(f, "position", H5P_DEFAULT);
      ASSERT_GE(set, 0) << file;
      std::vector<double> position(3 * 800);
      EXPECT_GE(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, position.data()), 0) << file;
      H5Dclose(set);
      H5Fclose(f);
      ++listed;
    }
    // the newest checkpoint is whole and continues the run
    const long newest = newest_checkpoint(out);
    if (newest < 0) continue;  // killed before the first checkpoint
    SCOPED_TRACE("killed after the checkpoint of step " + std::to_string(after_step) + ", " + std::to_string(listed) +
                 " snapshots listed, checkpoint " + std::to_string(newest));
    auto again = quiet_in(out);
    again.restart = (out / ("ck_" + std::to_string(newest) + ".rift")).string();
    const auto continued = rift::run::run(scene, again);
    ++continued_runs;
    EXPECT_GT(continued.first_step, 1);
    EXPECT_EQ(continued.final_energy.broken_bonds, whole.final_energy.broken_bonds);
    expect_same_outputs(dir / "whole", out);
  }
  EXPECT_EQ(continued_runs, 3) << "a run ended before its kill";
}
