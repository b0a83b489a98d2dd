// The checks of a scene before anything is built or written, shared by `rift check` and `rift run`:
// the memory a run would take (run/memory_estimate.hpp) against what the machine or --max-memory
// gives, and the output directory and checkpoint path writable. Each failure is a SceneError
// (exit status 2) naming the key or option that drives it.
#pragma once
#include <string>

#include "rift/run/memory_estimate.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

struct PreflightOptions {
  std::string output_dir;   // `rift run`: where the outputs go (checked writable); empty: `rift check`
  double max_memory = 0.0;  // bytes the whole run may take (--max-memory); 0: the machine's memory
  int ranks = 1;            // mpirun -np N: the machine limit holds for each rank's share
};

/// Every check above; returns the estimate (printed by `rift check`).
MemoryEstimate preflight(const scene::Scene& s, const PreflightOptions& o);

}  // namespace rift::run
