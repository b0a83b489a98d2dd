// Prototype microelastic brittle law (PMB; Silling and Askari 2005, eq. 15-17, 23-25): a bond force
// f = c omega(|xi|) s V_j along the deformed bond, s = (|y| - |xi|) / |xi|, and the strain energy
// W_i = c/4 sum_j g_i omega s^2 |xi| V_j; a bond breaks past min(s0_i, s0_j). One pass, forces and
// breaking together (pmb.hpp); it reads no dilatation.
#pragma once
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/critical_stretch.hpp"
#include "rift/pd/energy_runs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/pmb.hpp"

namespace rift::pd::laws {

struct Pmb {
  static constexpr scene::ModelKind kind = scene::ModelKind::pmb;
  static constexpr const char* name = "PMB";
  static constexpr const char* keyword = "pmb";  // [materials] model = "pmb"
  static constexpr const char* example_material = "";  // the material lines it needs beyond the elastic constants
  static constexpr bool state_based = false;  // no dilatation: one pass, nothing for the ghosts between passes
  static constexpr bool bond_history = false;
  static constexpr bool commits_at_equilibrium = false;  // a history that dynamic relaxation commits at each load step
  static constexpr int energy_moment_power = 1;  // the surface correction matches int omega |xi| s^2 (surface_correction.cpp)

  /// The law's own constants from the scene's material (make_constants does the elastic ones).
  static void take_constants(MaterialConstants&, const scene::Material&) {}

  /// The work to separate two half-spaces per unit area over s0^2 (G0 = gamma s0^2; critical_stretch.cpp).
  static double separation_work_per_stretch2(const MaterialConstants& c) { return pmb_separation_work_per_stretch2(c); }

  /// The forces and the breaking of a body's bonds (history_dt and rows unused: no state between passes).
  template <int D>
  static void first_pass(Model<D>& m, const BodyInfo& body, double /*history_dt*/, RowStates* /*rows*/) {
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() { pmb_forces<D, Omega>(m, body); });
  }
  template <int D>
  static void second_pass(Model<D>&, const BodyInfo&, double, const RowStates*) {}

  /// The history committed at an equilibrium (dynamic relaxation's load step): none.
  template <int D>
  static void commit(Model<D>&, const BodyInfo&) {}

  template <int D>
  static void energy_densities(const Model<D>& m, const BodyInfo& body, double* w) {
    if (body.constants.surface_correction) strain_energy_densities<D, false, false, true>(m, body, w);
    else strain_energy_densities<D, false, false, false>(m, body, w);
  }
  template <int D>
  static double energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
    return pmb_energy_density<D>(m, body, i);
  }

  /// t_i<j> + t_j<i> of bond k of row i (to j): the bond force density per V_j (bond-pair stress, stress.hpp).
  template <int D>
  static double pair_force_density(const Model<D>& m, const BodyInfo& body, std::size_t i, std::size_t j, std::int64_t k,
                                   double e, double xi, double omega) {
    const Bonds& b = m.bonds;
    return pmb_bond_force(body.constants.micromodulus * omega, e / xi, pmb_factor(b.correction(i, k), b.mirror_correction(j, k)));
  }
};

}  // namespace rift::pd::laws
