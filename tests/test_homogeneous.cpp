// Validation 1: homogeneous deformation. The strain energy density of every particle under a
// uniform strain is compared with classical linear elasticity: within 1% in the bulk (particles
// farther than one horizon from every face) and within 5% near free surfaces with the surface
// correction on. Source: W = lambda/2 (tr eps)^2 + G eps:eps (3D); kappa/2 (tr eps)^2 + G |dev eps|^2 (2D).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "scene_fixture.hpp"

namespace {

using Strain = std::array<std::array<double, 3>, 3>;

struct Errors {
  double bulk = 0.0, surface = 0.0;
  int bulk_count = 0, surface_count = 0;
};

template <int D>
Errors energy_errors(const std::string& scene_text, const Strain& eps) {
  auto s = rift::scene::parse_string(scene_text, "homogeneous.toml");
  auto m = rift::pd::discretize<D>(s);
  const auto& c = m.bodies[0].constants;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int a = 0; a < D; ++a) {
      double u = 0;
      for (int b = 0; b < D; ++b) u += eps[a][b] * m.reference_position[i][b];
      m.position[i][a] = m.reference_position[i][a] + u;
    }
  rift::pd::compute_forces<D>(m, nullptr);
  // classical energy density
  double tr = 0;
  for (int a = 0; a < D; ++a) tr += eps[a][a];
  double dev2 = 0;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) {
      double d = eps[a][b] - (a == b ? tr / D : 0.0);
      dev2 += d * d;
    }
  const double classical = 0.5 * c.kappa * tr * tr + c.shear_modulus * dev2;
  // box extent
  std::array<double, 3> lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const auto& x : m.reference_position)
    for (int a = 0; a < D; ++a) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
  Errors e;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double depth = 1e9;
    for (int a = 0; a < D; ++a)
      depth = std::min({depth, m.reference_position[i][a] - lo[a], hi[a] - m.reference_position[i][a]});
    const double err = std::abs(rift::pd::strain_energy_density<D>(m, i) / classical - 1.0);
    if (depth > c.horizon) {
      e.bulk = std::max(e.bulk, err);
      ++e.bulk_count;
    } else {
      e.surface = std::max(e.surface, err);
      ++e.surface_count;
    }
  }
  return e;
}

const Strain uniaxial{{{1e-4, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
const Strain shear{{{0, 1e-4, 0}, {1e-4, 0, 0}, {0, 0, 0}}};
const Strain volumetric{{{1e-4, 0, 0}, {0, 1e-4, 0}, {0, 0, 1e-4}}};

struct Case {
  int dim;
  const char* model;
  double nu;
  const char* plane;
};

class Homogeneous : public ::testing::TestWithParam<Case> {};

TEST_P(Homogeneous, EnergyDensityMatchesElasticity) {
  const auto& p = GetParam();
  const std::string scene = rift::test::box_scene(p.dim, p.model, p.nu, "", "", 3.015, p.plane);
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
  const std::string scene = rift::test::box_scene(3, "lps", 0.25, "", "", 3.015, "", "surface_correction = false\n");
  Errors e = energy_errors<3>(scene, uniaxial);
  EXPECT_GT(e.surface, 0.05);
}

// The corrected influence functions stay positive (no bond with negative stiffness), also at
// corners, for both dimensions and horizons of 3 and 4 spacings.
TEST(SurfaceCorrection, FactorsStayPositive) {
  for (int dim : {2, 3})
    for (double h : {3.015, 4.015})
      for (const char* model : {"pmb", "lps"}) {
        const std::string scene = rift::test::box_scene(dim, model, 0.25, "", "", h, "strain");
        auto s = rift::scene::parse_string(scene, "f.toml");
        float lo = 1e9f, hi = -1e9f;
        auto scan = [&](const auto& m) {
          for (float f : m.bonds.correction) lo = std::min(lo, f), hi = std::max(hi, f);
        };
        if (dim == 2) scan(rift::pd::discretize<2>(s));
        else scan(rift::pd::discretize<3>(s));
        std::printf("dim %d horizon %.3f %s: influence factors in [%.3f, %.3f]\n", dim, h, model, lo, hi);
        EXPECT_GT(lo, 0.0f);
      }
}

}  // namespace
