// The viscoelastic state-based model (ves; Mitchell 2011, LAMMPS peri/ves) against an independent
// evaluation of its formulas on a lattice deformed over several steps, and against the closed-form
// stress relaxation of the standard linear solid it stands for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "rift/pd/bond_slabs.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/influence.hpp"
#include "rift/pd/stress.hpp"
#include "rift/scene/parse.hpp"

namespace {

constexpr double dx = 0.001, K = 14.9e9, G = 8.6e9, horizon = 3.015 * dx;

std::string ves_scene(int edge, double lambda, double tau, bool lammps_lattice) {
  std::ostringstream s;
  s << "[scene]\ndimension = 3\n[materials.rock]\nmodel = \"ves\"\ndensity = 2500.0\n"
    << "bulk_modulus = " << K << "\nshear_modulus = " << G << "\nviscous_fraction = " << lambda << "\nrelaxation_time = " << tau << "\n"
    << "influence = \"inverse_distance\"\n"
    << (lammps_lattice ? "surface_correction = false\n" : "")
    << "[regions.cube]\nshape = \"box\"\nmin = [-0.0005, -0.0005, -0.0005]\nmax = [" << (edge - 0.5) * dx << ", " << (edge - 0.5) * dx
    << ", " << (edge - 0.5) * dx << "]\n"
    << "[bodies.cube]\nmaterial = \"rock\"\nregion = \"cube\"\nspacing = 0.001\nhorizon = 3.015\n"
    << "lattice_origin = [-0.0005, -0.0005, -0.0005]\n" << (lammps_lattice ? "partial_volume = \"lammps\"\n" : "")
    << "[contact]\nenabled = false\n[solver]\nend_time = 1e-6\n";
  return s.str();
}

// two smooth non-affine displacement fields (strains ~ 1e-3) whose mix changes from step to step, so
// every bond's deviatoric extension follows its own history
std::array<double, 3> displacement(const std::array<double, 3>& x, int step) {
  const double L = 0.007, a = 0.4 * step, b = step == 2 ? -0.5 : 0.3 * step;
  return {a * 1e-3 * x[0] * x[0] / L + b * 2e-4 * x[1], a * 5e-4 * x[1] * x[2] / L + b * 3e-4 * x[2] * x[0] / L,
          -a * 3e-4 * x[2] * x[2] / L + b * 4e-4 * x[0]};
}

// The formulas of ves.hpp evaluated by brute force over all pairs, with LAMMPS' partial volumes and
// omega = 1/|xi| (no surface correction), and a dense per-pair history.
struct Reference {
  std::size_t n;
  std::vector<double> ed, eb;  // n x n
  explicit Reference(std::size_t n_) : n(n_), ed(n_ * n_, 0.0), eb(n_ * n_, 0.0) {}

  std::vector<std::array<double, 3>> forces(const rift::pd::Model<3>& m, double lambda, double tau, double dt) {
    const double V = dx * dx * dx, half = 0.5 * dx;
    auto scale = [&](double r0) { return std::abs(r0 - horizon) <= half ? (horizon + half - r0) / dx : 1.0; };
    auto dist = [&](const auto& p, std::size_t i, std::size_t j) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += (p[j][k] - p[i][k]) * (p[j][k] - p[i][k]);
      return std::sqrt(d);
    };
    std::vector<double> wvol(n, 0.0), theta(n, 0.0), coupling(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double r0 = dist(m.reference_position, i, j);
        if (i == j || r0 > horizon) continue;
        wvol[i] += r0 * V * scale(r0);
        theta[i] += (dist(m.position, i, j) - r0) * V * scale(r0);
      }
    for (std::size_t i = 0; i < n; ++i) theta[i] *= 3.0 / wvol[i];
    const double decay = std::exp(-dt / tau), beta = 1.0 - tau / dt * (1.0 - decay);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double r0 = dist(m.reference_position, i, j);
        if (i == j || r0 > horizon) continue;
        const double e_dev = dist(m.position, i, j) - r0 - theta[i] * r0 / 3.0;
        double& h = ed[i * n + j];
        double& b = eb[i * n + j];
        b = h * (1.0 - decay) + b * decay + beta * (e_dev - h);  // d e_b/dt = (e_d - e_b)/tau, e_d linear over the step
        h = e_dev;
        coupling[i] += (e_dev - lambda * b) * V * scale(r0);  // omega |xi| = 1
      }
    std::vector<std::array<double, 3>> f(n, {0, 0, 0});
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double r0 = dist(m.reference_position, i, j);
        if (i == j || r0 > horizon) continue;
        const double r = dist(m.position, i, j);
        auto t = [&](std::size_t p, std::size_t q) {  // t_p<q>
          const double a = 15.0 * G / wvol[p];
          return 3.0 / wvol[p] * (K * theta[p] - a * coupling[p] / 3.0) + a / r0 * (r - r0 - theta[p] * r0 / 3.0 - lambda * eb[p * n + q]);
        };
        const double pair = (t(i, j) + t(j, i)) * V * scale(r0);
        for (int k = 0; k < 3; ++k) f[i][k] += pair * (m.position[j][k] - m.position[i][k]) / r;
      }
    return f;
  }
};

// rift's ves forces equal the independent evaluation over three steps of a changing deformation
// (lambda = 0.4, tau = 2 dt: the back extensions move a lot per step); tolerance 2e-7 of the largest
// force: rift stores the extension histories in single precision (6e-8; the dilatation weights of
// this uncorrected lattice are taken in double, lps.hpp dilatation_scale).
TEST(Viscoelastic, ForcesMatchAnIndependentEvaluationOverSteps) {
  const double lambda = 0.4, dt = 1e-7, tau = 2e-7;
  const int edge = 8;
  auto s = rift::scene::parse_string(ves_scene(edge, lambda, tau, true), "ves.toml");
  auto m = rift::pd::discretize<3>(s);
  ASSERT_EQ(m.size(), std::size_t(edge * edge * edge));
  Reference ref(m.size());
  for (int step = 1; step <= 3; ++step) {
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto u = displacement(m.reference_position[i], step);
      for (int k = 0; k < 3; ++k) m.position[i][k] = m.reference_position[i][k] + u[k];
    }
    rift::pd::compute_forces<3>(m, nullptr, dt);
    const auto f = ref.forces(m, lambda, tau, dt);
    double scale = 0, worst = 0;
    for (const auto& v : f) scale = std::max(scale, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    ASSERT_GT(scale, 0.0);
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(m.force[i][k] - f[i][k]) / scale);
    std::printf("step %d: max |f_rift - f_formula| / max |f| = %.2e\n", step, worst);
    EXPECT_LT(worst, 2e-7) << "step " << step;
  }
}

// P_i (ves.hpp ves_dilatation) comes from per-particle sums of the last step's histories, not from a
// pass over them: over five steps of a changing deformation, on the surface-corrected lattice and on
// LAMMPS's, with bonds broken between the steps (both directions, as the passes break them) and
// bonds the pass itself breaks, it equals the sum over every intact bond of g omega |xi| V (e_d -
// lambda e_b) with e_d at the step's positions and the back extensions as stored (the pass's own broken
// bonds are taken out of the sums term by term, ves.hpp take_out_of_viscous_sums). Tolerance 1e-6 of
// the sum of the terms' magnitudes per particle: the back extensions are stored in single precision
// (6e-8 each), the sums are not.
TEST(Viscoelastic, CouplingFromSumsEqualsTheSumOverTheHistories) {
  for (const bool lammps_lattice : {false, true}) {
    auto text = ves_scene(9, 0.4, 2e-7, lammps_lattice);
    text.replace(text.find("influence = "), 0, "critical_stretch = 3e-3\n");
    auto m = rift::pd::discretize<3>(rift::scene::parse_string(text, "ves.toml"));
    const auto& body = m.bodies[0];
    auto& b = m.bonds;
    std::size_t broken_by_hand = 0;
    for (int step = 1; step <= 5; ++step) {
      if (step >= 3)  // every seventh pair of the lower half, from the third step on
        for (std::size_t i = 0; i < m.size(); ++i)
          for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
            const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
            if (j <= i || m.reference_position[i][2] > 0.004 || (i * 31 + j + std::size_t(step)) % 7 != 0 ||
                b.intact[static_cast<std::size_t>(k)] != rift::pd::bond_intact)
              continue;
            b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
            b.intact.set(static_cast<std::size_t>(rift::pd::reverse_bond(b, body, i, k)), rift::pd::bond_broken);
            ++broken_by_hand;
          }
      for (std::size_t i = 0; i < m.size(); ++i) {
        const auto u = displacement(m.reference_position[i], step);
        for (int k = 0; k < 3; ++k) m.position[i][k] = m.reference_position[i][k] + u[k];
      }
      rift::pd::compute_forces<3>(m, nullptr, 1e-7);
      double worst = 0.0;
      for (std::size_t i = 0; i < m.size(); ++i) {
        double sum = 0.0, size = 0.0;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
          if (b.intact[static_cast<std::size_t>(k)] != rift::pd::bond_intact) continue;
          const double xi = b.length(k);
          const double w = b.correction(i, k) * rift::pd::influence(body.constants.influence, xi, body.constants.horizon) * xi * b.volume(k);
          const auto h = rift::pd::history_slot(b, body, i, k);
          const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
          const double e = std::sqrt(std::pow(m.position[j][0] - m.position[i][0], 2) + std::pow(m.position[j][1] - m.position[i][1], 2) +
                                     std::pow(m.position[j][2] - m.position[i][2], 2)) - xi;
          const double e_d = e - m.dilatation[i] * xi / 3.0;
          sum += w * (e_d - 0.4 * b.back_extension[h]);
          size += std::abs(w) * (std::abs(e_d) + 0.4 * std::abs(b.back_extension[h]));
        }
        ASSERT_GT(size, 0.0);
        worst = std::max(worst, std::abs(m.dilatation_coupling[i] - sum) / size);
      }
      std::printf("%s lattice, step %d: max |P - sum| / sum |terms| = %.2e\n", lammps_lattice ? "LAMMPS" : "corrected", step, worst);
      EXPECT_LT(worst, 1e-6) << "step " << step;
    }
    const auto failed = rift::pd::failed_bonds<3>(m) / 2;
    std::printf("bonds broken: %zu by hand, %zu by the pass\n", broken_by_hand, failed - broken_by_hand);
    EXPECT_GT(broken_by_hand, 0u);
    EXPECT_GT(failed, broken_by_hand);  // the pass broke some too
  }
}

// While the history is held (dt = 0: the in-situ stage, dynamic relaxation) and every back extension
// is zero as made, forces.cpp takes the LPS force pass, which does not read the history: the
// deviatoric extension less lambda times zero is the same double, so the forces are the VES pass's to
// the bit (tolerance: none), on the surface-corrected lattice and on LAMMPS's. The first step that
// advances the history ends it; with a history that is not zero the two passes differ.
TEST(Viscoelastic, HeldHistoryAtRestTakesTheElasticPassToTheBit) {
  for (const bool lammps_lattice : {false, true}) {
    auto m = rift::pd::discretize<3>(rift::scene::parse_string(ves_scene(9, 0.4, 2e-7, lammps_lattice), "ves.toml"));
    ASSERT_TRUE(m.bonds.back_extension_at_rest);
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto u = displacement(m.reference_position[i], 1);
      for (int k = 0; k < 3; ++k) m.position[i][k] = m.reference_position[i][k] + u[k];
    }
    auto forces = [&](bool at_rest) {
      m.bonds.back_extension_at_rest = at_rest;
      rift::pd::compute_forces<3>(m, nullptr, 0.0);
      return m.force;
    };
    const auto elastic = forces(true), viscous = forces(false);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int k = 0; k < 3; ++k) differ += std::memcmp(&elastic[i][k], &viscous[i][k], sizeof(double)) != 0;
    EXPECT_EQ(differ, 0u) << (lammps_lattice ? "LAMMPS" : "corrected") << " lattice";
    double largest = 0.0;
    for (const auto& f : elastic) largest = std::max({largest, std::abs(f[0]), std::abs(f[1]), std::abs(f[2])});
    EXPECT_GT(largest, 0.0);
    // a history that is not zero: the VES pass reads it, and the forces change
    std::fill(m.bonds.back_extension.begin(), m.bonds.back_extension.end(), 1e-5f);
    const auto moved = forces(false);
    double change = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int k = 0; k < 3; ++k) change = std::max(change, std::abs(moved[i][k] - elastic[i][k]));
    EXPECT_GT(change, 1e-3 * largest);
    // a step that advances the history ends the rest
    m.bonds.back_extension_at_rest = true;
    rift::pd::compute_forces<3>(m, nullptr, 1e-7);
    EXPECT_FALSE(m.bonds.back_extension_at_rest);
  }
}

// The history of bond j-i is found from bond i-j without a stored slot (bond_slabs.hpp): at its
// offset's place in a whole row, by a search in the others. A 12^3 cube has both kinds of rows.
TEST(Viscoelastic, ReverseBondIsTheBondBack) {
  auto s = rift::scene::parse_string(ves_scene(12, 0.4, 2e-7, false), "ves.toml");
  const auto m = rift::pd::discretize<3>(s);
  const auto& b = m.bonds;
  const auto& body = m.bodies[0];
  std::size_t whole = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto j_row = [&](std::int64_t k) { return static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]); };
    whole += static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]) == body.family_count;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto r = rift::pd::reverse_bond(b, body, i, k);
      const auto j = j_row(k);
      ASSERT_GE(r, b.offset[j]);
      ASSERT_LT(r, b.offset[j + 1]);
      ASSERT_EQ(static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(r)]), i);
      ASSERT_EQ(b.family[static_cast<std::size_t>(r)], b.family_of(k).mirror);
    }
  }
  EXPECT_EQ(whole, std::size_t(6 * 6 * 6));  // the particles 3 or more spacings from every face (the family reaches 3 along an axis)
}

// The history by lattice offset (bonds.hpp): every directed bond has its own slot, and the two
// directions of a pair sit history_block slots apart (mirror_history_slot).
TEST(Viscoelastic, HistorySlotsPairTheTwoDirections) {
  auto s = rift::scene::parse_string(ves_scene(12, 0.4, 2e-7, false), "ves.toml");
  const auto m = rift::pd::discretize<3>(s);
  const auto& b = m.bonds;
  const auto& body = m.bodies[0];
  ASSERT_GE(b.back_extension.size(), b.neighbor.size());
  std::vector<int> used(b.back_extension.size(), 0);
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto h = rift::pd::history_slot(b, body, i, k);
      ASSERT_LT(h, used.size());
      ++used[h];
      const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
      EXPECT_EQ(rift::pd::mirror_history_slot(h), rift::pd::history_slot(b, body, j, rift::pd::reverse_bond(b, body, i, k)));
      EXPECT_EQ(h & rift::pd::Bonds::history_block, j > i ? 0u : rift::pd::Bonds::history_block);  // the lower end's direction first
    }
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<std::ptrdiff_t>(b.neighbor.size()));
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), static_cast<std::ptrdiff_t>(used.size() - b.neighbor.size()));
}

// Standard linear solid (Zener) under a shear strain ramped linearly to gamma over t_r and then held:
//   G(t) = G [(1 - lambda) + lambda exp(-t / tau)],
//   tau_xy(t) = G gamma / t_r [(1 - lambda) t + lambda tau (1 - exp(-t / tau))],                t <= t_r,
//   tau_xy(t) = G gamma / t_r [(1 - lambda) t_r + lambda tau (1 - exp(-t_r / tau)) exp(-(t - t_r) / tau)], t > t_r.
// The lattice (surface-corrected, 15^3, every point moved affinely each step, no dynamics) carries it
// at its centre particle, whose neighbours' families are whole, over 2.3 tau (sampled every 5 steps): the shear stress divided by the elastic (lambda = 0) stress of the
// same strain matches the closed form to 1e-6 (the back-extension update is exact for e_d linear in
// time; gamma = 1e-6 keeps the bond stretch linear in the strain), and the elastic shear stress is
// G gamma within 1% (the bond-pair stress in the bulk). A volumetric strain is carried by K alone and
// does not relax.
TEST(Viscoelastic, StressRelaxesAsAStandardLinearSolid) {
  const double lambda = 0.6, tau = 3e-6, dt = 1e-7;
  const int edge = 15, ramp = 10, hold = 60;
  auto s = rift::scene::parse_string(ves_scene(edge, lambda, tau, false), "ves.toml");
  auto elastic_scene = s;
  elastic_scene.materials[0].viscous_fraction = 0.0;
  const double mid = 0.5 * (edge - 1) * dx, tr = ramp * dt;
  for (const bool shear : {true, false}) {
    const double gamma = shear ? 1e-6 : 0.0, volumetric = shear ? 0.0 : 1e-6;
    auto m = rift::pd::discretize<3>(s);
    auto e = rift::pd::discretize<3>(elastic_scene);
    std::size_t centre = 0;
    for (std::size_t i = 0; i < m.size(); ++i)
      if (std::abs(m.reference_position[i][0] - mid) + std::abs(m.reference_position[i][1] - mid) + std::abs(m.reference_position[i][2] - mid) < 0.6 * dx)
        centre = i;
    double worst = 0.0;
    for (int step = 1; step <= ramp + hold; ++step) {
      const double f = std::min(1.0, double(step) / ramp);
      for (auto* model : {&m, &e})
        for (std::size_t i = 0; i < model->size(); ++i) {
          const auto& X = model->reference_position[i];
          // engineering shear gamma in x-y (x += gamma y), or an isotropic strain
          model->position[i] = {X[0] + f * (gamma * (X[1] - mid) + volumetric / 3.0 * (X[0] - mid)),
                                X[1] + f * volumetric / 3.0 * (X[1] - mid), X[2] + f * volumetric / 3.0 * (X[2] - mid)};
        }
      rift::pd::compute_forces<3>(m, nullptr, dt);
      rift::pd::compute_forces<3>(e, nullptr, dt);
      if (step % 5) continue;
      const auto sv = rift::pd::particle_stress<3>(m), se = rift::pd::particle_stress<3>(e);
      const double t = step * dt;
      if (shear) {
        const double shape = t <= tr ? ((1 - lambda) * t + lambda * tau * (1 - std::exp(-t / tau))) / tr
                                     : ((1 - lambda) * tr + lambda * tau * (1 - std::exp(-tr / tau)) * std::exp(-(t - tr) / tau)) / tr;
        const double full = se[6 * centre + 3] / f;  // elastic stress of the full strain
        worst = std::max(worst, std::abs(sv[6 * centre + 3] / full - shape));
        if (step == ramp) {
          std::printf("elastic shear stress / G gamma = %.5f\n", full / (G * gamma));
          EXPECT_NEAR(full / (G * gamma), 1.0, 0.01);
        }
      } else {
        const double mean_v = (sv[6 * centre] + sv[6 * centre + 1] + sv[6 * centre + 2]) / 3.0;
        const double mean_e = (se[6 * centre] + se[6 * centre + 1] + se[6 * centre + 2]) / 3.0;
        worst = std::max(worst, std::abs(mean_v / mean_e - 1.0));
        if (step == ramp) {
          std::printf("mean stress / K volumetric strain = %.5f\n", mean_e / (K * volumetric));
          EXPECT_NEAR(mean_e / (K * volumetric), 1.0, 0.01);
        }
      }
    }
    std::printf("%s: max deviation from the closed form %.2e\n", shear ? "shear" : "volumetric", worst);
    EXPECT_LT(worst, 1e-6) << (shear ? "shear" : "volumetric");
  }
}

}  // namespace
