// Peridynamic stress of each particle in bond-pair form (the "partial stress" of Silling et al.
// 2007, sec. 12, as Peridigm writes it, with both ends of each bond averaged):
//   sigma_i = 1/2 sum_j (t_i<j> + t_j<i>) V_j (y_ij / |y_ij|) (x) xi_ij,
// t the force states of pmb.hpp, lps.hpp and ves.hpp (PMB: t_i<j> + t_j<i> is the bond force
// density). For a homogeneous deformation in the bulk t_i<j> = t_j<i> and this is the first
// Piola-Kirchhoff stress, sum_j T_i<j> (x) xi_ij V_j, of the material the model stands for; near
// free surfaces and cracks, where the family is cut, it is an estimate. Uses the dilatations of the
// last force evaluation. A failed interface bond adds 1/2 f (x) xi with f its contact force
// (interface_contact.hpp).
#pragma once
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/pd/interface_contact.hpp"
#include "rift/pd/lps.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/pmb.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The bond-pair stress of particle i (3 x 3, zero out of plane in 2D; not symmetrized).
template <int D>
void bond_pair_stress(const Model<D>& m, std::size_t i, double s[3][3]) {
  const auto& c = m.constants_of(i);
  const Bonds& b = m.bonds;
  const bool ves = c.model == scene::ModelKind::ves;
  const double a_dev = c.lps_deviatoric_coefficient(), lambda = c.viscous_fraction;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) s[p][q] = 0.0;
  const double a_i = a_dev / m.weighted_volume[i];
  const double pressure_i = pressure_factor<D>(c.kappa, m.dilatation[i], a_i, m.dilatation_coupling[i]);
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] == bond_broken) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const Vec<D> eta = m.position[j] - m.position[i];
    const Vec<D> xi_vec = m.reference_position[j] - m.reference_position[i];
    if (b.intact[k] == bond_interface_failed) {  // a frictional contact (interface_contact.hpp)
      const auto q = interface_entry<D>(m, i, k);
      if (q < 0) continue;
      const Vec<D> f = interface_contact_force<D>(m, i, j, k, static_cast<std::size_t>(q), nullptr);
      for (int p = 0; p < D; ++p)
        for (int r = 0; r < D; ++r) s[p][r] += 0.5 * f[p] * xi_vec[r];
      continue;
    }
    const double r = norm<D>(eta);
    const double xi = b.length(k);
    const double e = r - xi;
    const double omega = influence(c.influence, xi, c.horizon);
    double pair;
    if (c.model == scene::ModelKind::pmb) {
      pair = pmb_bond_force(c.micromodulus, omega, e / xi, b.correction(i, k), b.mirror_correction(j, k));
    } else {
      const double a_j = a_dev / m.weighted_volume[j];
      const double pressure_j = pressure_factor<D>(c.kappa, m.dilatation[j], a_j, m.dilatation_coupling[j]);
      const BodyInfo& body = m.bodies[m.body[i]];
      const std::size_t h = ves ? history_slot(b, body, i, k) : 0;
      const double eb_i = ves ? lambda * b.back_extension[h] : 0.0;
      const double eb_j = ves ? lambda * b.back_extension[mirror_history_slot(h)] : 0.0;
      const BondFactors &g_i = b.factors_of(i, k), &g_j = b.mirror_factors_of(j, k);
      const double b_i = c.surface_correction ? double(g_i.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[i]);
      const double b_j = c.surface_correction ? double(g_j.dilatation_weight) : omega * xi * dilatation_scale<D>(m.weighted_volume[j]);
      pair = force_state(b_i, pressure_i, a_i, g_i.correction, omega, e - m.dilatation[i] * xi / D - eb_i) +
             force_state(b_j, pressure_j, a_j, g_j.correction, omega, e - m.dilatation[j] * xi / D - eb_j);
    }
    const double scale = 0.5 * pair * b.volume(k) / r;
    for (int p = 0; p < D; ++p)
      for (int q = 0; q < D; ++q) s[p][q] += scale * eta[p] * xi_vec[q];
  }
}

/// Six components per particle: xx, yy, zz, xy, yz, xz (the symmetric part; zero out of plane in 2D).
template <int D>
std::vector<double> particle_stress(const Model<D>& m) {
  std::vector<double> out(6 * m.size(), 0.0);
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double s[3][3];
    bond_pair_stress<D>(m, i, s);
    double* o = &out[6 * i];
    o[0] = s[0][0], o[1] = s[1][1], o[3] = 0.5 * (s[0][1] + s[1][0]);
    if constexpr (D == 3) o[2] = s[2][2], o[4] = 0.5 * (s[1][2] + s[2][1]), o[5] = 0.5 * (s[0][2] + s[2][0]);
  }
  return out;
}

}  // namespace rift::pd
