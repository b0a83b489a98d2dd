// Pre-existing fractures (scene::Interface: a joint, a bedding plane, the paper sheet cast into the blocks
// of Zhou et al. 2008). The bonds that cross one keep the rock's stiffness until the interface law fails;
// then each is a frictional contact (interface_contact.hpp, pd/bonds.hpp bond_interface_failed): the faces
// press and slide with Coulomb friction, or open, and the fluid that reaches them enters where they are
// apart (hf/fluid_network.hpp). The law of bond i-j, evaluated before each force evaluation with the last
// one's positions, takes t = sigma n, sigma the mean of i's and j's rock stress from the strain of their
// intact bonds (pd/bulk_strain.hpp, rock_stress; that strain is also the reference of failed bonds' opening),
// sigma_n = -n . t, tau = t - (n . t) n, p the interface's fluid pressure at either end (pressure_in_interface):
//   tension: p - sigma_n > T (a stress: in plane strain a bond stretches under compression, by Poisson);
//   shear, Mohr-Coulomb (the thesis' EQ 4.1-4.2): |tau| > tau_0 + mu max(sigma_n - p, 0).
// The rock's own critical stretch still applies to these bonds. Both ends evaluate the same symmetric
// test, so each row breaks its own copy of the bond.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "rift/geomech/interface_contact.hpp"
#include "rift/parallel/team.hpp"
#include "rift/pd/bulk_strain.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/pd/model.hpp"

namespace rift::geomech {

using pd::Bonds, pd::FluidNetwork, pd::MaterialConstants, pd::bond_intact, pd::bulk_strain, pd::refresh_ghost_bond_states;

/// The law of the interface that bond k of row i crosses (nullptr for a bond across none).
template <int D>
const InterfaceLaw* interface_of_bond(const Model<D>& m, std::size_t i, std::int64_t k) {
  const auto q = interface_entry<D>(m, i, k);
  return q < 0 ? nullptr : &m.interface_bonds.laws[m.interface_bonds.interface[static_cast<std::size_t>(q)]];
}

/// The pressure of the fluid inside the interface at particle i: its pore pressure where one of its
/// failed interface bonds holds fluid (faces apart, wet at both ends), else 0. Fluid in a fracture
/// that comes within a horizon of the interface (its broken bonds wet every particle within a
/// horizon of it, and some of them cross the interface's plane) acts on the interface through the
/// pressure on those bonds, not as a pore pressure of the interface's bonds: at a 90-degree
/// interface it took the fluid pressure off the normal stress of every bond of the particles a
/// horizon short of it, and the interface slipped around the fracture's tip.
template <int D>
double pressure_in_interface(const Model<D>& m, std::size_t i) {
  const FluidNetwork& f = m.fluid_network;
  const InterfaceBonds& ib = m.interface_bonds;
  if (f.source.empty() || f.source[i] < 0) return 0.0;
  for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
    const auto k = ib.slot[static_cast<std::size_t>(q)];
    if (m.bonds.intact[static_cast<std::size_t>(k)] != bond_interface_failed) continue;
    const auto j = static_cast<std::size_t>(m.bonds.neighbor[static_cast<std::size_t>(k)]);
    if (f.source[j] != f.source[i]) continue;
    if (interface_faces_apart<D>(m, k, i, j, ib.laws[ib.interface[static_cast<std::size_t>(q)]]))
      return f.pressure[static_cast<std::size_t>(f.source[i])];
  }
  return 0.0;
}

/// The stress of the rock around a particle from its strain (pd/bulk_strain.hpp) by isotropic
/// elasticity with the body's moduli: sigma = (kappa - 2G/3) tr(eps) I + 2G eps (3D), in plane
/// (kappa - G) tr(eps) I + 2G eps (2D, kappa the dimension's bulk modulus). Unlike the bond-pair
/// stress, it stays right on a particle whose family a crack has cut (the shape tensor is taken over
/// the bonds left): beside a fracture that reaches a 90-degree interface the bond-pair stress lost up
/// to a third of the interface's normal compression. The viscoelastic model's stress is taken with
/// its instantaneous moduli.
template <int D>
std::array<double, 9> rock_stress(const MaterialConstants& c, const std::array<double, 9>& eps) {
  const double G = c.shear_modulus, lambda = c.lame_lambda();
  double trace = 0.0;
  for (int a = 0; a < D; ++a) trace += eps[4 * a];
  std::array<double, 9> sigma{};
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) sigma[3 * a + b] = 2.0 * G * eps[3 * a + b] + (a == b ? lambda * trace : 0.0);
  return sigma;
}

/// The strain of the interface particles' rock (InterfaceBonds::strain): each owned particle's from
/// its bonds; on N ranks the ghosts' from their owners (a ghost's row is cut to the window), D x D
/// values a particle.
template <int D>
void update_interface_strain(Model<D>& m) {
  InterfaceBonds& ib = m.interface_bonds;
  const auto& rows = ib.particles;
  ib.strain.resize(rows.size());
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    if (m.owns(i)) ib.strain[r] = bulk_strain<D>(m, i);
  }
  if (!m.ghosts) return;
  constexpr std::size_t width = D * D;
  std::vector<double> field(m.size() * width, 0.0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    if (!m.owns(i)) continue;
    for (int p = 0; p < D; ++p)
      for (int q = 0; q < D; ++q) field[i * width + static_cast<std::size_t>(D * p + q)] = ib.strain[r][static_cast<std::size_t>(3 * p + q)];
  }
  m.refresh_ghosts(field, width);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    if (m.owns(i)) continue;
    ib.strain[r] = {};
    for (int p = 0; p < D; ++p)
      for (int q = 0; q < D; ++q) ib.strain[r][static_cast<std::size_t>(3 * p + q)] = field[i * width + static_cast<std::size_t>(D * p + q)];
  }
}

/// Fails the intact bonds across interfaces whose law is exceeded (see the top of this file). On N
/// ranks (pd/window.hpp) a rank decides the bonds with an owned end, from the ghosts' bond states and
/// strains as their owners have them; the bonds between two ghosts are their owners'.
template <int D>
void apply_interface_law(Model<D>& m) {
  InterfaceBonds& ib = m.interface_bonds;
  if (m.ghosts ? ib.laws.empty() : ib.empty()) return;  // on N ranks every rank takes part in the exchanges
  refresh_ghost_bond_states<D>(m);
  update_interface_strain<D>(m);
  Bonds& b = m.bonds;
  const auto& rows = ib.particles;
  auto owned = [&](std::size_t i) { return m.owns(i); };
  std::vector<std::array<double, 9>> stress(rows.size());
  std::vector<double> pressure(rows.size());
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) stress[r] = rock_stress<D>(m.constants_of(static_cast<std::size_t>(rows[r])), ib.strain[r]);
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) pressure[r] = pressure_in_interface<D>(m, static_cast<std::size_t>(rows[r]));  // reads both ends' strains
  std::uint8_t* const state = b.intact.writable();
  bool failed = false;
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static) reduction(|| : failed)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    if (!m.constants_of(i).breakable) continue;
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
      if (b.intact[k] != bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (!owned(i) && !owned(j)) continue;  // between two ghosts: their owners decide it
      const InterfaceLaw& law = ib.laws[ib.interface[static_cast<std::size_t>(q)]];
      // the mirror bond j-i crosses the same interface, so j is in the list
      const auto rj = static_cast<std::size_t>(std::lower_bound(rows.begin(), rows.end(), static_cast<std::int32_t>(j)) - rows.begin());
      std::array<double, 3> t{0, 0, 0};
      for (int p = 0; p < 3; ++p)
        for (int c = 0; c < 3; ++c) t[p] += 0.5 * (stress[r][3 * p + c] + stress[rj][3 * p + c]) * law.normal[c];
      const double tn = dot<3>(t, law.normal);
      const std::array<double, 3> shear{t[0] - tn * law.normal[0], t[1] - tn * law.normal[1], t[2] - tn * law.normal[2]};
      const double effective = -tn - std::max(pressure[r], pressure[rj]);  // sigma_n - p
      const bool parts = -effective > law.tensile_strength;
      const bool slips = norm<3>(shear) > law.cohesion + law.friction_coefficient * std::max(effective, 0.0);
      if (parts || slips) state[k] = bond_interface_failed, failed = true;
    }
  }
  if (failed) b.intact.changed();
}

}  // namespace rift::geomech
