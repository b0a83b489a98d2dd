// Static equilibrium of a body whose bonds are held (the in-situ stage), by preconditioned conjugate
// gradients (Hestenes and Stiefel 1952; Saad 2003, algorithm 9.1), matrix free: the stiffness K
// times a direction p is the change of the forces over a probe along p, K p = -(F(x + e p) -
// F(x)) / e, at a fixed base point x. The forces of a held body are linear in the displacements up
// to the geometric terms (of the order of the strain, 1e-4 here), so the iterations are Newton's:
// once the linear residual is under a hundredth of the base's, the forces are evaluated at the
// iterate, which becomes the next base. The preconditioner is the dynamic relaxation's diagonal
// (Kilic and Madenci 2010, eq. 10, the row sum of the stiffness), a platen (platens.hpp) one unknown
// with its particles' summed diagonal, plus a coarse space of aggregates (coarse_space.hpp) where
// the body has no platen and is three aggregates across; a free body's rigid motions are projected
// out of the preconditioned residual (rigid_motion.hpp; a deflated conjugate gradient). With the
// diagonal alone the iterations go as the lattice's sites along the body (the square root of K's
// condition number), as dynamic relaxation's at its best damping; the coarse space makes them go as
// an aggregate's sites across. The thesis example at 1 mm: 227 force evaluations (81 of them the
// coarse operator's probes), 510 with the diagonal alone, dynamic relaxation 978 and its 50 power
// iterations.
#pragma once
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
template <int D>
RelaxationResult solve_static_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                                          const std::vector<double>& diagonal, int max_iterations, double tolerance);

}  // namespace rift::pd
