// The memory a scene would take, estimated from its regions, spacings and horizons without
// building it (a lower bound: a run takes at least this), and what the machine gives a process.
// run/preflight.hpp compares the two before anything is built; the scene-parser fuzz target runs
// the estimate on every scene it makes (tests/fuzz).
#pragma once
#include <string>

#include "rift/scene/scene.hpp"

namespace rift::run {

/// What a scene would hold, estimated before it is built (a lower bound of its memory: a run takes
/// at least this).
struct MemoryEstimate {
  double particles = 0.0;        // PD particles or MPM material points
  double directed_bonds = 0.0;   // PD
  double grid_nodes = 0.0;       // MPM
  double bytes = 0.0;
};

/// Particles from the share of each body's bounding box its region fills (sampled on a lattice of
/// at most 2^17 sites), bonds from the lattice offsets within the horizon. Raises a SceneError where
/// a body's lattice or family alone is past what the code holds (2e9 sites, 65,536 offsets).
MemoryEstimate estimate_memory(const scene::Scene& s);

/// The memory this machine gives a process: the smaller of its physical memory and its cgroup's
/// limit, bytes (0: unknown).
double machine_memory();

/// "8G", "512M", "1.5T", "1000000" (bytes) as bytes; negative where not such a text.
double parse_memory_size(const std::string& text);

}  // namespace rift::run
