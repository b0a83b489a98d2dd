// Every member of a peridynamic run's state, listed once for the checkpoint (io/checkpoint.hpp):
// `visit(archive, x)` calls archive("name", member) for each member of x, and the checkpoint's
// writer and reader both go through it, so what is written is what is read back.
//
// The whole model is listed, the arrays a restart could rebuild from the scene (bonds, families)
// too: a restart then takes nothing from a second discretization but its shape, and a member whose
// state changes in a run cannot be left out by a wrong guess that it does not. The sizes below
// fail the build when a member is added to one of these structs and not to its list here.
#pragma once
#include "rift/pd/contact.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

#if defined(__x86_64__) && defined(__GLIBCXX__)
// 24 bytes per std::vector, 32 per std::string (libstdc++, x86_64); a bool or int member padded to 8
static_assert(sizeof(FamilyOffset) == 7 * 8, "a member was added to FamilyOffset: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(MaterialConstants) == 3 * 4 + 4 + 13 * 8 + 2 * 8, "a member was added to MaterialConstants: list it in pd/checkpoint_state.hpp");
// (the states carry a count of their changes, and the kept rows and whether the back extensions are
// at rest are caches: none is saved)
static_assert(sizeof(Bonds) == 14 * 24 + 8 + 8 + sizeof(Bonds::KeptRows), "a member was added to Bonds: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(CrackBonds) == 7 * 24, "a member was added to CrackBonds: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(InterfaceLaw) == 12 * 8 + 24 + 8 * 5 + 8, "a member was added to InterfaceLaw: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(InterfaceBonds) == 8 * 24, "a member was added to InterfaceBonds: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(ViscousFluid) == 6 * 8 + 2 * 24, "a member was added to ViscousFluid: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(CrackSurface) == 8 + 9 * 24 + 2 * 8, "a member was added to CrackSurface: list it in pd/checkpoint_state.hpp");
// (the bond states' version its counts were made at, and the network load's run terms, are caches:
// not saved; the recent crossing breaks are saved merged into crossing_broken)
static_assert(sizeof(FluidNetwork) == 28 * 24 + 2 * 8 + 2 * 8 + sizeof(CrackSurface), "a member was added to FluidNetwork: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(Platen) == 8 + 24, "a member was added to Platen: list it in pd/checkpoint_state.hpp");
static_assert(sizeof(BodyInfo) == 32 + 10 * 8 + 2 * 24 + sizeof(MaterialConstants), "a member was added to BodyInfo: list it in pd/checkpoint_state.hpp");
// (Contact's beyond_ is not state: a distributed run gathers it at each rebuild of the pairs)
static_assert(sizeof(Contact<3>) == 8 + 2 * 8 + 5 * 24 + 8 + 2 * 24 + sizeof(BeyondWindow<3>),
              "a member was added to Contact: list it in its visit_state");
// (its observer prints a run's progress: not state)
static_assert(sizeof(DynamicRelaxation<3>) == 24 + 8 + 8 + 8 + 2 * 24 + 8 + 8 + 8 + sizeof(std::function<void(int, double)>), "a member was added to DynamicRelaxation: list it in its visit_state");
static_assert(sizeof(Model<3>) == 19 * 24 + sizeof(Numbering) + sizeof(Bonds) + sizeof(CrackBonds) + sizeof(InterfaceBonds) + sizeof(FluidNetwork) + 4 * 8 + 2 * 8,
              "a member was added to Model: list it in pd/checkpoint_state.hpp");
// (Model's owned_ranges, numbering, cut_rows and ghosts are not state: a distributed run makes them at its
// start; nor are its coupling, which the scene's loads install, and its force stages, which the run's
// set-up installs)
#endif

// structs with padding, member by member (io/checkpoint.hpp visitable)
template <class A>
void visit(A& a, FamilyOffset& f) {
  a("family.xi", f.xi), a("family.length", f.length), a("family.inverse_length", f.inverse_length), a("family.volume", f.volume);
  a("family.mirror", f.mirror);
}

template <class A>
void visit(A& a, MaterialConstants& c) {
  a("constants.model", c.model), a("constants.influence", c.influence), a("constants.dimension", c.dimension);
  a("constants.horizon", c.horizon), a("constants.spacing", c.spacing), a("constants.thickness", c.thickness);
  a("constants.density", c.density), a("constants.kappa", c.kappa), a("constants.shear_modulus", c.shear_modulus);
  a("constants.micromodulus", c.micromodulus), a("constants.equivalent_micromodulus", c.equivalent_micromodulus);
  a("constants.critical_stretch", c.critical_stretch), a("constants.alpha", c.alpha), a("constants.breakable", c.breakable);
  a("constants.normal_stress_failure", c.normal_stress_failure), a("constants.viscous_fraction", c.viscous_fraction);
  a("constants.relaxation_time", c.relaxation_time), a("constants.yield_stress", c.yield_stress);
  a("constants.surface_correction", c.surface_correction);
}

template <class A>
void visit(A& a, Bonds& b) {
  a("bonds.offset", b.offset), a("bonds.neighbor", b.neighbor), a("bonds.family", b.family), a("bonds.intact", b.intact.replace());
  a("bonds.families", b.families), a("bonds.factor_row", b.factor_row), a("bonds.factors", b.factors);
  a("bonds.back_extension", b.back_extension), a("bonds.last_extension", b.last_extension);
  a("bonds.history_dilatation", b.history_dilatation), a("bonds.deviatoric_sum", b.deviatoric_sum), a("bonds.back_sum", b.back_sum);
  a("bonds.intact_weighted_volume", b.intact_weighted_volume), a("bonds.summed_bonds", b.summed_bonds);
  b.back_extension_at_rest = false;  // a cache (bonds.hpp): a restored history need not be zero
}

template <class A>
void visit(A& a, CrackBonds& c) {
  a("crack_bonds.offset", c.offset), a("crack_bonds.neighbor", c.neighbor), a("crack_bonds.volume", c.volume);
  a("crack_bonds.source", c.source), a("crack_bonds.xi", c.xi), a("crack_bonds.fluid_weighted_volume", c.fluid_weighted_volume);
  a("crack_bonds.coefficient", c.coefficient);
}

template <class A>
void visit(A& a, InterfaceLaw& l) {
  a("law.point", l.point), a("law.normal", l.normal), a("law.tangent", l.tangent), a("law.binormal", l.binormal);
  a("law.polygon", l.polygon), a("law.length", l.length), a("law.tensile_strength", l.tensile_strength), a("law.cohesion", l.cohesion);
  a("law.friction_coefficient", l.friction_coefficient), a("law.near_side", l.near_side);
  a("law.in_situ_normal_compression", l.in_situ_normal_compression);
}

template <class A>
void visit(A& a, InterfaceBonds& i) {
  a("interface_bonds.offset", i.offset), a("interface_bonds.slot", i.slot), a("interface_bonds.interface", i.interface);
  a("interface_bonds.laws", i.laws), a("interface_bonds.slip", i.slip), a("interface_bonds.across_crack", i.across_crack);
  a("interface_bonds.particles", i.particles), a("interface_bonds.strain", i.strain);
}

template <class A>
void visit(A& a, ViscousFluid& v) {
  a("viscous.viscosity", v.viscosity), a("viscous.started", v.started), a("viscous.stored_time", v.stored_time);
  a("viscous.trial_time", v.trial_time), a("viscous.stored_inlet", v.stored_inlet), a("viscous.trial_inlet", v.trial_inlet);
  a("viscous.stored", v.stored), a("viscous.trial", v.trial);
}

template <class A>
void visit(A& a, CrackSurface& c) {
  a("crack_surface.made", c.made), a("crack_surface.patches", c.patches), a("crack_surface.planes", c.planes);
  a("crack_surface.moments", c.moments), a("crack_surface.sorted_patches", c.sorted_patches), a("crack_surface.decided", c.decided);
  a("crack_surface.cell", c.cell), a("crack_surface.reach", c.reach), a("crack_surface.cell_keys", c.cell_keys);
  a("crack_surface.in_cell", c.in_cell), a("crack_surface.row_keys", c.row_keys), a("crack_surface.row_first", c.row_first);
}

template <class A>
void visit(A& a, FluidNetwork& f) {
  f.settle_crossing_broken();  // the recent ones saved in the one list (and none left beside a restored one)
  f.network_run_terms.clear();  // a cache of the network ends' terms (hf/network_load.hpp): made again from the ends saved
  a("fluid.source", f.source), a("fluid.relabel", f.relabel), a("fluid.pressure_bonds", f.pressure_bonds), a("fluid.bond_counts", f.bond_counts);
  a("fluid.outer_surface", f.outer_surface), a("fluid.in_crack", f.in_crack), a("fluid.immersed", f.immersed);
  a("fluid.pore_stretch", f.pore_stretch), a("fluid.open_interface_bonds", f.open_interface_bonds);
  visit(a, f.crack_surface);
  a("fluid.crossing_broken", f.crossing_broken), a("fluid.load_changed", f.load_changed), a("fluid.load_changed_mark", f.load_changed_mark);
  a("fluid.load_from_scratch", f.load_from_scratch), a("fluid.network_load", f.network_load), a("fluid.is_end", f.is_end);
  a("fluid.network_ends", f.network_ends), a("fluid.dry", f.dry), a("fluid.sealed", f.sealed), a("fluid.has_network", f.has_network);
  a("fluid.reference_volume", f.reference_volume), a("fluid.pressure", f.pressure), a("fluid.pore_pressure", f.pore_pressure);
  a("fluid.cavity_volume", f.cavity_volume), a("fluid.vented", f.vented), a("fluid.broke_through", f.broke_through);
  a("fluid.escaped_volume", f.escaped_volume), a("fluid.viscous", f.viscous), a("fluid.local_pressure", f.local_pressure);
  a("fluid.local_pore_pressure", f.local_pore_pressure);
}

template <class A>
void visit(A& a, Platen& p) {
  a("platen.axis", p.axis), a("platen.particles", p.particles);
}

template <class A>
void visit(A& a, BodyInfo& b) {
  a("body.name", b.name), a("body.first", b.first), a("body.last", b.last), a("body.first_family", b.first_family);
  a("body.family_count", b.family_count), a("body.slab_length", b.slab_length), a("body.slab_count", b.slab_count), a("body.runs", b.runs), a("body.slab_runs", b.slab_runs);
  a("body.history_base", b.history_base), a("body.origin", b.origin), a("body.whole_first", b.whole_first);
  a("body.first_slab", b.first_slab);
  a("body.constants", b.constants);
}

template <class A, int D>
void visit(A& a, Model<D>& m) {
  a("reference_position", m.reference_position), a("position", m.position), a("velocity", m.velocity), a("force", m.force);
  a("body_force", m.body_force), a("volume", m.volume), a("weighted_volume", m.weighted_volume), a("dilatation", m.dilatation);
  a("dilatation_coupling", m.dilatation_coupling), a("stretch_limit", m.stretch_limit), a("next_stretch_limit", m.next_stretch_limit);
  a("damage", m.damage), a("failure_strain", m.failure_strain), a("body", m.body), a("constrained", m.constrained);
  a("platens", m.platens);
  visit(a, m.bonds);
  visit(a, m.crack_bonds);
  visit(a, m.interface_bonds);
  visit(a, m.fluid_network);
  a("bodies", m.bodies), a("dimension", m.dimension), a("thickness", m.thickness), a("time", m.time);
}

template <class A, int D>
void visit(A& a, Contact<D>& c) {
  c.visit_state(a);
}

template <class A, int D>
void visit(A& a, DynamicRelaxation<D>& r) {
  r.visit_state(a);
}

}  // namespace rift::pd
