// Effective stress in a crack's wet rock (Terzaghi; Biot coefficient 1). In the toughness-dominated limit
// the fluid has no lag behind the tip (Detournay 2004): the cracked rock's bonds fail under sigma + p I.
// -p I gives every bond the stretch -p / (d kappa) (kappa the bulk modulus of the dimension, d = 2 or 3),
// so a bond whose two ends the fluid reaches across a crack breaks when
//   s > min(s0_i, s0_j) - (1 + alpha) min(s_p,i, s_p,j),   s_p = p / (d kappa)  (the pore stretch),
// 1 + alpha because s0 = s00 - alpha s_min follows the same shift (Silling and Askari 2005, eq. 23).
// Both ends must be wet, and the bond must cross the crack or its extension at the tip (crack_surface.hpp):
// a bond beside the faces carries the total stress. A borehole's intact wall is not cracked rock (Hubbert
// and Willis 1957): breakdown keeps the total stress. The pore stretch is pore_stretch.hpp's. The bond
// passes reach the wet rock through the model's coupling (pd/bond_coupling.hpp), which this installs.
// Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "rift/hf/crack_surface.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/pd/bond_coupling.hpp"

namespace rift::hf {

/// What the bond passes read of the wet rock: the pore stretch per particle (nullptr: no pressure
/// yet) and the crack surface whose crossing bonds it shifts (crack_surface.hpp).
template <int D>
struct WetRock {
  const double* pore_stretch = nullptr;
  const CrackSurface* surface = nullptr;
  const Vec<D>* reference = nullptr;
  double patch_bond = 0.0;  // the longest bond whose crossing the crack surface keeps (makes_patch)
  explicit operator bool() const { return surface != nullptr; }
  /// How far the wet rock would lower the stretch limit of bond i-j if it crosses the crack:
  /// (1 + alpha) min(s_p,i, s_p,j).
  double shift(double alpha, std::size_t i, std::size_t j) const {
    if (!pore_stretch) return 0.0;
    const double* s = pore_stretch;
    return (1.0 + alpha) * (s[i] < s[j] ? s[i] : s[j]);
  }
  bool crosses(std::size_t i, std::size_t j) const { return pierces_crack<D>(*surface, reference[i], reference[j]); }
};

/// The wet rock the bond passes read; empty where no crack holds a fluid.
template <int D>
WetRock<D> wet_rock(const Model<D>& m) {
  const FluidNetwork& f = m.fluid_network;
  if (f.crack_surface.empty()) return {};
  return {f.pore_stretch.size() == m.size() ? f.pore_stretch.data() : nullptr, &f.crack_surface, m.reference_position.data(),
          detail::patch_bond_length<D>(m)};
}

/// Whether bond i-j (reference length xi) of value `value` (its stretch, or its normal stress in
/// stretch units) against `limit` breaks, in wet rock on the effective stretch where it crosses the
/// crack; `crossed` says whether a bond that breaks crosses the crack, where that matters: a short
/// bond that crosses extends the crack (crack_surface.hpp makes_patch asks no longer bond), so a
/// longer one that breaks on its stretch alone is not looked at (the search was 6% of a step in the
/// thesis example's shattered block).
template <int D>
bool breaks_in_wet_rock(const WetRock<D>& wet, double alpha, std::size_t i, std::size_t j, double xi, double value, double limit,
                        bool& crossed) {
  if (value > limit) {
    crossed = xi <= wet.patch_bond && wet.crosses(i, j);
    return true;
  }
  const double shift = wet.shift(alpha, i, j);
  crossed = shift > 0.0 && value > limit - shift && wet.crosses(i, j);
  return crossed;
}

/// A pass's view of the wet rock (pd/bond_coupling.hpp BondBreaker), made once per pass.
template <int D>
class WetRockBreaker final : public pd::BondBreaker {
 public:
  explicit WetRockBreaker(const WetRock<D>& wet) : wet_(wet) {}
  const double* pore_stretch() const override { return wet_.pore_stretch; }
  bool breaks(double alpha, std::size_t i, std::size_t j, double xi, double value, double limit, bool& crossed) const override {
    return breaks_in_wet_rock<D>(wet_, alpha, i, j, xi, value, limit, crossed);
  }

 private:
  WetRock<D> wet_;
};

/// The wet rock as the bond passes' coupling (pd/bond_coupling.hpp): active where a crack holds fluid.
template <int D>
class WetRockCoupling final : public pd::BondCoupling<D> {
 public:
  bool active(const Model<D>& m) const override { return !m.fluid_network.crack_surface.empty(); }
  std::unique_ptr<const pd::BondBreaker> breaker(const Model<D>& m) const override {
    return std::make_unique<const WetRockBreaker<D>>(wet_rock<D>(m));
  }
  void broke_across(Model<D>& m, const std::vector<std::pair<std::size_t, std::int64_t>>& crossing) const override {
    record_crossing_breaks<D>(m, crossing);
  }
};

/// The one coupling of the wet rock (it holds no state: every model may point to it).
template <int D>
const pd::BondCoupling<D>* wet_rock_coupling() {
  static const WetRockCoupling<D> coupling;
  return &coupling;
}

}  // namespace rift::hf
