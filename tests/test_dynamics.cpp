// Validation 3: linear and angular momentum of a free body with random velocities are conserved
// to round-off by velocity-Verlet with pairwise-antisymmetric bond forces (Silling 2000).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <omp.h>

#include "rift/load/boundary.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/velocity_verlet.hpp"
#include "cases/homogeneous.hpp"

namespace {

template <int D>
void momentum_conserved(const std::string& model) {
  auto s = rift::scene::parse_string(rift::validation::box_scene(D, model, 0.25, "", "", 3.015, "strain", "critical_stretch = 0.002\n"), "m.toml");
  auto m = rift::pd::discretize<D>(s);
  rift::load::Boundaries<D> loads(s, m);
  rift::pd::Contact<D> contact(s.contact, m);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 5.0);
  for (auto& v : m.velocity)
    for (auto& c : v) c = g(rng);
  auto totals = [&](double& p_norm, std::array<double, 3>& p, std::array<double, 3>& L) {
    p = {0, 0, 0};
    L = {0, 0, 0};
    for (std::size_t i = 0; i < m.size(); ++i) {
      const double mass = m.constants_of(i).density * m.volume[i];
      std::array<double, 3> x{0, 0, 0}, v{0, 0, 0};
      for (int k = 0; k < D; ++k) x[k] = m.position[i][k], v[k] = m.velocity[i][k];
      for (int k = 0; k < 3; ++k) p[k] += mass * v[k];
      L[0] += mass * (x[1] * v[2] - x[2] * v[1]);
      L[1] += mass * (x[2] * v[0] - x[0] * v[2]);
      L[2] += mass * (x[0] * v[1] - x[1] * v[0]);
    }
    p_norm = 0;
    for (std::size_t i = 0; i < m.size(); ++i)
      p_norm += m.constants_of(i).density * m.volume[i] * std::sqrt(rift::dot<D>(m.velocity[i], m.velocity[i]));
  };
  double scale0;
  std::array<double, 3> p0, L0, p1, L1;
  totals(scale0, p0, L0);
  const double dt = 0.5 * rift::pd::stable_time_step<D>(m);
  rift::pd::compute_forces<D>(m, &contact);
  for (int step = 0; step < 200; ++step) rift::pd::velocity_verlet_step<D>(m, loads, &contact, dt);
  double scale1;
  totals(scale1, p1, L1);
  const double length = 0.02;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(p1[k], p0[k], 1e-12 * scale0) << model << " p" << k;
    EXPECT_NEAR(L1[k], L0[k], 1e-10 * scale0 * length) << model << " L" << k;
  }
  auto e = rift::pd::summarize<D>(m);
  EXPECT_GT(e.broken_bonds, 0) << "random velocities should break some bonds";
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
