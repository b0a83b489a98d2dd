// Static equilibrium of a body whose bonds are held (the in-situ stage), by preconditioned conjugate
// gradients (Hestenes and Stiefel 1952; Saad 2003, algorithm 9.1), matrix free at a fixed base point x:
// K p = -(F(x + e p) - F(x)) / e. The forces are linear in the displacements up to geometric terms of the
// order of the strain, so the iterations are Newton's: once the linear residual is under a hundredth of
// the base's, the forces are evaluated at the iterate, which becomes the next base. Preconditioner: the
// dynamic relaxation's diagonal (Kilic and Madenci 2010, eq. 10, the row sum of the stiffness), a platen
// (platens.hpp) one unknown with its particles' summed diagonal, plus a coarse space of aggregates
// (coarse_space.hpp) where the body has no platen and is three aggregates across. A free body's rigid
// motions are projected out of the preconditioned residual (rigid_motion.hpp; a deflated conjugate
// gradient). The iterations go as the lattice's sites along the body with the diagonal alone, as an
// aggregate's sites across with the coarse space.
// Why, and what was measured: docs/decisions/method-notes.md.
#pragma once
#include <functional>
#include <vector>

#include "rift/pd/contact.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/loads.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// Moves the particles to the equilibrium of the internal forces and the loads at time t, the
/// residual ||F + b|| measured as dynamic relaxation measures it (relax). diagonal[i]: the
/// preconditioner per unit volume (DynamicRelaxation::fictitious_density). Call with the bonds
/// held (HeldBreaking). Returns converged = false where the iterations run out, a linear solve
/// takes far longer than the lattice's size suggests, a Newton step does not halve the residual, or
/// K p is not positive along a direction (forces that switch: a contact, an interface's friction),
/// with the particles at the last iterate whose forces were evaluated; stopped = true where a stop
/// signal came (core/stop_signal.hpp: read at each iteration, the solve is not resumable).
/// `observe(evaluations, residual)`, where given, after each iteration (a run's progress lines).
template <int D>
RelaxationResult solve_static_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                                          const std::vector<double>& diagonal, int max_iterations, double tolerance,
                                          const std::function<void(int, double)>& observe = {});

}  // namespace rift::pd
