// A failed interface bond (pd/bonds.hpp, bond_interface_failed) is a frictional contact between its two
// particles, in the frame of the interface: with n its normal oriented from i to j and
// delta = (x_j - x_i) - (X_j - X_i) the jump of their displacements, delta_n = delta . n stretches
// the bond (> 0: no force) or presses its ends together (< 0), and the tangential jump less the slip
// s so far is the elastic part, capped by Coulomb friction:
//   g_n = -delta_n,  g_t = delta - delta_n n - s,  |g_t| <= mu g_n (past it the excess becomes slip),
//   f_i = k (delta_n n + g_t),  k = c omega(|xi|) V_j cos^2 / |xi|,
// c the PMB micromodulus equivalent to the rock's moduli (pd/material_constants.hpp) and cos = xi . n /
// |xi|: the stiffness along n of the bond. A block sliding on a failed interface thus carries mu
// times its normal force. While the faces are apart the slip follows the tangential jump.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "rift/parallel/team.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::geomech {

using pd::Model, pd::InterfaceBonds, pd::InterfaceLaw, pd::bond_interface_failed, pd::influence;

/// The entry of the interface bonds that is bond k of row i, or -1 (rows list their slots ascending).
template <int D>
std::int64_t interface_entry(const Model<D>& m, std::size_t i, std::int64_t k) {
  const InterfaceBonds& ib = m.interface_bonds;
  if (ib.empty()) return -1;
  const auto first = ib.slot.begin() + ib.offset[i], last = ib.slot.begin() + ib.offset[i + 1];
  const auto it = std::lower_bound(first, last, k);
  return it != last && *it == k ? static_cast<std::int64_t>(it - ib.slot.begin()) : -1;
}

/// Whether the failed interface bond of entry q joins the two faces of a crack the fluid fills
/// (hf/crack_junction.hpp): its ends are apart, no contact.
inline bool across_crack(const InterfaceBonds& ib, std::int64_t q) {
  return q >= 0 && static_cast<std::size_t>(q) < ib.across_crack.size() && ib.across_crack[static_cast<std::size_t>(q)] != 0;
}

/// Bond i-j across an interface in the interface's frame: the jump of its ends' displacements
/// delta = (x_j - x_i) - (X_j - X_i), the interface normal n oriented from i to j, the reference
/// bond's component along the interface's own normal (across = xi . normal) and the bond's normal
/// stretch delta . n (< 0 presses its ends together).
struct InterfaceJump {
  std::array<double, 3> xi{}, delta{}, n{};
  double across = 0.0, normal_stretch = 0.0;
};

template <int D>
InterfaceJump interface_jump(const Model<D>& m, std::size_t i, std::size_t j, const InterfaceLaw& law) {
  InterfaceJump g;
  for (int a = 0; a < D; ++a) {
    g.xi[a] = m.reference_position[j][a] - m.reference_position[i][a];
    g.delta[a] = m.position[j][a] - m.position[i][a] - g.xi[a];
    g.across += g.xi[a] * law.normal[a];
  }
  for (int a = 0; a < 3; ++a) g.n[a] = g.across > 0.0 ? law.normal[a] : -law.normal[a];
  for (int a = 0; a < 3; ++a) g.normal_stretch += g.delta[a] * g.n[a];
  return g;
}

/// The row of particle i in the interface bonds' particle list (-1: none).
template <int D>
std::int64_t interface_row(const Model<D>& m, std::size_t i) {
  const auto& rows = m.interface_bonds.particles;
  const auto it = std::lower_bound(rows.begin(), rows.end(), static_cast<std::int32_t>(i));
  return it != rows.end() && *it == static_cast<std::int32_t>(i) ? static_cast<std::int64_t>(it - rows.begin()) : -1;
}

/// The normal opening of the faces at the failed interface bond i-j, (delta - eps xi) . n with eps
/// the mean strain of the rock around i and j (pd/bulk_strain.hpp, as the interface law last refreshed
/// it): the bond also stretches with the rock on either side, by eps_nn xi_n + eps_nt xi_t, which
/// in a sheared block exceeds a breaking rock bond's stretch while the faces stay shut. Where the
/// contact presses the bond's ends together (delta . n < 0) the faces touch: the opening is at most 0.
/// > 0: the faces apart; 0 where they only slide.
template <int D>
double interface_opening(const Model<D>& m, std::size_t i, std::size_t j, const InterfaceLaw& law) {
  const InterfaceJump g = interface_jump<D>(m, i, j, law);
  double opening = g.normal_stretch;
  const auto& strain = m.interface_bonds.strain;
  const auto ri = interface_row<D>(m, i), rj = interface_row<D>(m, j);
  if (ri >= 0 && rj >= 0 && strain.size() == m.interface_bonds.particles.size()) {
    const auto& ei = strain[static_cast<std::size_t>(ri)];
    const auto& ej = strain[static_cast<std::size_t>(rj)];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) opening -= g.n[a] * 0.5 * (ei[3 * a + c] + ej[3 * a + c]) * g.xi[c];
  }
  return g.normal_stretch < 0.0 ? std::min(opening, 0.0) : opening;
}

/// Whether the faces of the failed interface bond k = i-j are apart: their normal opening
/// (interface_opening above) passes the stretch at which a rock bond of its length breaks, s0 |xi|. A
/// closed interface, or one that only slides (its faces then part and press by round-off about 0),
/// keeps the fluid out. The outcome reader calls the same faces open (dilated).
template <int D>
bool interface_faces_apart(const Model<D>& m, std::int64_t k, std::size_t i, std::size_t j, const InterfaceLaw& law) {
  return interface_opening<D>(m, i, j, law) > m.constants_of(i).critical_stretch * m.bonds.length(k);
}

/// Force density on particle i from its failed interface bond k = i-j, interface entry q; with
/// `slip_update` the Coulomb return writes the entry's new slip there.
template <int D>
Vec<D> interface_contact_force(const Model<D>& m, std::size_t i, std::size_t j, std::int64_t k, std::size_t q,
                               std::array<double, 3>* slip_update) {
  const InterfaceBonds& ib = m.interface_bonds;
  const InterfaceLaw& law = ib.laws[ib.interface[q]];
  const auto& c = m.constants_of(i);
  const auto kk = static_cast<std::size_t>(k);
  const double length = m.bonds.length(static_cast<std::int64_t>(kk));
  const double stiffness = c.equivalent_micromodulus * influence(c.influence, length, c.horizon) * m.bonds.volume(static_cast<std::int64_t>(kk)) / length;
  const InterfaceJump jump = interface_jump<D>(m, i, j, law);
  const auto& delta = jump.delta;
  const auto& n = jump.n;
  const double delta_n = jump.normal_stretch;
  const double k_n = stiffness * (jump.across / length) * (jump.across / length);  // the bond's stiffness along n
  std::array<double, 3> slip = ib.slip[q];
  Vec<D> f{};
  // ends not pressed together, or on the two faces of a crack the fluid fills: no force, the slip follows
  if (delta_n >= 0.0 || across_crack(ib, static_cast<std::int64_t>(q))) {
    for (int a = 0; a < 3; ++a) slip[a] = delta[a] - delta_n * n[a];
    if (slip_update) *slip_update = slip;
    return f;
  }
  std::array<double, 3> g{0, 0, 0};
  double g_t = 0.0;
  for (int a = 0; a < 3; ++a) {
    g[a] = delta[a] - delta_n * n[a] - slip[a];
    g_t += g[a] * g[a];
  }
  g_t = std::sqrt(g_t);
  const double limit = law.friction_coefficient * -delta_n;
  if (g_t > limit) {
    const double keep = limit / g_t;
    for (int a = 0; a < 3; ++a) {
      slip[a] += (1.0 - keep) * g[a];
      g[a] *= keep;
    }
  }
  if (slip_update) *slip_update = slip;
  for (int a = 0; a < D; ++a) f[a] = k_n * (delta_n * n[a] + g[a]);
  return f;
}

/// Adds the contact forces of the failed interface bonds to m.force (each row its own); with `slide`
/// (a step of explicit dynamics) their slips advance, otherwise (dynamic relaxation, whose iterations
/// are no physical path) they are held, as the viscoelastic history is, and the friction is the
/// capped elastic force from the held slip: path-independent, so the iterations converge.
template <int D>
void add_interface_contact(Model<D>& m, bool slide) {
  InterfaceBonds& ib = m.interface_bonds;
  if (ib.empty()) return;
  const auto& rows = ib.particles;
#pragma omp parallel for if(rift::parallel::worth_a_team(rows.size())) schedule(static)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(rows[r]);
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = ib.slot[static_cast<std::size_t>(q)];
      if (m.bonds.intact[static_cast<std::size_t>(k)] != bond_interface_failed) continue;
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[static_cast<std::size_t>(k)]);
      const Vec<D> f = interface_contact_force<D>(m, i, j, k, static_cast<std::size_t>(q), slide ? &ib.slip[static_cast<std::size_t>(q)] : nullptr);
      for (int a = 0; a < D; ++a) m.force[i][a] += f[a];
    }
  }
}

}  // namespace rift::geomech
