// When a run writes its checkpoints and how it reads one back (io/checkpoint.hpp), for the
// peridynamic and the MPM runner alike: [checkpoint] every_steps and every_seconds, a stop signal
// (core/stop_signal.hpp), and `rift run --restart FILE`.
#pragma once
#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "rift/core/error.hpp"
#include "rift/io/checkpoint.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/run/runner.hpp"
#include "rift/core/stop_signal.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

/// Where the scene's checkpoint after `step` goes ([checkpoint] file, relative to the output
/// directory; a '*' in it becomes the step, as in LAMMPS' restart command, to keep each one).
inline std::string checkpoint_path(const scene::Scene& s, const std::string& output_dir, long step) {
  std::string file = s.checkpoint.file.empty() ? "checkpoint.rift" : s.checkpoint.file;
  if (const auto star = file.find('*'); star != std::string::npos) file.replace(star, 1, std::to_string(step));
  return std::filesystem::path(file).is_absolute() ? file : output_dir + "/" + file;
}

/// The output directory and the folder of the scene's checkpoints, made where missing (run/preflight.hpp
/// found them writable before the run began). A run killed while it wrote leaves the file it was
/// writing under its name + ".tmp" (renamed into place once whole): those of the snapshots, their
/// index and the checkpoints are removed here.
inline void make_output_folders(const scene::Scene& s, const std::string& output_dir) {
  namespace fs = std::filesystem;
  fs::create_directories(output_dir);
  const fs::path checkpoint = checkpoint_path(s, output_dir, 0);
  const auto folder = checkpoint.parent_path();
  if (!folder.empty()) fs::create_directories(folder);
  for (const fs::path& dir : {fs::path(output_dir), folder}) {
    std::error_code ec;
    for (const auto& f : fs::directory_iterator(dir, ec)) {
      const std::string name = f.path().filename().string();
      const bool ours = name.ends_with(".tmp") && (name.starts_with("fields") || name.ends_with(".rift.tmp") ||
                                                   name == checkpoint.filename().string() + ".tmp");
      if (ours && f.is_regular_file(ec)) fs::remove(f.path(), ec);
    }
  }
}

/// What `rift check` says of the scene's checkpoints.
inline std::string checkpoint_plan(const scene::Scene& s) {
  const auto& c = s.checkpoint;
  const std::string file = c.file.empty() ? "checkpoint.rift" : c.file;
  if (c.every_steps <= 0 && c.every_seconds <= 0.0) return "checkpoint   on SIGTERM/SIGINT -> checkpoint.rift (the whole state, about the memory of the run)\n";
  std::string when;
  if (c.every_steps > 0)
    when = fmt::format("every {} {}steps", c.every_steps, s.solver.kind == scene::SolverKind::explicit_dynamics ? "" : "load ");
  if (c.every_seconds > 0.0) when += fmt::format("{}every {:g} s of wall time", when.empty() ? "" : " and ", c.every_seconds);
  return "checkpoint   " + when + " -> " + file + " (the whole state, about the memory of the run, each), and on SIGTERM/SIGINT\n";
}

/// Reads the checkpoint of Options::restart through visit(reader) and returns the step it
/// continues after. Every record is read before the caller touches an output, so a checkpoint of
/// another scene, damaged, or of another build changes nothing: a SceneError (exit status 2).
template <class Visit>
long read_checkpoint(const scene::Scene& s, const Options& o, long steps, Visit visit) {
  try {
    io::CheckpointReader checkpoint(o.restart);
    const auto& h = checkpoint.header();
    if (h.scene_fingerprint != s.fingerprint)
      throw std::runtime_error("it was written for another scene, or for " + s.file +
                               " before it was edited (a restart continues the same scene, unchanged)");
    if (h.step < 0 || h.step > steps) throw std::runtime_error(fmt::format("it is at step {}, past the scene's {} steps", h.step, steps));
    visit(checkpoint);
    checkpoint.finish();
    return h.step;
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError({o.restart, 0, 0}, "", std::string("cannot restart from this checkpoint: ") + e.what());
  }
}

/// A restart continues the stopped run's output files, which must be in the output directory
/// (the same -o) and hold at least what the checkpoint counted; a SceneError (exit status 2)
/// before anything is written otherwise.
inline void require_output_file(const Options& o, const std::string& path, std::int64_t bytes) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size < static_cast<std::uintmax_t>(bytes))
    throw SceneError({o.restart, 0, 0}, "",
                     fmt::format("cannot restart from this checkpoint: {} {} (the checkpoint counts {} bytes of it); restart with the "
                                 "output directory of the run that wrote the checkpoint (-o)",
                                 path, ec ? "does not exist" : fmt::format("holds only {} bytes", size), bytes));
}

/// After each step of a run: writes a checkpoint where [checkpoint] asks for one or a stop came,
/// and says whether the run stops there (Result::stopped, its checkpoint written).
class Checkpointing {
 public:
  Checkpointing(const scene::Scene& s, const Options& o, std::string output_dir)
      : scene_(s), stop_after_step_(o.stop_after_step), output_dir_(std::move(output_dir)), last_(std::chrono::steady_clock::now()) {}

  /// visit(writer) writes the records; the checkpoint holds the model at `time` after `step`.
  template <class Visit>
  bool after_step(long step, double time, Result& res, Visit visit) {
    return after_step(step, time, res, [] {}, visit);
  }
  /// A distributed run: every rank calls gather() before rank 0 writes the records with visit.
  template <class Gather, class Visit>
  bool after_step(long step, double time, Result& res, Gather gather, Visit visit) {
    // every rank of a distributed run stops after the same step (a signal reaches each at its own
    // time) and writes the same checkpoints (their clocks differ)
    const auto& comm = parallel::Communicator::world();
    const bool stop = comm.any(stop_signal() != 0 || (stop_after_step_ > 0 && step >= stop_after_step_));
    const auto& c = scene_.checkpoint;
    const bool due = comm.any((c.every_steps > 0 && step % c.every_steps == 0) ||
                              (c.every_seconds > 0.0 &&
                               std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= c.every_seconds));
    if (stop || due) {
      write(step, step, time, res, gather, visit);
      last_ = std::chrono::steady_clock::now();
    }
    if (stop) stopped_after(step, res);
    return stop;
  }
  /// A stop within `step` (an iteration of its relaxation): every rank calls gather() before rank 0
  /// writes the records with visit, under the name of `step` (where the scene's file has a '*'; the
  /// step's own checkpoint replaces it once the restart has finished it) and as after step - 1.
  template <class Gather, class Visit>
  void stop_within(long step, double time, Result& res, Gather gather, Visit visit) {
    write(step, step - 1, time, res, gather, visit);
    stopped_after(step - 1, res);
  }
  /// A stop before the first step (in the in-situ stage): rank 0 writes the checkpoint of step 0
  /// that visit(writer) makes, and the run is stopped there.
  template <class Visit>
  void after_stop_before_start(Result& res, Visit visit) {
    write(0, 0, 0.0, res, [] {}, visit);
    stopped_after(0, res);
  }

 private:
  /// Every rank calls gather(); rank 0 writes the records with visit into the checkpoint named after
  /// `named_step`, its header's step `step`.
  template <class Gather, class Visit>
  void write(long named_step, long step, double time, Result& res, Gather gather, Visit visit) {
    const std::string file = checkpoint_path(scene_, output_dir_, named_step);
    gather();
    if (parallel::Communicator::world().root()) {
      io::CheckpointWriter w(file, {scene_.fingerprint, step, time});
      visit(w);
      w.commit();
    }
    res.checkpoint = file;
  }
  /// The run stops after `step` (a signal's, or Options::stop_after_step).
  void stopped_after(long step, Result& res) const {
    res.stopped = true;
    res.stop_signal = stop_signal();
    res.steps = step;
  }
  const scene::Scene& scene_;
  long stop_after_step_;
  std::string output_dir_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace rift::run
