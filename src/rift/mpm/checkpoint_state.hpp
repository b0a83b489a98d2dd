// Every member of a material point run's state, listed once for the checkpoint (io/checkpoint.hpp),
// as pd/checkpoint_state.hpp does for peridynamics: the material points, the grid, the bodies and
// the explicit cracks. The sizes below fail the build when a member is added to one of these
// structs and not to its list here. The solver's other members are taken anew in every step
// before they are read (the stencils, the scatter's buffers, the crack fields of the points),
// and Solver::visit_state lists the one that lasts, the crack particles.
#pragma once
#include <Eigen/Core>

#include "rift/mpm/crack.hpp"
#include "rift/mpm/model.hpp"

namespace rift::material {

#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(Constants) == 8 + 6 * 8, "a member was added to material::Constants: list it in mpm/checkpoint_state.hpp");
static_assert(sizeof(State<2>) == 3 * 32 + 8 + 8, "a member was added to material::State: list it in mpm/checkpoint_state.hpp");
#endif

// with padding: member by member
template <class A>
void visit(A& a, Constants& c) {
  a("constants.kind", c.kind), a("constants.density", c.density), a("constants.lambda", c.lambda);
  a("constants.shear_modulus", c.shear_modulus), a("constants.bulk_modulus", c.bulk_modulus);
  a("constants.yield_stress", c.yield_stress), a("constants.hardening_modulus", c.hardening_modulus);
}

template <class A, int D>
void visit(A& a, State<D>& s) {
  a("state.stress", s.stress), a("state.strain", s.strain), a("state.plastic_strain", s.plastic_strain);
  a("state.equivalent_plastic_strain", s.equivalent_plastic_strain);
}

}  // namespace rift::material

namespace rift::mpm {

#if defined(__x86_64__) && defined(__GLIBCXX__)
// 24 bytes per std::vector, 32 per std::string (libstdc++, x86_64)
static_assert(sizeof(Particles<2>) == 11 * 24, "a member was added to Particles: list it in mpm/checkpoint_state.hpp");
// (Grid::offset is not listed: a checkpoint holds the whole grid, offset 0)
static_assert(sizeof(Grid<2>) == 2 * 8 + 8 + 3 * 8 + 8 + 3 * 8 + 8 * 24, "a member was added to Grid: list it in mpm/checkpoint_state.hpp");
static_assert(sizeof(BodyInfo) == 32 + 2 * 8 + sizeof(material::Constants), "a member was added to BodyInfo: list it in mpm/checkpoint_state.hpp");
static_assert(sizeof(Model<2>) == sizeof(Particles<2>) + sizeof(Grid<2>) + 24 + 4 * 8, "a member was added to Model: list it in mpm/checkpoint_state.hpp");
static_assert(sizeof(CrackSet::Crack) == 3 * 24 + 2 * 16, "a member was added to CrackSet::Crack: list it in mpm/checkpoint_state.hpp");
static_assert(sizeof(CrackTip) == 2 * 8, "a member was added to CrackTip: list it in mpm/checkpoint_state.hpp");
#endif

template <class A, int D>
void visit(A& a, Particles<D>& p) {
  a("points.position", p.position), a("points.reference_position", p.reference_position), a("points.velocity", p.velocity);
  a("points.external_force", p.external_force), a("points.mass", p.mass), a("points.volume", p.volume);
  a("points.reference_volume", p.reference_volume), a("points.deformation_gradient", p.deformation_gradient);
  a("points.affine_velocity", p.affine_velocity), a("points.state", p.state), a("points.body", p.body);
}

template <class A, int D>
void visit(A& a, Grid<D>& g) {
  a("grid.origin", g.origin), a("grid.cell_size", g.cell_size), a("grid.nodes", g.nodes), a("grid.fields", g.fields);
  a("grid.mass", g.mass), a("grid.momentum", g.momentum), a("grid.force", g.force), a("grid.velocity", g.velocity);
  a("grid.velocity_start", g.velocity_start), a("grid.mass_gradient", g.mass_gradient), a("grid.volume", g.volume);
  a("grid.displacement", g.displacement);
}

template <class A>
void visit(A& a, BodyInfo& b) {
  a("body.name", b.name), a("body.first", b.first), a("body.last", b.last), a("body.constants", b.constants);
}

template <class A, int D>
void visit(A& a, Model<D>& m) {
  visit(a, m.particles);
  visit(a, m.grid);
  a("bodies", m.bodies), a("shape", m.shape), a("particle_half_width", m.particle_half_width), a("thickness", m.thickness);
  a("time", m.time);
}

template <class A>
void visit(A& a, CrackSet::Crack& c) {
  a("crack.points", c.points), a("crack.above", c.above), a("crack.below", c.below), a("crack.lo", c.lo), a("crack.hi", c.hi);
}

template <class A>
void visit(A& a, CrackTip& t) {
  a("tip.crack", t.crack), a("tip.end", t.end);
}

}  // namespace rift::mpm
