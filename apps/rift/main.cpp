// rift: peridynamic fracture simulator.
//   rift run SCENE [-o DIR] [--threads N] [--restart FILE]
//                                           run a scene and write fields, history and images
//                                           (or continue it from a checkpoint)
//   rift check SCENE                        validate a scene and print what a run would do
//   rift --version
//   mpirun -np N rift run SCENE ...         the same run on N ranks (pd/window.hpp); rank 0 writes
//                                           the outputs and prints
// Exit status: 0 success, 1 physics failure during a run, 2 bad input (nothing written), 128 + the
// signal when SIGTERM or SIGINT stopped a run (its checkpoint written).
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "rift/core/error.hpp"
#include "rift/core/stop_signal.hpp"
#include "rift/core/version.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/parallel/cpu_quota.hpp"
#include "rift/run/preflight.hpp"
#include "rift/run/runner.hpp"
#include "rift/scene/parse.hpp"

namespace {

/// "PxQ" or "PxQxR" as its 2 or 3 positive numbers (none: not such a text).
std::optional<std::vector<int>> processor_grid_of(const std::string& text) {
  std::vector<int> grid;
  for (std::size_t at = 0; at <= text.size();) {
    const auto x = std::min(text.find('x', at), text.size());
    const auto part = text.substr(at, x - at);
    if (part.empty() || part.size() > 6 || part.find_first_not_of("0123456789") != std::string::npos || std::stoi(part) < 1)
      return std::nullopt;
    grid.push_back(std::stoi(part));
    at = x + 1;
  }
  if (grid.size() != 2 && grid.size() != 3) return std::nullopt;
  return grid;
}

int rift_main(int argc, char** argv) {
  const auto& comm = rift::parallel::Communicator::world();
  if (!comm.root() && !std::freopen("/dev/null", "w", stdout)) return 1;  // rank 0 prints the run's report
  rift::parallel::limit_threads_to_cpu_quota();
  CLI::App app{"rift: fracture of solids with peridynamics"};
  app.set_version_flag("--version", std::string("rift ") + rift::version);
  app.require_subcommand(1);
  std::string scene_path, output_dir, restart, cut_along;
  int threads = 0;
  bool quiet = false;
  auto* run = app.add_subcommand("run", "Run a scene and write its results");
  run->add_option("scene", scene_path, "Scene file (TOML)")->required();
  run->add_option("-o,--output", output_dir, "Output directory (default: results/<scene name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            const bool whole = !text.empty() && text.size() <= 4 && text.find_first_not_of("0123456789") == std::string::npos;
            return whole && std::stoi(text) >= 1 ? std::string() : "a whole number of threads from 1 to 9999, got " + text;
          },
          "N"));
  std::string max_memory;
  const auto memory_validator = CLI::Validator(
      [](const std::string& text) {
        return rift::run::parse_memory_size(text) > 0.0 ? std::string() : "a size in bytes, or with K, M, G or T (as 8G), got " + text;
      },
      "SIZE");
  run->add_option("--max-memory", max_memory,
                  "Refuse a scene whose estimated memory exceeds this (bytes, or 512M, 8G, ...; default: this machine's memory)")
      ->check(memory_validator);
  run->add_flag("-q,--quiet", quiet, "No progress output");
  run->add_option("--restart", restart, "Continue the run from this checkpoint (written by [checkpoint] or on SIGTERM/SIGINT)");
  run->add_option("--cut-along", cut_along,
                  "mpirun: cut the ranks' slabs across this axis alone (default: a material point grid's processor grid whose cuts "
                  "cross the fewest nodes, see --processor-grid; peridynamics: the lattice's slowest axis, z in 3D and y in 2D, the "
                  "only one it takes)")
      ->check(CLI::IsMember({"x", "y", "z"}));
  std::string processor_grid;
  run->add_option("--processor-grid", processor_grid,
                  "mpirun: the ranks' boxes of a material point grid, PxQ in 2D or PxQxR in 3D, whose product is the number of ranks "
                  "(default: the grid whose cuts cross the fewest nodes; peridynamics takes 1xN or 1x1xN alone)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            return processor_grid_of(text) ? std::string() : "a processor grid is 2 or 3 positive whole numbers joined by x, as 2x2 or 2x1x2";
          },
          "PxQ[xR]"))
      ->excludes("--cut-along");
  auto* check = app.add_subcommand("check", "Validate a scene and print particles, bonds, memory, time step and outputs");
  check->add_option("scene", scene_path, "Scene file (TOML)")->required();
  check->add_option("--max-memory", max_memory, "As for run: the memory the scene may take")->check(memory_validator);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    auto scene = rift::scene::parse_file(scene_path);
    // before anything is built or written: the memory the scene takes and where its outputs go
    rift::run::PreflightOptions preflight;
    preflight.max_memory = max_memory.empty() ? 0.0 : rift::run::parse_memory_size(max_memory);
    preflight.ranks = comm.size();
    if (*run) preflight.output_dir = output_dir.empty() ? "results/" + scene.name : output_dir;
    const auto estimate = rift::run::preflight(scene, preflight);
    if (comm.root())
      for (const auto& w : scene.warnings) std::fprintf(stderr, "%s\n", w.c_str());
    if (*check) {
      rift::run::check(scene, std::cout);
      const double limit = preflight.max_memory > 0.0 ? preflight.max_memory : rift::run::machine_memory();
      const bool mpm = scene.method == rift::scene::Method::mpm;
      std::printf("pre-flight   estimated before building: %.4g %s, %.4g %s, %.4g MB at least (the limit: %.4g GB, %s)\n", estimate.particles,
                  mpm ? "material points" : "particles", mpm ? estimate.grid_nodes : estimate.directed_bonds, mpm ? "grid nodes" : "directed bonds",
                  estimate.bytes / 1e6, limit / 1e9, preflight.max_memory > 0.0 ? "--max-memory" : "this machine's memory");
      return 0;
    }
    rift::run::Options options{output_dir, threads, quiet, restart};
    if (!cut_along.empty()) options.cut_axis = cut_along[0] - 'x';
    if (!processor_grid.empty()) options.processor_grid = *processor_grid_of(processor_grid);
    long boxes = 1;
    for (const int p : options.processor_grid) boxes *= p;
    if (!processor_grid.empty() && boxes != comm.size())
      throw rift::SceneError({scene_path, 0, 0}, "--processor-grid",
                             fmt::format("a grid of {} boxes for {} rank{}; its numbers' product must be the ranks' number (mpirun -np {})", boxes,
                                         comm.size(), comm.size() == 1 ? "" : "s", boxes));
    rift::catch_stop_signals();
    auto r = rift::run::run(scene, options);
    if (r.stopped) {
      const std::string where = r.stopped_in.empty() ? fmt::format("after step {}", r.steps) : r.stopped_in;
      std::printf("rift: stopped by signal %d %s (t = %.6g s); checkpoint %s\n", r.stop_signal, where.c_str(), r.time, r.checkpoint.c_str());
      std::printf("rift: continue with: rift run %s%s%s --restart %s\n", scene_path.c_str(), output_dir.empty() ? "" : " -o ",
                  output_dir.c_str(), r.checkpoint.c_str());
      return r.stop_signal > 0 ? 128 + r.stop_signal : 0;
    }
    if (r.first_step > 1) std::printf("rift: continued from %s at step %ld\n", restart.c_str(), r.first_step - 1);
    if (scene.method == rift::scene::Method::mpm)
      std::printf("rift: %ld steps, t = %.6g s, kinetic energy %.6g J, strain energy %.6g J, crack growth %ld increments\n", r.steps,
                  r.time, r.final_energy.kinetic, r.final_energy.strain, r.crack_growth_events);
    else
      std::printf("rift: %ld steps, t = %.6g s, kinetic energy %.6g J, strain energy %.6g J, broken bonds %lld, max damage %.3f\n",
                  r.steps, r.time, r.final_energy.kinetic, r.final_energy.strain, static_cast<long long>(r.final_energy.broken_bonds),
                  r.max_damage);
    const double per_second = r.loop_seconds > 0.0 ? 1.0 / r.loop_seconds : 0.0;
    std::string rate = scene.method == rift::scene::Method::mpm
                           ? fmt::format("{:.4g} M particle-steps/s", 1e-6 * r.particle_steps * per_second)
                           : fmt::format("{:.4g} M bonds/s", 1e-6 * r.bond_updates * per_second);
    const long steps_run = r.steps - r.first_step + 1;  // by this process
    const int threads = omp_get_max_threads();
    std::printf("rift: loop time %.6g s (%.4g s per step, %d thread%s; %s)\n", r.loop_seconds, r.loop_seconds / double(std::max(1L, steps_run)),
                threads, threads == 1 ? "" : "s", rate.c_str());
    if (!r.phases.empty()) std::printf("rift: by phase: %s\n", r.phases.c_str());
    if (scene.method != rift::scene::Method::mpm) {
      const std::string in_situ = r.in_situ_seconds > 0.0 ? fmt::format(", in-situ stage {:.4g} s", r.in_situ_seconds) : std::string();
      std::printf("rift: before the loop: set-up %.4g s%s\n", r.setup_seconds, in_situ.c_str());
    }
    // peak resident memory of the process (getrusage: kilobytes on Linux), for the memory targets
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("rift: peak memory %.1f MiB\n", double(usage.ru_maxrss) / 1024.0);
    std::printf("results in %s/\n  fields   %s (open in ParaView)\n  history  %s\n", r.output_dir.c_str(), r.fields_xdmf.c_str(),
                r.history_csv.c_str());
    for (const auto& [what, path] : r.files) std::printf("  %-8s %s\n", what.c_str(), path.c_str());
    for (const auto& note : r.notes) std::printf("  %s\n", note.c_str());
    return 0;
  } catch (const rift::SceneError& e) {  // raised on every rank alike, before anything is written
    if (comm.root()) std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const rift::PhysicsError& e) {  // every rank's, from the reduced history (the one that found it says where)
    const std::string rank = comm.distributed() ? fmt::format(" (rank {})", comm.rank()) : "";
    std::fprintf(stderr, "rift: run stopped%s: %s\n", rank.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {
    if (!comm.distributed()) {
      std::fprintf(stderr, "rift: error: %s\n", e.what());
      return 1;
    }
    // one rank's failure (an output it cannot write): the others may wait for it in an exchange
    std::fprintf(stderr, "rift: error on rank %d: %s\n", comm.rank(), e.what());
    rift::parallel::MpiSession::abort(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  rift::parallel::MpiSession mpi(argc, argv);
  return rift_main(argc, argv);
}
