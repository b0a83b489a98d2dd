// Scene -> material point model: background grid, material points filling each body's region
// (particles_per_cell along each axis, at the centres of the sub-cells), constitutive constants,
// initial velocities.
#pragma once
#include "rift/mpm/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::mpm {

template <int D>
Model<D> discretize(const scene::Scene& s);

/// Continuum constants of a material for the scene's dimension and plane condition.
material::Constants continuum_constants(const scene::Scene& s, const scene::Material& m);

}  // namespace rift::mpm
