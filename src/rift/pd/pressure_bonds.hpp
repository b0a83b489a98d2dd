// The pressure bonds of a model (fluid_state.hpp CrackBonds), made with the model: the bonds a pre-crack
// cuts and those from a borehole's wall to its fluid sites, which carry the fluid's pressure
// (hf/crack_pressure.hpp). Their coefficients d omega V_j (1/m_i + 1/m_j) take the whole-family weighted
// volumes m, without the surface correction; a particle whose whole family falls short of a full one
// is on the body's outer surface (where a fluid escapes, hf/fluid_network.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Whole-family weighted volumes m_i = sum omega |xi|^2 V_j over every bond ever in i's family
/// (intact or broken) and the bonds a pressurized pre-crack cut, without the surface correction.
template <int D>
std::vector<double> whole_family_weighted_volumes(const Model<D>& m) {
  const std::size_t n = m.size();
  std::vector<double> whole(n, 0.0);
  const Bonds& b = m.bonds;
  const CrackBonds& w = m.crack_bonds;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = m.constants_of(i);
    double sum = 0.0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
      sum += influence(c.influence, b.length(k), c.horizon) * b.length(k) * b.length(k) * b.volume(k);
    if (!w.offset.empty())
      for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
        const double xi = w.length(static_cast<std::size_t>(k));
        sum += influence(c.influence, xi, c.horizon) * xi * xi * w.volume[k];
      }
    whole[i] = sum;
  }
  return whole;
}

/// Particles on the outer free surface of their body: whole-family weighted volume (every bond ever
/// in the family, and those a pre-crack or borehole cut) under `outer_surface_fraction` of a full
/// family's, the continuum int omega |xi|^2 dV. With a horizon of 3 spacings a particle on a flat
/// face keeps 0.57 of it, one a row deeper 0.73 (2D); the faces of cracks and boreholes keep all of it.
inline constexpr double outer_surface_fraction = 0.65;

template <int D>
std::vector<std::uint8_t> outer_surface_particles(const Model<D>& m, const std::vector<double>& whole) {
  std::vector<std::uint8_t> outer(m.size(), 0);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& c = m.constants_of(i);
    outer[i] = whole[i] < outer_surface_fraction * family_moment(D, c.influence, c.horizon, c.thickness, 2) ? 1 : 0;
  }
  return outer;
}

/// The coefficients d omega V_j (1/m_i + 1/m_j) of the pressure-carrying bonds (after the weighted
/// volumes; m over whole families), and which particles are on the outer surface.
template <int D>
void prepare_pressure_bonds(Model<D>& m) {
  CrackBonds& w = m.crack_bonds;
  if (w.neighbor.empty()) return;
  m.fluid_network.pressure_bonds = true;
  const std::vector<double> whole = whole_family_weighted_volumes<D>(m);
  m.fluid_network.outer_surface = outer_surface_particles<D>(m, whole);
  w.coefficient.assign(w.neighbor.size(), 0.0);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& c = m.constants_of(i);
    for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
      const double m_j = w.neighbor[k] >= 0 ? whole[static_cast<std::size_t>(w.neighbor[k])] : w.fluid_weighted_volume[k];
      w.coefficient[k] = D * influence(c.influence, w.length(static_cast<std::size_t>(k)), c.horizon) * w.volume[k] * (1.0 / whole[i] + 1.0 / m_j);
    }
  }
}

}  // namespace rift::pd
