// Peridynamic stress of each particle in bond-pair form (the "partial stress" of Silling et al.
// 2007, sec. 12, as Peridigm writes it, with both ends of each bond averaged):
//   sigma_i = 1/2 sum_j (t_i<j> + t_j<i>) V_j (y_ij / |y_ij|) (x) xi_ij,
// t the force states of the body's law (laws/registry.hpp; PMB: t_i<j> + t_j<i> is the bond force
// density). For a homogeneous deformation in the bulk t_i<j> = t_j<i> and this is the first
// Piola-Kirchhoff stress, sum_j T_i<j> (x) xi_ij V_j, of the material the model stands for; near
// free surfaces and cracks, where the family is cut, it is an estimate. Uses the dilatations of the
// last force evaluation. A bond a force stage holds (force_stages.hpp: a failed interface bond's
// frictional contact) adds 1/2 f (x) xi with f its force.
#pragma once
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/pd/force_stages.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// The bond-pair stress of particle i of `body`, whose law is Law (3 x 3, zero out of plane in 2D;
/// not symmetrized); `stages` the model's (force_stages_of).
template <int D, class Law>
void bond_pair_stress(const Model<D>& m, const ForceStages<D>* stages, const BodyInfo& body, std::size_t i, double s[3][3]) {
  const auto& c = body.constants;
  const Bonds& b = m.bonds;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) s[p][q] = 0.0;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] == bond_broken) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const Vec<D> eta = m.position[j] - m.position[i];
    const Vec<D> xi_vec = m.reference_position[j] - m.reference_position[i];
    if (b.intact[k] == bond_interface_failed) {  // held by a force stage
      Vec<D> f{};
      if (!stages || !stages->held_bond_force(m, i, j, k, f)) continue;
      for (int p = 0; p < D; ++p)
        for (int r = 0; r < D; ++r) s[p][r] += 0.5 * f[p] * xi_vec[r];
      continue;
    }
    const double r = norm<D>(eta);
    const double xi = b.length(k);
    const double e = r - xi;
    const double omega = influence(c.influence, xi, c.horizon);
    const double pair = Law::template pair_force_density<D>(m, body, i, j, k, e, xi, omega);
    const double scale = 0.5 * pair * b.volume(k) / r;
    for (int p = 0; p < D; ++p)
      for (int q = 0; q < D; ++q) s[p][q] += scale * eta[p] * xi_vec[q];
  }
}

/// Six components per particle: xx, yy, zz, xy, yz, xz (the symmetric part; zero out of plane in 2D).
template <int D>
std::vector<double> particle_stress(const Model<D>& m) {
  std::vector<double> out(6 * m.size(), 0.0);
  const ForceStages<D>* stages = force_stages_of(m);
  for (const BodyInfo& body : m.bodies)
    with_law(body.constants.model, [&]<class Law>() {
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
      for (std::size_t i = body.first; i < body.last; ++i) {
        double s[3][3];
        bond_pair_stress<D, Law>(m, stages, body, i, s);
        double* o = &out[6 * i];
        o[0] = s[0][0], o[1] = s[1][1], o[3] = 0.5 * (s[0][1] + s[1][0]);
        if constexpr (D == 3) o[2] = s[2][2], o[4] = 0.5 * (s[1][2] + s[2][1]), o[5] = 0.5 * (s[0][2] + s[2][0]);
      }
    });
  return out;
}

}  // namespace rift::pd
