// Linear peridynamic solid (LPS; Silling et al. 2007, eq. 88-92; 2D: Le, Chan and Schwartz 2014),
// ordinary state-based: the force state t_i<j> = b_ij p_i + a_i sigma_ij (e - theta_i |xi| / d), the
// energy W_i = kappa/2 theta_i^2 + a_i/2 sum_j sigma_ij (e - theta_i |xi| / d)^2 V_j (lps.hpp). Two
// passes: the dilatation (breaking there), then the forces.
#pragma once
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/critical_stretch.hpp"
#include "rift/pd/energy_runs.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/lps.hpp"

namespace rift::pd::laws {

/// t_i<j> + t_j<i> of bond k of row i (to j), extension e, of an ordinary state-based body; Viscous:
/// each end's deviatoric extension less lambda times its back extension (ves.hpp).
template <int D, bool Viscous>
double state_based_pair_force_density(const Model<D>& m, const BodyInfo& body, std::size_t i, std::size_t j, std::int64_t k, double e,
                                      double xi, double omega) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  const double a_dev = c.lps_deviatoric_coefficient(), lambda = c.viscous_fraction;
  const double a_i = a_dev / m.weighted_volume[i];
  const double pressure_i = pressure_factor<D>(c.kappa, m.dilatation[i], a_i, m.dilatation_coupling[i]);
  const double a_j = a_dev / m.weighted_volume[j];
  const double pressure_j = pressure_factor<D>(c.kappa, m.dilatation[j], a_j, m.dilatation_coupling[j]);
  const std::size_t h = Viscous ? history_slot(b, body, i, k) : 0;
  const double eb_i = Viscous ? lambda * b.back_extension[h] : 0.0;
  const double eb_j = Viscous ? lambda * b.back_extension[mirror_history_slot(h)] : 0.0;
  const BondFactors &g_i = b.factors_of(i, k), &g_j = b.mirror_factors_of(j, k);
  const double b_i = c.surface_correction ? double(g_i.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[i]);
  const double b_j = c.surface_correction ? double(g_j.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[j]);
  return force_state(b_i, pressure_i, a_i, g_i.correction, omega, e - m.dilatation[i] * xi / D - eb_i) +
         force_state(b_j, pressure_j, a_j, g_j.correction, omega, e - m.dilatation[j] * xi / D - eb_j);
}

/// What the ordinary state-based laws share: the dilatation read by the force pass, the LPS's
/// separation work, and the strain energy and bond-pair force of t = b p + a sigma (e_d - lambda e_h)
/// (History: a stored extension e_h of each direction of every bond, VES's e_b or EPS's e_p).
template <bool History>
struct OrdinaryStateBased {
  static constexpr bool state_based = true;  // the force pass reads the dilatations (and P) of both ends
  static constexpr bool bond_history = History;
  static constexpr int energy_moment_power = 2;  // the surface correction matches int omega |xi|^2 (the weighted volume)

  static double separation_work_per_stretch2(const MaterialConstants& c) { return pd::separation_work_per_stretch2(c, true); }

  template <int D>
  static void energy_densities(const Model<D>& m, const BodyInfo& body, double* w) {
    if (body.constants.surface_correction) strain_energy_densities<D, true, History, true>(m, body, w);
    else strain_energy_densities<D, true, History, false>(m, body, w);
  }
  template <int D>
  static double energy_density(const Model<D>& m, const BodyInfo& body, std::size_t i) {
    return state_based_energy_density<D, History>(m, body, i);
  }
  template <int D>
  static double pair_force_density(const Model<D>& m, const BodyInfo& body, std::size_t i, std::size_t j, std::int64_t k,
                                   double e, double xi, double omega) {
    return state_based_pair_force_density<D, History>(m, body, i, j, k, e, xi, omega);
  }
};

struct Lps : OrdinaryStateBased<false> {
  static constexpr scene::ModelKind kind = scene::ModelKind::lps;
  static constexpr const char* name = "LPS";
  static constexpr const char* keyword = "lps";  // [materials] model = "lps"
  static constexpr const char* example_material = "";  // the material lines it needs beyond the elastic constants
  static constexpr bool commits_at_equilibrium = false;  // a history that dynamic relaxation commits at each load step

  /// The law's own constants from the scene's material (make_constants does the elastic ones).
  static void take_constants(MaterialConstants&, const scene::Material&) {}

  /// The dilatation (and P) of a body's particles, breaking the bonds past their limits.
  template <int D>
  static void first_pass(Model<D>& m, const BodyInfo& body, double /*history_dt*/, RowStates* rows) {
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() { lps_dilatation<D, Omega>(m, body, rows); });
  }
  /// The pair forces, from every dilatation of the step.
  template <int D>
  static void second_pass(Model<D>& m, const BodyInfo& body, double /*history_dt*/, const RowStates* rows) {
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() { state_based_forces<D, Omega, false>(m, body, 0.0, rows); });
  }

  /// The history committed at an equilibrium (dynamic relaxation's load step): none.
  template <int D>
  static void commit(Model<D>&, const BodyInfo&) {}
};

}  // namespace rift::pd::laws
