// The elastic-plastic state-based law (model = "eps"; Mitchell 2011, SAND2011-3166; pd/laws/eps.hpp).
//  - Forces against an independent evaluation of the model's formulas, bond by bond, with plastic
//    extensions in every bond and particles past yield: 1e-11 of the largest force.
//  - With a yield stress no state reaches, the trajectory of the LPS (1e-12 relative).
//  - With a low yield stress the run leaves the LPS's and keeps its linear momentum to round-off.
//  - Homogeneous paths (3D and plane strain; omega = 1): a pure shear is elastic (tau = G gamma) up
//    to tau = sigma_Y / sqrt(3), then flows at it, and unloads with slope G to the permanent set
//    gamma_max - tau_Y / G; a 3D uniaxial strain yields at sigma_xx - sigma_yy = sigma_Y (J2), each
//    within 2% (the closed forms of perfect J2 plasticity, which the law's psi_0 makes).
// The common checks of every law (energy, patch test, momentum, G0) are in test_law_conformance.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "cases/homogeneous.hpp"
#include "cases/momentum.hpp"
#include "rift/load/boundary.hpp"
#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/stress.hpp"
#include "rift/pd/velocity_verlet.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace {

using rift::validation::box_scene;

template <int D>
rift::pd::Model<D> eps_box(double yield_stress, const std::string& extra_material = "", const std::string& size = "") {
  const std::string material = "yield_stress = " + std::to_string(yield_stress) + "\n" + extra_material;
  return rift::pd::discretize<D>(rift::scene::parse_string(box_scene(D, "eps", 0.25, "", size, 3.015, "strain", material), "eps.toml"));
}

TEST(Eps, ForcesMatchAnIndependentEvaluationOfMitchellsFormulas) {
  constexpr int D = 3;
  auto m = eps_box<D>(4.0e5, "surface_correction = false\n", "max = [0.008, 0.008, 0.008]");
  const auto& body = m.bodies[0];
  const auto& c = body.constants;
  auto& b = m.bonds;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int k = 0; k < D; ++k) m.position[i][k] = m.reference_position[i][k] * (1.0 + 2e-4 * (k + 1)) + 2e-7 * u(rng);
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) b.back_extension[rift::pd::history_slot(b, body, i, k)] = static_cast<float>(1e-7 * u(rng));
  rift::pd::compute_forces<D>(m, nullptr);  // trial states from the stored e_p (nothing committed)

  // the model's formulas, row by row: theta, m, the trial norm, beta, t_i<j>
  const std::size_t n = m.size();
  const double G = c.shear_modulus, K = c.kappa;
  // psi_0 of each particle: ||t_d||^2 / 2 of its family under the pure shear gamma = sigma_Y / (sqrt(3) G),
  // the shear's orientations averaged: (15 G / m)^2 (gamma^2 / 2) (2/15) sum |xi|^2 V / 2
  const double gamma = c.yield_stress / (std::sqrt(3.0) * G);
  std::vector<double> weighted(n, 0.0), theta(n, 0.0), beta(n, 1.0);
  auto extension = [&](std::size_t i, std::int64_t k) {
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    double r2 = 0.0;
    for (int q = 0; q < D; ++q) r2 += (m.position[j][q] - m.position[i][q]) * (m.position[j][q] - m.position[i][q]);
    return std::sqrt(r2) - b.length(k);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) weighted[i] += b.length(k) * b.length(k) * b.volume(k);
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) theta[i] += 3.0 / weighted[i] * b.length(k) * extension(i, k) * b.volume(k);
  auto deviatoric = [&](std::size_t i, std::int64_t k) {  // the trial t_d of direction i -> j
    return 15.0 * G / weighted[i] * (extension(i, k) - theta[i] * b.length(k) / 3.0 - b.back_extension[rift::pd::history_slot(b, body, i, k)]);
  };
  int yielded = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double norm2 = 0.0, family = 0.0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      norm2 += deviatoric(i, k) * deviatoric(i, k) * b.volume(k);
      family += b.length(k) * b.length(k) * b.volume(k);
    }
    const double psi0 = 0.5 * std::pow(15.0 * G / weighted[i], 2) * (0.5 * gamma * gamma) * (2.0 / 15.0) * family;
    if (norm2 / 2.0 > psi0) beta[i] = std::sqrt(2.0 * psi0 / norm2), ++yielded;
  }
  auto t = [&](std::size_t i, std::int64_t k) { return 3.0 * K * theta[i] * b.length(k) / weighted[i] + beta[i] * deviatoric(i, k); };
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double f[D] = {};
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      std::int64_t back = -1;  // j's bond to i
      for (auto l = b.offset[j]; l < b.offset[j + 1]; ++l)
        if (static_cast<std::size_t>(b.neighbor[l]) == i) back = l;
      ASSERT_GE(back, 0);
      const double r = extension(i, k) + b.length(k);
      for (int q = 0; q < D; ++q) f[q] += (t(i, k) + t(j, back)) * b.volume(k) * (m.position[j][q] - m.position[i][q]) / r;
    }
    for (int q = 0; q < D; ++q) worst = std::max(worst, std::abs(f[q] - m.force[i][q])), largest = std::max(largest, std::abs(f[q]));
  }
  std::printf("%d of %zu particles past yield; largest force %.3e, worst difference %.3e\n", yielded, n, largest, worst);
  EXPECT_GT(yielded, 0);
  EXPECT_LT(yielded, static_cast<int>(n));
  EXPECT_LT(worst, 1e-11 * largest);
}

/// Positions after `steps` velocity-Verlet steps from the same random velocities; the total energy
/// (kinetic and strain) before and after into `energy`, where given.
template <int D>
rift::pd::Model<D> run_steps(const std::string& model, const std::string& material, int steps, double* energy = nullptr) {
  auto s = rift::scene::parse_string(box_scene(D, model, 0.25, "", "", 3.015, "strain", "critical_stretch = 0.01\n" + material), "run.toml");
  auto m = rift::pd::discretize<D>(s);
  rift::load::Boundaries<D> loads(s, m);
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 2.0);
  for (auto& v : m.velocity)
    for (auto& x : v) x = g(rng);
  const double dt = 0.5 * rift::pd::stable_time_step<D>(m);
  rift::pd::compute_forces<D>(m, nullptr);
  auto total = [&] {
    const auto e = rift::pd::summarize<D>(m);
    return e.kinetic + e.strain;
  };
  if (energy) energy[0] = total();
  for (int step = 0; step < steps; ++step) rift::pd::velocity_verlet_step<D>(m, loads, nullptr, dt);
  if (energy) energy[1] = total();
  return m;
}

template <int D>
double largest_difference(const rift::pd::Model<D>& a, const rift::pd::Model<D>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < D; ++k)
      worst = std::max(worst, std::abs((a.position[i][k] - a.reference_position[i][k]) - (b.position[i][k] - b.reference_position[i][k])));
  return worst;
}

TEST(Eps, UnreachableYieldStressGivesTheLpsTrajectory) {
  const auto lps = run_steps<3>("lps", "", 100);
  const auto eps = run_steps<3>("eps", "yield_stress = 1.0e15\n", 100);
  double scale = 0.0;
  for (std::size_t i = 0; i < lps.size(); ++i)
    for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(lps.position[i][k] - lps.reference_position[i][k]));
  EXPECT_LE(largest_difference(lps, eps), 1e-12 * scale);
}

TEST(Eps, PlasticRunLeavesTheLpsAndConservesMomentum) {
  const auto lps = run_steps<3>("lps", "", 100);
  double energy[2];
  const auto eps = run_steps<3>("eps", "yield_stress = 1.0e6\n", 100, energy);
  double scale = 0.0, plastic = 0.0;
  for (std::size_t i = 0; i < lps.size(); ++i)
    for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(lps.position[i][k] - lps.reference_position[i][k]));
  for (float e : eps.bonds.back_extension) plastic = std::max(plastic, double(std::abs(e)));
  std::printf("largest plastic extension %.3e m; displacements differ by %.3e of the largest\n", plastic, largest_difference(lps, eps) / scale);
  std::printf("total energy %.6e J before, %.6e J after (plastic work and broken bonds dissipate)\n", energy[0], energy[1]);
  EXPECT_LT(energy[1], energy[0]);
  EXPECT_GT(plastic, 0.0);
  EXPECT_GT(largest_difference(lps, eps), 1e-3 * scale);
  EXPECT_LT((rift::validation::momentum_drift<3>("eps", 200, "yield_stress = 1.0e6\n")), 1e-11);
  EXPECT_LT((rift::validation::momentum_drift<2>("eps", 200, "yield_stress = 1.0e6\n")), 1e-11);
}

/// Drives a box through homogeneous strains eps(gamma_k) (each an explicit step's evaluation, which
/// commits e_p) and returns the mean bond-pair stress sigma_pq of the particles farther than two
/// horizons from every face, at each.
template <int D>
std::vector<double> stress_along(rift::pd::Model<D>& m, const std::vector<double>& path, int p, int q, int along_p, int along_q,
                                 bool symmetric) {
  const auto [lo, hi] = m.reference_bounds();
  const double horizon = m.bodies[0].constants.horizon;
  std::vector<std::size_t> deep;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double depth = 1e9;
    for (int a = 0; a < D; ++a) depth = std::min({depth, m.reference_position[i][a] - lo[a], hi[a] - m.reference_position[i][a]});
    if (depth > 2.0 * horizon) deep.push_back(i);
  }
  std::vector<double> out;
  for (double g : path) {
    for (std::size_t i = 0; i < m.size(); ++i) {
      m.position[i] = m.reference_position[i];
      m.position[i][along_p] += (symmetric ? 0.5 : 1.0) * g * m.reference_position[i][along_q];
      if (symmetric) m.position[i][along_q] += 0.5 * g * m.reference_position[i][along_p];
    }
    rift::pd::compute_forces<D>(m, nullptr, 1.0);  // as a step: commits e_p
    const auto s = rift::pd::particle_stress<D>(m);
    const int component = p == q ? p : (p + q == 1 ? 3 : p + q == 3 ? 4 : 5);  // xx, yy, zz, xy, yz, xz
    double sum = 0.0;
    for (auto i : deep) sum += s[6 * i + static_cast<std::size_t>(component)];
    out.push_back(sum / static_cast<double>(deep.size()));
  }
  return out;
}

template <int D>
void check_pure_shear() {
  const double sy = 2.0e6;
  auto m = eps_box<D>(sy, "", D == 3 ? "max = [0.016, 0.016, 0.016]" : "max = [0.02, 0.02]");
  const double G = m.bodies[0].constants.shear_modulus, tau_y = sy / std::sqrt(3.0), gamma_y = tau_y / G;
  std::vector<double> path;
  for (int k = 1; k <= 30; ++k) path.push_back(3.0 * gamma_y * k / 30);  // to three times the yield strain
  for (int k = 1; k <= 20; ++k) path.push_back(3.0 * gamma_y - 2.0 * gamma_y * k / 20);  // unloaded by 2 gamma_y
  const auto tau = stress_along<D>(m, path, 0, 1, 0, 1, true);
  double worst = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const double g = path[k];
    double expected = std::min(G * g, tau_y);  // loading
    if (k >= 30) expected = tau_y - G * (3.0 * gamma_y - g);  // elastic unloading from the flow stress
    worst = std::max(worst, std::abs(tau[k] - expected) / tau_y);
    if (std::getenv("EPS_DEBUG")) std::printf("%zu gamma/gamma_y %.3f tau/tau_y %.5f expected %.5f\n", k, g / gamma_y, tau[k] / tau_y, expected / tau_y);
  }
  // the permanent set: the strain where the unloading line reaches zero stress
  const double set = path.back() - tau.back() / G, expected_set = 3.0 * gamma_y - gamma_y;
  std::printf("%dD pure shear: worst |tau - closed form| %.2e of tau_Y; permanent set %.4e (closed form %.4e)\n", D, worst, set, expected_set);
  EXPECT_LT(worst, 0.02);
  EXPECT_NEAR(set / expected_set, 1.0, 0.02);
}

TEST(Eps, PureShearYieldsAtTheVonMisesShearStressFlowsAndUnloadsToThePermanentSet) {
  check_pure_shear<3>();
  check_pure_shear<2>();
}

TEST(Eps, UniaxialStrainYieldsAsJ2) {
  const double sy = 2.0e6;
  auto m = eps_box<3>(sy, "", "max = [0.016, 0.016, 0.016]");
  const double G = m.bodies[0].constants.shear_modulus, K = m.bodies[0].constants.kappa, eps_y = sy / (2.0 * G);
  std::vector<double> path;
  for (int k = 1; k <= 30; ++k) path.push_back(3.0 * eps_y * k / 30);
  auto copy = m;
  const auto sxx = stress_along<3>(m, path, 0, 0, 0, 0, false);
  const auto syy = stress_along<3>(copy, path, 1, 1, 0, 0, false);
  double worst = 0.0, worst_mean = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    worst = std::max(worst, std::abs((sxx[k] - syy[k]) - std::min(2.0 * G * path[k], sy)) / sy);
    worst_mean = std::max(worst_mean, std::abs((sxx[k] + 2.0 * syy[k]) / 3.0 - K * path[k]) / (K * path.back()));
  }
  std::printf("uniaxial strain: worst |sxx - syy - closed form| %.2e of sigma_Y, mean stress %.2e of its largest\n", worst, worst_mean);
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(worst_mean, 0.02);
}

// The in-situ stage is the run's first equilibrium, and it commits the plastic extensions it reached
// (run/simulation.hpp equilibrate_in_situ, pd::commit_at_equilibrium), as a load step of dynamic
// relaxation does. A 5 mm borehole in a 40 x 40 mm plane strain block under the hydrostatic far-field
// stress p = 10 MPa: Kirsch's elastic wall stresses are sigma_theta = -2p, sigma_r = 0 and, in plane
// strain, sigma_z = nu (sigma_theta + sigma_r) = -p/2, so sqrt(J2) = 1.04 p at the wall, and the wall
// yields where that passes the shear yield k = sigma_Y / sqrt(3) (J2). sigma_Y = 12 MPa (k = 0.69 p):
// plastic extensions after the stage, and a second commit at the same equilibrium changes none (to
// float round-off); sigma_Y = 30 MPa (k = 1.73 p): none.
TEST(Eps, TheInSituStageCommitsThePlasticExtensionsOfItsEquilibrium) {
  for (const double yield : {12e6, 30e6}) {
    const std::string text = R"([scene]
dimension = 2
plane = "strain"
thickness = 0.001
[materials.rock]
model = "eps"
density = 2500.0
youngs_modulus = 10e9
poisson_ratio = 0.25
yield_stress = )" + std::to_string(yield) + R"(
[regions.block]
shape = "box"
min = [-0.02, -0.02]
max = [0.02, 0.02]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0]
radius = 0.005
[regions.rock]
shape = "difference"
of = ["block", "hole"]
[bodies.block]
material = "rock"
region = "rock"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = -10e6
tolerance = 1e-8
[solver]
type = "dynamic_relaxation"
)";
    auto s = rift::scene::parse_string(text, "eps_borehole.toml");
    rift::run::Simulation<2> sim(s);
    const auto r = sim.equilibrate_in_situ(s.in_situ);
    ASSERT_TRUE(r.converged) << r.residual << " after " << r.iterations;
    const auto& e_p = sim.model.bonds.back_extension;
    float largest = 0.0f;
    for (std::size_t h = 0; h < e_p.size(); ++h) largest = std::max(largest, std::abs(e_p[h]));
    std::printf("sigma_Y %.0f MPa: in-situ stage %d iterations, largest plastic extension %.3e m\n", yield / 1e6, r.iterations, largest);
    if (yield > 20e6) {
      EXPECT_EQ(largest, 0.0f) << "k > p: the wall stays elastic";
      continue;
    }
    ASSERT_GT(largest, 0.0f) << "k < p: the wall yields, and the stage commits it";
    const std::vector<float> committed(e_p.data(), e_p.data() + e_p.size());
    rift::pd::commit_at_equilibrium<2>(sim.model, sim.contact_ptr());
    float change = 0.0f;
    for (std::size_t h = 0; h < e_p.size(); ++h) change = std::max(change, std::abs(e_p[h] - committed[h]));
    EXPECT_LE(change, 1e-5f * largest) << "the stage's equilibrium is committed";
  }
}

}  // namespace
