// Peridynamic constants of one body: PMB micromodulus, LPS moduli, critical stretch, all derived
// from the classical constants for the body's dimension, plane condition and influence function.
#pragma once
#include "rift/scene/scene.hpp"

namespace rift::pd {

struct MaterialConstants {
  scene::ModelKind model{};  // the body's law (laws/registry.hpp)
  scene::Influence influence = scene::Influence::constant;
  int dimension = 3;
  double horizon = 0.0, spacing = 0.0, thickness = 1.0;
  double density = 0.0;
  /// Bulk modulus of the dimension: K (3D), K + G/3 (plane strain), 9KG/(3K+4G) (plane stress).
  double kappa = 0.0;
  double shear_modulus = 0.0;
  /// PMB micromodulus c: bond force density f = c omega(|xi|) s V_j (Silling and Askari 2005).
  /// 3D: c = 18 kappa / (4 pi int omega r^3 dr); 2D: c = 4 kappa / (pi t int omega r^2 dr).
  double micromodulus = 0.0;
  /// Micromodulus of the PMB body with the same P-wave modulus: stable time step, contact, ADR.
  double equivalent_micromodulus = 0.0;
  double critical_stretch = 0.0;  // s00; 0 = unbreakable
  double alpha = 0.0;
  bool breakable = false;
  /// Bonds break on the normal stress along them (bond_failure = normal_stress): critical_stretch is
  /// then the tensile strength over d kappa, the stretch of a uniform expansion with that stress.
  bool normal_stress_failure = false;
  /// A law with a history of each bond (laws/registry.hpp bond_history): lambda, the share of the
  /// deviatoric extension measured from each direction's stored extension (VES: the share that
  /// relaxes, Mitchell 2011; EPS: 1, the plastic extension), and VES's relaxation time tau (s).
  double viscous_fraction = 0.0, relaxation_time = 0.0;
  /// EPS (laws/eps.hpp): the uniaxial yield stress sigma_Y, Pa.
  double yield_stress = 0.0;
  bool surface_correction = true;

  /// Lame's first parameter of the dimension: kappa - 2G/3 (3D), kappa - G (2D).
  double lame_lambda() const { return dimension == 3 ? kappa - 2.0 * shear_modulus / 3.0 : kappa - shear_modulus; }
  /// P-wave (constrained) modulus of the dimension: kappa + 4G/3 (3D), kappa + G (2D).
  double p_wave_modulus() const { return dimension == 3 ? kappa + 4.0 * shear_modulus / 3.0 : kappa + shear_modulus; }
  /// Coefficients of the LPS force scalar t = A_dil theta omega |xi| / m + A_dev omega e / m:
  /// 3D: (3K - 5G, 15G) (Silling et al. 2007; LAMMPS peri/lps, peri/ves); 2D: (2 kappa - 4G, 8G) (Le et al. 2014).
  double lps_dilatation_coefficient() const {
    return dimension == 3 ? 3.0 * kappa - 5.0 * shear_modulus : 2.0 * kappa - 4.0 * shear_modulus;
  }
  double lps_deviatoric_coefficient() const { return dimension == 3 ? 15.0 * shear_modulus : 8.0 * shear_modulus; }
};

/// PMB micromodulus for a given dimension bulk modulus (see MaterialConstants::micromodulus).
double pmb_micromodulus(int dimension, double kappa, double horizon, double thickness, scene::Influence influence);

/// Build the constants of a body; fracture energy is turned into a critical stretch with
/// critical_stretch_from_fracture_energy().
MaterialConstants make_constants(const scene::Scene& s, const scene::Material& m, double horizon, double spacing);

}  // namespace rift::pd
