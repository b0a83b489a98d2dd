// The in-situ stage's starting point: the uniform strain that Hooke's law gives the far-field
// principal stresses, eps_kk = (sigma_k - lambda tr(eps)) / 2G with tr(eps) = tr(sigma) / (d kappa)
// (kappa and lambda of the body's dimension and plane condition, pd/material_constants.hpp; the first d
// principal stresses of [in_situ_stress]). It is the block's equilibrium away from its faces, its
// edges and the borehole, so the relaxation from it has only their local fields left to find
// (pd/dynamic_relaxation.hpp: the damping then measured on the motion away from this start).
// Displacements count from the lowest lattice coordinate on each axis, which a platen holds
// (pd/platens.hpp); a component that a boundary condition constrains keeps its position.
#pragma once
#include "rift/parallel/communicator.hpp"
#include "rift/pd/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::geomech {

/// Strain of the far-field stresses in a body with these constants (principal axes = coordinate axes).
template <int D>
Vec<D> in_situ_strain(const pd::MaterialConstants& c, const scene::InSituStress& s) {
  double trace_sigma = 0.0;
  for (int k = 0; k < D; ++k) trace_sigma += s.principal(k);
  const double trace_eps = trace_sigma / (D * c.kappa);
  Vec<D> eps;
  for (int k = 0; k < D; ++k) eps[k] = (s.principal(k) - c.lame_lambda() * trace_eps) / (2.0 * c.shear_modulus);
  return eps;
}

/// Moves every particle to the uniform in-situ strain of its body.
template <int D>
void apply_in_situ_strain(pd::Model<D>& m, const scene::InSituStress& s) {
  Vec<D> low = m.reference_bounds()[0];
  if (m.ghosts)  // a distributed run's window: the whole block's lowest coordinates
    for (int k = 0; k < D; ++k) low[k] = parallel::Communicator::world().min(low[k]);
  for (const auto& body : m.bodies) {
    if (!(body.constants.shear_modulus > 0.0)) continue;
    const Vec<D> eps = in_situ_strain<D>(body.constants, s);
    for (std::size_t i = body.first; i < body.last; ++i)
      for (int k = 0; k < D; ++k)
        if (!(m.constrained[i] >> k & 1)) m.position[i][k] = m.reference_position[i][k] + eps[k] * (m.reference_position[i][k] - low[k]);
  }
}

}  // namespace rift::geomech
