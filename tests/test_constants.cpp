// Peridynamic constants against closed forms from the literature.
#include <gtest/gtest.h>

#include <cmath>

#include "rift/pd/critical_stretch.hpp"
#include "rift/pd/material_constants.hpp"

namespace {

using rift::scene::Influence;
using rift::scene::ModelKind;
constexpr double pi = 3.14159265358979323846;

rift::pd::MaterialConstants constants(int dim, ModelKind model, Influence omega, double nu,
                                      rift::scene::PlaneCondition plane = rift::scene::PlaneCondition::stress) {
  rift::scene::Scene s;
  s.dimension = dim;
  s.plane = dim == 2 ? plane : rift::scene::PlaneCondition::none;
  s.thickness = 0.002;
  rift::scene::Material m;
  m.model = model;
  m.influence = omega;
  m.density = 2440;
  const double E = 72e9;
  m.bulk_modulus = E / (3 * (1 - 2 * nu));
  m.shear_modulus = E / (2 * (1 + nu));
  return rift::pd::make_constants(s, m, 0.003, 0.001);
}

// Silling and Askari (2005), eq. 17 and 24: c = 18K/(pi delta^4), s0 = sqrt(5 G0 / (9 K delta)).
TEST(Constants, PmbThreeDimensionalSillingAskari) {
  auto mc = constants(3, ModelKind::pmb, Influence::constant, 0.25);
  const double K = 72e9 / (3 * 0.5), delta = 0.003, G0 = 3.8;
  EXPECT_NEAR(mc.micromodulus, 18 * K / (pi * std::pow(delta, 4)), 1e-9 * mc.micromodulus);
  EXPECT_NEAR(rift::pd::critical_stretch_from_fracture_energy(mc, G0), std::sqrt(5 * G0 / (9 * K * delta)), 1e-12);
}

// Ha and Bobaru (2010), plane stress nu = 1/3: c = 9E/(pi t delta^3), s0 = sqrt(4 pi G0 / (9 E delta)).
TEST(Constants, PmbPlaneStressHaBobaru) {
  auto mc = constants(2, ModelKind::pmb, Influence::constant, 1.0 / 3.0);
  const double E = 72e9, delta = 0.003, t = 0.002, G0 = 3.8;
  EXPECT_NEAR(mc.micromodulus, 9 * E / (pi * t * std::pow(delta, 3)), 1e-9 * mc.micromodulus);
  EXPECT_NEAR(rift::pd::critical_stretch_from_fracture_energy(mc, G0), std::sqrt(4 * pi * G0 / (9 * E * delta)), 1e-12);
}

// propagation_toughness_ratio divides the separation work's s0: K of every break scales with s0 in
// the linear lattice, so a grown crack that advanced at ratio K_Ic advances at K_Ic.
TEST(Constants, PropagationToughnessRatioDividesTheCriticalStretch) {
  rift::scene::Scene s;
  s.dimension = 3;
  rift::scene::Material m;
  m.model = ModelKind::lps;
  m.density = 2440;
  m.bulk_modulus = 48e9;
  m.shear_modulus = 28.8e9;
  m.fracture_energy = 3.8;
  const double plain = rift::pd::make_constants(s, m, 0.003, 0.001).critical_stretch;
  m.propagation_toughness_ratio = 1.25;
  EXPECT_NEAR(rift::pd::make_constants(s, m, 0.003, 0.001).critical_stretch, plain / 1.25, 1e-15);
}

// The quadrature of the rigid-separation work reproduces the PMB closed form (tolerance 0.2%)
// for both dimensions and both influence functions.
TEST(Constants, SeparationWorkQuadratureMatchesPmbClosedForm) {
  for (int dim : {2, 3})
    for (auto omega : {Influence::constant, Influence::inverse_distance}) {
      auto mc = constants(dim, ModelKind::pmb, omega, 0.25, rift::scene::PlaneCondition::strain);
      const double closed = rift::pd::pmb_separation_work_per_stretch2(mc);
      const double quad = rift::pd::separation_work_per_stretch2(mc, false);
      EXPECT_NEAR(quad / closed, 1.0, 2e-3) << "dim " << dim;
    }
}

// LPS with nu = 1/4 (3D) has nearly the PMB fracture energy; Madenci and Oterkus (2014, eq. 6.x)
// give s0 = sqrt(G0 / ((3G + (3/4)^4 (K - 5G/3)) delta)) = PMB value at nu = 1/4. Our quadrature of the
// actual LPS separation work agrees within 10%.
TEST(Constants, LpsSeparationWorkNearPmbAtQuarterPoisson) {
  auto lps = constants(3, ModelKind::lps, Influence::constant, 0.25);
  auto pmb = constants(3, ModelKind::pmb, Influence::constant, 0.25);
  EXPECT_NEAR(rift::pd::separation_work_per_stretch2(lps, true) / rift::pd::pmb_separation_work_per_stretch2(pmb), 1.0, 0.1);
}

}  // namespace
