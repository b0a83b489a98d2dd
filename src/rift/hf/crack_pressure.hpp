// Fluid pressure on the faces of a pre-crack and on the wall of a borehole. The bonds the crack cuts are
// not part of the solid, nor are those from the material to the borehole's lattice sites, but the fluid
// that fills the crack or the hole carries the isotropic stress -p I across them. Its force state is the
// one whose bond-pair stress (pd/stress.hpp) is -p I for a whole family,
//   T_i<xi> = -p d omega xi / m_i   (sum_j T_i<xi_ij> (x) xi_ij V_j = -p I: sum omega xi (x) xi V = m I / d),
// so each cut bond pushes its two ends apart with the force density
//   f_i = -p d omega (1/m_i + 1/m_j) |xi| V_j y_ij / |y_ij|,
// m_i = sum omega |xi|^2 V_j over i's whole family, its bonds and the cut ones, without the surface
// correction (which would count the crack faces as free surfaces and scale the kept bonds up). Summed over
// the cut bonds of a particle next to a straight crack this is the traction p on the face (Lehoucq and
// Silling 2008: the force flux of -p I across the crack plane). A fluid site of a borehole has the
// weighted volume of a whole family.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "rift/hf/fluid_network.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::hf {

/// Adds the pressure forces to m.body_force; pressure[s] is source s's current pressure (the scene's
/// cracks, then its boreholes). Between two particles the force follows the deformed bond; toward a
/// fluid site, which does not move, the reference one.
template <int D>
void add_crack_pressure(Model<D>& m, const std::vector<double>& pressure) {
  const CrackBonds& w = m.crack_bonds;
  if (w.neighbor.empty()) return;
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
      const int source = pressure_bond_source<D>(m, k, i);
      if (source < 0) continue;
      double p_fluid = pressure[static_cast<std::size_t>(source)];
      if (is_viscous(m.fluid_network, static_cast<std::size_t>(source)))  // the local pressure (viscous_fluid.hpp)
        p_fluid = w.neighbor[k] >= 0 ? 0.5 * (m.fluid_network.local_pressure[i] + m.fluid_network.local_pressure[static_cast<std::size_t>(w.neighbor[k])])
                                     : m.fluid_network.local_pressure[i];
      const double p = p_fluid * w.coefficient[k];
      const auto& xi = w.xi[k];
      const double length = w.length(static_cast<std::size_t>(k));
      Vec<D> eta;
      for (int q = 0; q < D; ++q) eta[q] = xi[q];
      if (w.neighbor[k] >= 0) eta = m.position[static_cast<std::size_t>(w.neighbor[k])] - m.position[i];
      const double scale = -p * length / norm<D>(eta);
      for (int q = 0; q < D; ++q) m.body_force[i][q] += scale * eta[q];
    }
}

}  // namespace rift::hf
