// Every registered peridynamic law (pd/laws/registry.hpp Laws) through the same checks, so that a
// law is tested the moment it is registered:
//  - homogeneous deformation: the strain energy density of the bulk particles (farther than one
//    horizon from a face) is linear elasticity's, W = kappa/2 (tr eps)^2 + G |dev eps|^2, within 1%;
//  - patch test: under the same homogeneous deformation a particle farther than two horizons from
//    every face (its family and its neighbours' families whole) carries no force, to round-off
//    (1e-9 of kappa |eps| / delta), and its bond-pair stress is the classical sigma within 1%;
//  - momentum: random velocities that break bonds change the linear and angular momentum by no more
//    than 1e-11 of sum m |v| over 200 steps (Silling 2000: exact conservation);
//  - separation work: pulling a bar apart across a plane takes G0 per unit area within 10% (the
//    critical stretch comes from G0, Silling and Askari 2005 eq. 24; as validation pd_fracture_energy).
// Nu = 1/4 in plane strain and 3D, the Poisson ratio a bond-based law has there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cases/homogeneous.hpp"
#include "cases/momentum.hpp"
#include "cases/separation_work.hpp"
#include "rift/pd/laws/registry.hpp"
#include "rift/pd/stress.hpp"

namespace {

template <class List>
struct TestTypes;
template <class... L>
struct TestTypes<rift::pd::LawList<L...>> {
  using type = ::testing::Types<L...>;
};

template <class Law>
class LawConformance : public ::testing::Test {};

struct LawName {
  template <class Law>
  static std::string GetName(int) {
    return Law::keyword;
  }
};
TYPED_TEST_SUITE(LawConformance, TestTypes<rift::pd::Laws>::type, LawName);

using rift::validation::Strain;

/// Largest |W / W_classical - 1| over the bulk; largest |f| over particles two horizons deep, over
/// kappa |eps| / delta; largest |sigma - sigma_classical| there, over |sigma_classical|.
struct PatchErrors {
  double energy = 0.0, force = 0.0, stress = 0.0;
  int deep = 0;
};

template <int D, class Law>
PatchErrors patch_errors(const Strain& eps) {
  const std::string size = D == 2 ? "max = [0.02, 0.02]" : "max = [0.016, 0.016, 0.016]";
  auto s = rift::scene::parse_string(rift::validation::box_scene(D, Law::keyword, 0.25, "", size, 3.015, "strain", Law::example_material),
                                     "conformance.toml");
  auto m = rift::pd::discretize<D>(s);
  const auto& c = m.bodies[0].constants;
  rift::validation::deform<D>(m, eps);
  rift::pd::compute_forces<D>(m, nullptr);
  double tr = 0.0, norm = 0.0;
  for (int a = 0; a < D; ++a) tr += eps[a][a];
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) norm += eps[a][b] * eps[a][b];
  const double classical = rift::validation::classical_energy_density<D>(c, eps);
  // sigma = kappa tr eps I + 2 G dev eps, in the plane (the dimension's kappa)
  double sigma[3][3] = {}, sigma_norm = 0.0;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      sigma[a][b] = (a == b ? c.kappa * tr : 0.0) + 2.0 * c.shear_modulus * (eps[a][b] - (a == b ? tr / D : 0.0));
      sigma_norm = std::max(sigma_norm, std::abs(sigma[a][b]));
    }
  const auto stress = rift::pd::particle_stress<D>(m);
  const auto [lo, hi] = m.reference_bounds();
  PatchErrors e;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double depth = 1e9;
    for (int a = 0; a < D; ++a) depth = std::min({depth, m.reference_position[i][a] - lo[a], hi[a] - m.reference_position[i][a]});
    if (depth <= c.horizon) continue;
    e.energy = std::max(e.energy, std::abs(rift::pd::strain_energy_density<D>(m, i) / classical - 1.0));
    if (depth <= 2.0 * c.horizon) continue;
    ++e.deep;
    e.force = std::max(e.force, std::sqrt(rift::dot<D>(m.force[i], m.force[i])) / (c.kappa * std::sqrt(norm) / c.horizon));
    const double* o = &stress[6 * i];  // xx, yy, zz, xy, yz, xz
    const double got[3][3] = {{o[0], o[3], o[5]}, {o[3], o[1], o[4]}, {o[5], o[4], o[2]}};
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) e.stress = std::max(e.stress, std::abs(got[a][b] - sigma[a][b]) / sigma_norm);
  }
  return e;
}

template <int D, class Law>
void check_patch(const char* dimension) {
  for (const auto* eps : {&rift::validation::uniaxial_strain, &rift::validation::shear_strain, &rift::validation::volumetric_strain}) {
    const PatchErrors e = patch_errors<D, Law>(*eps);
    const char* mode = eps == &rift::validation::uniaxial_strain ? "uniaxial" : eps == &rift::validation::shear_strain ? "shear" : "volumetric";
    std::printf("%s %s %-10s energy %.2e, force %.2e, stress %.2e (%d deep particles)\n", Law::name, dimension, mode, e.energy, e.force,
                e.stress, e.deep);
    EXPECT_GT(e.deep, 0);
    EXPECT_LT(e.energy, 0.01) << dimension << " " << mode;
    EXPECT_LT(e.force, 1e-9) << dimension << " " << mode;
    EXPECT_LT(e.stress, 0.01) << dimension << " " << mode;
  }
}

TYPED_TEST(LawConformance, HomogeneousDeformationGivesElasticEnergyNoForceAndTheClassicalStress) {
  check_patch<2, TypeParam>("2D");
  check_patch<3, TypeParam>("3D");
}

TYPED_TEST(LawConformance, ConservesMomentumWhileBondsBreak) {
  EXPECT_LT((rift::validation::momentum_drift<2>(TypeParam::keyword, 200, TypeParam::example_material)), 1e-11);
  EXPECT_LT((rift::validation::momentum_drift<3>(TypeParam::keyword, 200, TypeParam::example_material)), 1e-11);
}

TYPED_TEST(LawConformance, SeparationWorkIsTheFractureEnergy) {
  const double r2 = rift::validation::separation_work_ratio<2>(TypeParam::keyword, true, TypeParam::example_material);
  const double r3 = rift::validation::separation_work_ratio<3>(TypeParam::keyword, true, TypeParam::example_material);
  std::printf("%s G/G0: 2D %.4f, 3D %.4f\n", TypeParam::name, r2, r3);
  EXPECT_NEAR(r2, 1.0, 0.1);
  EXPECT_NEAR(r3, 1.0, 0.1);
}

}  // namespace
