// The names of the peridynamic core (pd/) that hydraulic fracture uses: hf/ works on a pd::Model,
// its bonds and runs, and the fluid state it holds (pd/fluid_state.hpp FluidNetwork, CrackBonds).
#pragma once
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/bonds.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/model.hpp"

namespace rift::hf {

using pd::Model;
using pd::Bonds, pd::BondFactors, pd::BondRun, pd::FamilyOffset, pd::RowStates, pd::RunMask;
using pd::bond_broken, pd::bond_intact, pd::bond_interface_failed, pd::kept_row_count, pd::max_run_length, pd::simd_ends_apart;
using pd::PairForcesToBuffers;
using pd::CrackBonds, pd::CrackSurface, pd::FluidNetwork, pd::InterfaceBonds, pd::InterfaceLaw, pd::NetworkEnd, pd::NetworkRunTerms,
    pd::ViscousFluid, pd::network_load_block;
using pd::LawTraits, pd::MaterialConstants;
using pd::family_moment, pd::influence;
using pd::Numbering, pd::set_on_any_rank;
using pd::PassBuffer, pd::component, pd::pass_buffer, pd::short_run;
using pd::law_traits, pd::pmb_bond_force, pd::pmb_factor, pd::dilatation_scale, pd::pressure_factor, pd::force_state;
using pd::PairForcesToEnds, pd::add_pair_forces_to_run_ends;

}  // namespace rift::hf
