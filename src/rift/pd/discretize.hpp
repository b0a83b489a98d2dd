// Scene -> peridynamic model: fill each body's region with particles on its lattice, build the
// bond families (partial volumes, pre-cracks), weighted volumes, surface correction, initial
// velocities. Mistakes that only show here (a region with no particle, an unbounded body) are
// SceneErrors with the scene position of the offending entry.
#pragma once
#include "rift/pd/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::pd {

template <int D>
Model<D> discretize(const scene::Scene& s);

/// Share of the cell at integer lattice offset `o` (in spacings) inside a horizon of `h` spacings.
double partial_volume_fraction(const int* o, int dimension, double h, scene::Body::PartialVolume scheme);

}  // namespace rift::pd
