// Viscoelastic state-based law (VES; Mitchell 2011, as LAMMPS peri/ves): the LPS with a share lambda
// of the deviatoric extension relaxing towards a back extension e_b with time constant tau,
// t_i<j> = b_ij p_i + a_i sigma_ij [(1 - lambda) e_d + lambda (e_d - e_b)] (ves.hpp); e_b is a
// history of each direction of every bond, advanced by the force pass.
#pragma once
#include "rift/pd/laws/lps.hpp"
#include "rift/pd/ves.hpp"

namespace rift::pd::laws {

struct Ves : OrdinaryStateBased<true> {
  static constexpr scene::ModelKind kind = scene::ModelKind::ves;
  static constexpr const char* name = "VES";
  static constexpr const char* keyword = "ves";  // [materials] model = "ves"
  static constexpr const char* example_material = "viscous_fraction = 0.5\nrelaxation_time = 1.0e-4\n";  // the material lines it needs beyond the elastic constants
  static constexpr bool commits_at_equilibrium = false;  // a history that dynamic relaxation commits at each load step

  static void take_constants(MaterialConstants& c, const scene::Material& m) {
    c.viscous_fraction = m.viscous_fraction;
    c.relaxation_time = m.relaxation_time;
  }

  /// The dilatation, breaking, and the history's sums over each row (ves.hpp ves_dilatation).
  template <int D>
  static void first_pass(Model<D>& m, const BodyInfo& body, double history_dt, RowStates* rows) {
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() { ves_dilatation<D, Omega>(m, body, history_dt, rows); });
  }
  /// The pair forces, advancing the back extensions over history_dt. With the history held (0) and
  /// every back extension zero (bonds.hpp back_extension_at_rest) the deviatoric extension less lambda
  /// times zero is the LPS's to the bit, and the LPS pass serves without reading the history.
  template <int D>
  static void second_pass(Model<D>& m, const BodyInfo& body, double history_dt, const RowStates* rows) {
    const bool viscous = history_dt > 0.0 || !m.bonds.back_extension_at_rest;
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() {
      if (viscous) state_based_forces<D, Omega, true>(m, body, history_dt, rows);
      else state_based_forces<D, Omega, false>(m, body, 0.0, rows);
    });
  }

  /// The history committed at an equilibrium (dynamic relaxation's load step): none.
  template <int D>
  static void commit(Model<D>&, const BodyInfo&) {}
};

}  // namespace rift::pd::laws
