// From a validated Scene to results: discretize, report the plan (`rift check`) or run the solver
// with outputs (`rift run`). All scene checks happen before anything is written.
#pragma once
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "rift/pd/forces.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

struct Options {
  std::string output_dir;  // default: results/<scene name>
  int threads = 0;         // 0: OpenMP default
  bool quiet = false;
  std::string restart;     // a checkpoint to continue from (io/checkpoint.hpp); empty: from the start
  long stop_after_step = 0;  // tests: stop after this step as a stop signal would (checkpoint, then return); 0: never
  /// tests: stop within a load step of relaxation once this many iterations have run, as SIGTERM would
  /// (the checkpoint of an unfinished load step, then return); 0: never
  long stop_after_iterations = 0;
  /// mpirun: the axis (0, 1, 2: x, y, z) across which the ranks' slabs are cut; -1: chosen (material
  /// points: the processor grid that crosses the fewest nodes; peridynamics: the lattice's slowest,
  /// the only one it takes)
  int cut_axis = -1;
  /// mpirun: the processor grid P_x, P_y (, P_z) of the ranks' boxes (material points: mpm/domain.hpp;
  /// peridynamics takes N along the lattice's slowest axis alone); empty: chosen
  std::vector<int> processor_grid = {};
};

struct Plan {
  std::size_t particles = 0;
  std::int64_t bonds = 0;
  double bytes_per_particle = 0.0, bytes_per_bond = 0.0;
  double stable_time_step = 0.0, time_step = 0.0;
  long steps = 0;
};

struct Result {
  std::string output_dir, fields_h5, fields_xdmf, history_csv;
  std::vector<std::pair<std::string, std::string>> files;  // further outputs: (what, path)
  std::vector<std::string> notes;                          // outputs not written and why, stage and interface reports
  std::vector<std::string> interface_outcomes;             // per pre-existing fracture (geomech/interface_outcome.hpp)
  long steps = 0;
  double time = 0.0;
  double loop_seconds = 0.0;  // wall time of the step loop (with outputs)
  // PD: wall time before the loop, the in-situ stage's equilibrium and the rest (the model made or
  // read from a checkpoint, the first forces)
  double setup_seconds = 0.0, in_situ_seconds = 0.0;
  std::string phases;         // PD: the loop's time by phase (core/phase_times.hpp)
  /// Work done in the loop: PD, directed bonds times force evaluations (steps, or dynamic relaxation
  /// iterations); MPM, material points times steps.
  double bond_updates = 0.0, particle_steps = 0.0;
  pd::EnergySummary final_energy;
  double max_damage = 0.0;
  long crack_growth_events = 0;  // MPM: crack particles added by propagation
  long first_step = 1;           // 1, or the step after the checkpoint a restart continued from
  int stop_signal = 0;           // the run stopped early on this signal (core/stop_signal.hpp), its checkpoint written
  bool stopped = false;          // stopped early (a signal, or Options::stop_after_step): `steps` is where
  std::string stopped_in;        // where a stop came within a step (a load step's iteration, the in-situ stage); empty: after `steps`
  std::string checkpoint;        // the last checkpoint written, empty if none
};

/// Discretize and print what a run would do (particles, bonds, memory, time step, outputs).
Plan check(const scene::Scene& s, std::ostream& out);
/// Run the scene and write its outputs.
Result run(const scene::Scene& s, const Options& options);

}  // namespace rift::run
