#include "rift/pd/material_constants.hpp"

#include "rift/pd/critical_stretch.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/laws/registry.hpp"

namespace rift::pd {

namespace {
constexpr double pi = 3.14159265358979323846;
}

double pmb_micromodulus(int dimension, double kappa, double horizon, double thickness, scene::Influence influence) {
  // Match the strain energy density of an isotropic expansion (Silling and Askari 2005, eq. 17):
  // 3D: (1/4) c eps^2 4 pi int omega r^3 dr = (9/2) K eps^2 ; 2D: (1/4) c t eps^2 2 pi int omega r^2 dr = 2 kappa eps^2.
  if (dimension == 3) return 18.0 * kappa / (4.0 * pi * influence_moment(influence, horizon, 3));
  return 4.0 * kappa / (pi * thickness * influence_moment(influence, horizon, 2));
}

MaterialConstants make_constants(const scene::Scene& s, const scene::Material& m, double horizon, double spacing) {
  MaterialConstants mc;
  mc.model = m.model;
  mc.influence = m.influence;
  mc.dimension = s.dimension;
  mc.horizon = horizon;
  mc.spacing = spacing;
  mc.thickness = s.dimension == 2 ? s.thickness : 1.0;
  mc.density = m.density;
  mc.shear_modulus = m.shear_modulus;
  const double K = m.bulk_modulus, G = m.shear_modulus;
  if (s.dimension == 3) mc.kappa = K;
  else if (s.plane == scene::PlaneCondition::strain) mc.kappa = K + G / 3.0;
  else mc.kappa = 9.0 * K * G / (3.0 * K + 4.0 * G);
  mc.micromodulus = pmb_micromodulus(mc.dimension, mc.kappa, horizon, mc.thickness, mc.influence);
  // PMB has kappa = 5G/3 (3D) or 2G (2D): P-wave modulus 9 kappa/5 (3D) or 3 kappa/2 (2D).
  const double kappa_equivalent = mc.dimension == 3 ? 5.0 * mc.p_wave_modulus() / 9.0 : 2.0 * mc.p_wave_modulus() / 3.0;
  mc.equivalent_micromodulus = pmb_micromodulus(mc.dimension, kappa_equivalent, horizon, mc.thickness, mc.influence);
  mc.alpha = m.alpha;
  mc.surface_correction = m.surface_correction;
  with_law(mc.model, [&]<class Law>() { Law::take_constants(mc, m); });
  if (m.bond_failure == scene::BondFailure::normal_stress) {
    mc.normal_stress_failure = true;
    mc.critical_stretch = *m.tensile_strength / (mc.dimension * mc.kappa);
    mc.breakable = true;
  } else if (m.critical_stretch) {
    mc.critical_stretch = *m.critical_stretch;
    mc.breakable = true;
  } else if (m.fracture_energy) {
    // the separation work's s0 (Silling and Askari 2005), scaled so that a grown crack, not a sharp
    // cut, advances at K_Ic (the problem is linear up to a break: K of every event scales with s0)
    mc.critical_stretch = critical_stretch_from_fracture_energy(mc, *m.fracture_energy) / m.propagation_toughness_ratio;
    mc.breakable = true;
  }
  return mc;
}

}  // namespace rift::pd
