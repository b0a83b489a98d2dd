// Validation 3: linear and angular momentum of a free body with random velocities are conserved
// to round-off by velocity-Verlet with pairwise-antisymmetric bond forces (Silling 2000).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <omp.h>

#include "rift/load/boundary.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/velocity_verlet.hpp"
#include "cases/momentum.hpp"

namespace {

// Tolerance: 1e-11 of sum m|v| (round-off over 200 steps is about 1e-16).
template <int D>
void momentum_conserved(const std::string& model) {
  const double drift = rift::validation::momentum_drift<D>(model, 200);
  std::printf("%s %dD: momentum drift %.2e\n", model.c_str(), D, drift);
  EXPECT_LT(drift, 1e-11);
}

TEST(Momentum, PmbThreeD) { momentum_conserved<3>("pmb"); }
TEST(Momentum, LpsThreeD) { momentum_conserved<3>("lps"); }
TEST(Momentum, PmbTwoD) { momentum_conserved<2>("pmb"); }
TEST(Momentum, LpsTwoD) { momentum_conserved<2>("lps"); }

}  // namespace

namespace {

// The same scene gives bit-identical results for 1 and 2 threads (each particle owns its force
// sum; energies are summed in fixed blocks).
TEST(Determinism, SameBitsForAnyThreadCount) {
  auto s = rift::scene::parse_string(
      rift::validation::box_scene(2, "lps", 0.25, "", "max = [0.03, 0.02]", 3.015, "strain", "critical_stretch = 0.001\n"), "d.toml");
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    auto m = rift::pd::discretize<2>(s);
    rift::load::Boundaries<2> loads(s, m);
    rift::pd::Contact<2> contact(s.contact, m);
    for (std::size_t i = 0; i < m.size(); ++i) m.velocity[i] = {std::sin(1e3 * m.reference_position[i][1]) * 20.0, 3.0 * std::cos(i * 0.7)};
    rift::pd::compute_forces<2>(m, &contact);
    const double dt = 0.5 * rift::pd::stable_time_step<2>(m);
    for (int step = 0; step < 100; ++step) rift::pd::velocity_verlet_step<2>(m, loads, &contact, dt);
    auto e = rift::pd::summarize<2>(m);
    return std::make_pair(m.position, e.kinetic + e.strain);
  };
  auto [x1, e1] = run(1);
  auto [x2, e2] = run(2);
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_EQ(x1, x2);
  EXPECT_EQ(e1, e2);
}

}  // namespace

namespace {

// A history without strain-energy columns skips the pass over the bonds (runner.cpp) but still
// sums the kinetic energy and the broken bonds exactly as before, and still carries a non-finite
// position out (as NaN) for the runner's check.
TEST(Summary, WithoutStrainEnergySameKineticAndBrokenBonds) {
  auto s = rift::scene::parse_string(
      rift::validation::box_scene(2, "ves", 0.25, "", "max = [0.03, 0.02]", 3.015, "strain",
                                  "critical_stretch = 0.001\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\n"),
      "s.toml");
  auto m = rift::pd::discretize<2>(s);
  rift::load::Boundaries<2> loads(s, m);
  rift::pd::Contact<2> contact(s.contact, m);
  for (std::size_t i = 0; i < m.size(); ++i) m.velocity[i] = {40.0 * std::sin(1e3 * m.reference_position[i][1]), 0.0};
  rift::pd::compute_forces<2>(m, &contact);
  const double dt = 0.5 * rift::pd::stable_time_step<2>(m);
  for (int step = 0; step < 50; ++step) rift::pd::velocity_verlet_step<2>(m, loads, &contact, dt);
  const auto full = rift::pd::summarize<2>(m), lean = rift::pd::summarize<2>(m, false);
  EXPECT_GT(full.strain, 0.0);
  EXPECT_EQ(lean.strain, 0.0);
  EXPECT_EQ(lean.kinetic, full.kinetic);
  EXPECT_GT(full.broken_bonds, 0);
  EXPECT_EQ(lean.broken_bonds, full.broken_bonds);
  m.position[m.size() / 2][1] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(rift::pd::summarize<2>(m, false).strain));
}

}  // namespace
