// Validation 1: homogeneous deformation. The strain energy density of every particle under a
// uniform strain is compared with classical linear elasticity: within 1% in the bulk (particles
// farther than one horizon from every face) and within 5% near free surfaces with the surface
// correction on. Source: W = lambda/2 (tr eps)^2 + G eps:eps (3D); kappa/2 (tr eps)^2 + G |dev eps|^2 (2D).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "cases/homogeneous.hpp"

namespace {

using rift::validation::box_scene;
using rift::validation::energy_errors;
using rift::validation::EnergyErrors;
using Errors = EnergyErrors;
const auto& uniaxial = rift::validation::uniaxial_strain;
const auto& shear = rift::validation::shear_strain;
const auto& volumetric = rift::validation::volumetric_strain;

struct Case {
  int dim;
  const char* model;
  double nu;
  const char* plane;
};

class Homogeneous : public ::testing::TestWithParam<Case> {};

TEST_P(Homogeneous, EnergyDensityMatchesElasticity) {
  const auto& p = GetParam();
  const std::string scene = box_scene(p.dim, p.model, p.nu, "", "", 3.015, p.plane);
  for (const auto* eps : {&uniaxial, &shear, &volumetric}) {
    Errors e = p.dim == 2 ? energy_errors<2>(scene, *eps) : energy_errors<3>(scene, *eps);
    const char* mode = eps == &uniaxial ? "uniaxial" : eps == &shear ? "shear" : "volumetric";
    std::printf("%-22s %-10s max error bulk %.2e (%d particles), near surface %.2e (%d particles)\n",
                ::testing::UnitTest::GetInstance()->current_test_info()->name(), mode, e.bulk, e.bulk_count, e.surface,
                e.surface_count);
    ASSERT_GT(e.bulk_count, 0);
    EXPECT_LT(e.bulk, 0.01) << mode << " bulk";
    EXPECT_LT(e.surface, 0.05) << mode << " surface";
  }
}

INSTANTIATE_TEST_SUITE_P(
    PmbAndLps, Homogeneous,
    ::testing::Values(Case{3, "pmb", 0.25, ""}, Case{3, "lps", 0.2, ""}, Case{3, "lps", 0.3, ""},
                      Case{2, "pmb", 1.0 / 3.0, "stress"}, Case{2, "pmb", 0.25, "strain"}, Case{2, "lps", 0.2, "stress"},
                      Case{2, "lps", 0.3, "stress"}, Case{2, "lps", 0.2, "strain"}, Case{2, "lps", 0.3, "strain"}),
    [](const auto& info) {
      return std::string(info.param.model) + std::to_string(info.param.dim) + "d_" +
             (info.param.plane[0] ? std::string(info.param.plane) + "_" : "") + "nu" +
             std::to_string(static_cast<int>(info.param.nu * 100 + 0.5));
    });

}  // namespace

namespace {

// Without the correction the particles near the free surfaces are too soft (the test above would
// fail): the correction is what brings them to the classical energy.
TEST(SurfaceCorrection, UncorrectedSurfaceIsOffByMoreThanFivePercent) {
  const std::string scene = box_scene(3, "lps", 0.25, "", "", 3.015, "", "surface_correction = false\n");
  Errors e = energy_errors<3>(scene, uniaxial);
  EXPECT_GT(e.surface, 0.05);
}

// The corrected influence functions stay positive (no bond with negative stiffness), also at
// corners, for both dimensions and horizons of 3 and 4 spacings.
TEST(SurfaceCorrection, FactorsStayPositive) {
  for (int dim : {2, 3})
    for (double h : {3.015, 4.015})
      for (const char* model : {"pmb", "lps"}) {
        const std::string scene = box_scene(dim, model, 0.25, "", "", h, "strain");
        auto s = rift::scene::parse_string(scene, "f.toml");
        float lo = 1e9f, hi = -1e9f;
        auto scan = [&](const auto& m) {
          for (std::size_t i = 0; i < m.size(); ++i)
            for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) {
              const float f = m.bonds.correction(i, k);
              lo = std::min(lo, f), hi = std::max(hi, f);
            }
        };
        if (dim == 2) scan(rift::pd::discretize<2>(s));
        else scan(rift::pd::discretize<3>(s));
        std::printf("dim %d horizon %.3f %s: influence factors in [%.3f, %.3f]\n", dim, h, model, lo, hi);
        EXPECT_GT(lo, 0.0f);
      }
}

}  // namespace
