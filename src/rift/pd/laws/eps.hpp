// Elastic-plastic state-based law (EPS; Mitchell 2011, SAND2011-3166, as LAMMPS peri/eps): the LPS
// with a plastic deviatoric extension e_p of each direction of every bond,
//   t_i<j> = b_ij p_i + a_i sigma_ij (e_d - e_p),   e_d = e - theta_i |xi| / d,
// perfectly plastic under the yield function f = ||t_d||^2 / 2 - psi_0 (eps.hpp: the return map,
// beta of each end in the pair force, so Newton's third law holds where LAMMPS's peri/eps takes i's
// dilatation and e_p for both halves). psi_0 (eps.hpp YieldShear), each particle's from its own
// family, makes a homogeneous pure shear yield at tau = sigma_Y / sqrt(3) (von Mises; Mitchell's
// 25 sigma_Y^2 / (8 pi delta^5) on the continuum's family in 3D with omega = 1). In 3D any
// homogeneous deformation then yields as J2 (the norm is |dev eps|), and with omega = 1 flows at
// sigma_Y; a 2D uniaxial stress yields at 2 sigma_Y / sqrt(3). The dilatation (and P) are the
// LPS's; e_p commits after each explicit step, and at each load step's equilibrium in dynamic
// relaxation (trials from the committed e_p between).
#pragma once
#include <vector>

#include "rift/pd/eps.hpp"
#include "rift/pd/laws/lps.hpp"

namespace rift::pd::laws {

struct Eps : OrdinaryStateBased<true> {
  static constexpr scene::ModelKind kind = scene::ModelKind::eps;
  static constexpr const char* name = "EPS";
  static constexpr const char* keyword = "eps";  // [materials] model = "eps"
  static constexpr const char* example_material = "yield_stress = 1.0e12\n";  // the material lines it needs beyond the elastic constants
  static constexpr bool commits_at_equilibrium = true;  // a history that dynamic relaxation commits at each load step

  /// sigma_Y; lambda = 1: the deviatoric term is measured from e_p.
  static void take_constants(MaterialConstants& c, const scene::Material& m) {
    c.yield_stress = m.yield_stress;
    c.viscous_fraction = 1.0;
  }

  /// The LPS's: the dilatation (and P), breaking the bonds past their limits.
  template <int D>
  static void first_pass(Model<D>& m, const BodyInfo& body, double history_dt, RowStates* rows) {
    Lps::first_pass<D>(m, body, history_dt, rows);
  }
  /// beta of each particle, the pair forces with the returned deviatoric states, and, where the step
  /// advances (history_dt > 0), e_p committed.
  template <int D>
  static void second_pass(Model<D>& m, const BodyInfo& body, double history_dt, const RowStates* given_rows) {
    const RowStates rows = given_rows ? *given_rows : whole_rows(m.bonds, body);
    std::vector<double>& beta = yield_scales<D>(m, body, rows);
    with_influence(body.constants.influence,
                   [&]<scene::Influence Omega>() { state_based_forces<D, Omega, true>(m, body, 0.0, &rows, beta.data()); });
    if (history_dt > 0.0) commit_plastic_extension<D>(m, body, rows, beta);
  }
  /// e_p committed at an equilibrium (dynamic relaxation's load step), from the last force evaluation's dilatations.
  template <int D>
  static void commit(Model<D>& m, const BodyInfo& body) {
    const RowStates rows = whole_rows(m.bonds, body);
    commit_plastic_extension<D>(m, body, rows, yield_scales<D>(m, body, rows));
  }

 private:
  /// beta of every particle of the window (the ghosts' from their owners): the calling thread's buffer.
  template <int D>
  static std::vector<double>& yield_scales(const Model<D>& m, const BodyInfo& body, const RowStates& rows) {
    static thread_local std::vector<double> beta;
    beta.assign(m.size(), 1.0);
    with_influence(body.constants.influence, [&]<scene::Influence Omega>() { plastic_yield_scales<D, Omega>(m, body, rows, beta); });
    m.refresh_ghosts(beta);
    return beta;
  }
};

}  // namespace rift::pd::laws
