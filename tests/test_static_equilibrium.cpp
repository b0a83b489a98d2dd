// The in-situ stage's conjugate gradients (pd/static_equilibrium.hpp) against dynamic relaxation
// (Kilic and Madenci 2010), the solver it replaced: both find the one static equilibrium of a held
// body, so at a tolerance of 1e-9 their displacements agree to a millionth of the largest one, and the
// forces evaluated afresh at the conjugate gradients' positions meet the tolerance. Cases: a 3D VES
// block (the thesis example's shale) with a borehole, held by tractions alone (its rigid motions
// projected out), and a 2D block with a borehole between rigid platens (a platen one unknown).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rift/pd/coarse_space.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/geomech/in_situ_strain.hpp"
#include "rift/pd/rigid_motion.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"
#include "dense_stiffness.hpp"
#include "rock_scene.hpp"

namespace {

// 12 x 12 x 8 mm of the thesis' shale at 1 mm, a 4 mm borehole along z through it, under
// sigma_v = -1.5, sigma_H = -1.0, sigma_h = -0.75 MPa
std::string shale_block(const std::string& solver) {
  return R"([scene]
dimension = 3
[materials.shale]
model = "ves"
density = 2500.0
bulk_modulus = 10.6e9
shear_modulus = 1.0e9
critical_stretch = 5e-4
alpha = 0.1
viscous_fraction = 0.5
relaxation_time = 1e-4
surface_correction = false
[regions.block]
shape = "box"
min = [-0.006, -0.006, -0.004]
max = [0.006, 0.006, 0.004]
[regions.hole]
shape = "cylinder"
center = [0.0, 0.0, -0.004]
axis = [0.0, 0.0, 0.008]
radius = 0.002
[regions.rock]
shape = "difference"
of = ["block", "hole"]
[bodies.block]
material = "shale"
region = "rock"
spacing = 0.001
horizon = 3.0
[[boreholes]]
region = "hole"
pressure = 0.5e6
[in_situ_stress]
sigma_v = -1.5e6
sigma_H = -1.0e6
sigma_h = -0.75e6
start = "uniform_strain"
tolerance = 1e-9
solver = ")" + solver + R"("
[solver]
type = "explicit"
end_time = 1e-6
)";
}

// A plane strain block of the tests' rock, 2 half_x by 2 half_y, with a borehole of `radius` at
// `pressure` in its middle; in_situ_keys go to [in_situ_stress] (with the tolerance 1e-9 and the
// solver).
std::string block_with_borehole(double half_x, double half_y, double radius, double pressure, const std::string& in_situ_keys,
                                const std::string& solver) {
  auto number = [](double v) { return std::to_string(v); };
  return rift::test::plane_strain_rock() + "[regions.block]\nshape = \"box\"\nmin = [-" + number(half_x) + ", -" + number(half_y) +
         "]\nmax = [" + number(half_x) + ", " + number(half_y) + "]\n[regions.hole]\nshape = \"cylinder\"\ncenter = [0.0, 0.0]\nradius = " +
         number(radius) + R"(
[regions.rock]
shape = "difference"
of = ["block", "hole"]
[bodies.block]
material = "rock"
region = "rock"
spacing = 0.001
horizon = 3.015
[[boreholes]]
region = "hole"
pressure = )" + number(pressure) + "\n[in_situ_stress]\n" + in_situ_keys + "tolerance = 1e-9\nsolver = \"" + solver + R"("
[solver]
type = "dynamic_relaxation"
)";
}

// a 20 x 40 mm block between platens, a 6 mm borehole at 1 MPa, sigma_H = -10 MPa along y and
// sigma_h = -2 MPa along x
std::string block_between_platens(const std::string& solver) {
  return block_with_borehole(0.01, 0.02, 0.003, 1e6, "sigma_H = -10e6\nsigma_h = -2e6\nsigma_H_axis = \"y\"\nfaces = \"platens\"\n", solver);
}

// The residual of relax's measure, from a fresh evaluation of the forces at the particles' positions:
// free components less a free body's rigid part, a platen's net force, over the loads and reactions.
template <int D>
double fresh_residual(rift::run::Simulation<D>& sim) {
  auto& m = sim.model;
  rift::pd::HeldBreaking<D> held(m);
  rift::pd::compute_forces<D>(m, sim.contact_ptr());
  sim.loads.apply_body_forces(m, 0.0);
  const std::size_t n = m.size();
  const bool free_body = std::none_of(m.constrained.begin(), m.constrained.end(), [](std::uint8_t c) { return c != 0; });
  auto total = [&](std::size_t i) {
    rift::Vec<D> f;
    for (int k = 0; k < D; ++k) f[k] = (m.force[i][k] + m.body_force[i][k]) * m.volume[i];
    return f;
  };
  const rift::pd::DynamicRelaxation<D> dr(m);  // its bound, as the weight of the rigid part
  const auto rigid = rift::pd::rigid_acceleration<D>(
      m.position, [&](std::size_t i) { return dr.fictitious_density()[i] * m.volume[i]; }, total, rift::pd::line_of(m));
  std::vector<std::uint8_t> on_platen(n, 0);
  for (const auto& p : m.platens)
    for (const auto i : p.particles) on_platen[i] |= std::uint8_t(1u << p.axis);
  double squared = 0.0, load = 0.0, reaction = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) {
      const double b = m.body_force[i][k] * m.volume[i], f = m.force[i][k] * m.volume[i];
      load += b * b;
      if (m.constrained[i] >> k & 1) {
        reaction += f * f;
        continue;
      }
      if (on_platen[i] >> k & 1) continue;
      const double r = total(i)[k] - (free_body ? dr.fictitious_density()[i] * m.volume[i] * rigid.at(m.position[i])[k] : 0.0);
      squared += r * r;
    }
  for (const auto& p : m.platens) {
    double net = 0.0;
    for (const auto i : p.particles) net += total(i)[p.axis];
    squared += net * net;
  }
  return std::sqrt(squared) / (std::sqrt(load) + std::sqrt(reaction));
}

template <int D, class Scene>
void check_same_equilibrium(Scene scene, const char* name) {
  std::vector<rift::Vec<D>> displacement[2];
  int iterations[2] = {};
  for (int solver = 0; solver < 2; ++solver) {
    auto s = rift::scene::parse_string(scene(solver == 0 ? "conjugate_gradient" : "dynamic_relaxation"), name);
    rift::run::Simulation<D> sim(s);
    const auto r = sim.equilibrate_in_situ(s.in_situ);
    ASSERT_TRUE(r.converged) << name << " solver " << solver << ": residual " << r.residual;
    iterations[solver] = r.iterations + (solver == 1 ? 50 : 0);  // and dynamic relaxation's 50 power iterations
    if (solver == 0) {
      EXPECT_EQ(r.density_factor, 0.0) << "the conjugate gradients needed dynamic relaxation to finish";
      EXPECT_LT(fresh_residual<D>(sim), 1e-9) << name;
    }
    for (std::size_t i = 0; i < sim.model.size(); ++i) displacement[solver].push_back(sim.model.displacement(i));
  }
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < displacement[0].size(); ++i)
    for (int k = 0; k < D; ++k) {
      largest = std::max(largest, std::abs(displacement[1][i][k]));
      difference = std::max(difference, std::abs(displacement[0][i][k] - displacement[1][i][k]));
    }
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(difference, 1e-6 * largest) << name;
  EXPECT_LT(iterations[0], iterations[1]) << name;
  std::printf("%s: %d force evaluations of conjugate gradients, %d of dynamic relaxation (with its power iterations); "
              "displacements differ by %.2g of the largest\n",
              name, iterations[0], iterations[1], difference / largest);
}

// a 64 x 64 mm block held by tractions, an 8 mm borehole at 2 MPa, sigma_H = -10 MPa along x and
// sigma_h = -5 MPa: nine aggregates of 7.03 mm on each axis
std::string large_free_block(const std::string& solver) {
  return block_with_borehole(0.032, 0.032, 0.004, 2e6, "sigma_H = -10e6\nsigma_h = -5e6\nstart = \"uniform_strain\"\n", solver);
}

TEST(StaticEquilibrium, ConjugateGradientsFindDynamicRelaxationsEquilibriumOfAFreeBlockWithABorehole) {
  check_same_equilibrium<3>(shale_block, "shale_block.toml");
}

TEST(StaticEquilibrium, ConjugateGradientsFindDynamicRelaxationsEquilibriumBetweenPlatens) {
  check_same_equilibrium<2>(block_between_platens, "block_platens.toml");
}

// With the coarse space of aggregates (pd/coarse_space.hpp) in play: the 64 mm block's equilibrium
// is dynamic relaxation's, in fewer force evaluations (its probes of the coarse operator included).
TEST(StaticEquilibrium, ConjugateGradientsWithTheCoarseSpaceFindTheSameEquilibrium) {
  check_same_equilibrium<2>(large_free_block, "large_free_block.toml");
}

// The coarse operator that coarse_space.hpp assembles from 3^D coloured probes is the Galerkin
// product P^T K P of the whole stiffness (up to its symmetrization and the 1e-10 of its largest
// diagonal it adds): on an 18 x 18 LPS lattice at 1 mm at its in-situ strain (three aggregates of 7.03 mm on
// each axis; LPS couples particles two horizons apart), K dense by central differences of the
// forces, to 1e-9 of K_c's largest entry.
TEST(StaticEquilibrium, CoarseOperatorFromColouredProbesIsTheGalerkinProduct) {
  const std::string text = rift::test::plane_strain_rock() + R"([regions.block]
shape = "box"
min = [-0.0085, -0.0085]
max = [0.0085, 0.0085]
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[in_situ_stress]
sigma_H = -10e6
sigma_h = -5e6
[solver]
type = "dynamic_relaxation"
)";
  auto s = rift::scene::parse_string(text, "coarse.toml");
  rift::run::Simulation<2> sim(s);
  auto& m = sim.model;
  rift::pd::HeldBreaking<2> held_bonds(m);
  rift::geomech::apply_in_situ_strain<2>(m, s.in_situ);
  const std::size_t n = m.size(), N = 2 * n;
  ASSERT_EQ(n, 324u);
  const Eigen::MatrixXd K = rift::test::dense_stiffness<2>(m, 1e-9);
  rift::pd::CoarseSpace<2> coarse;
  const double edge = 2.0 * m.bodies[0].constants.horizon + m.bodies[0].constants.spacing;
  ASSERT_TRUE(coarse.make_aggregates(m.reference_position, edge));
  ASSERT_EQ(coarse.aggregates(), 9u);
  Eigen::VectorXd response(static_cast<Eigen::Index>(N));
  const bool factored = coarse.assemble([](std::size_t, int) { return false; }, [&](auto direction) {
    Eigen::VectorXd u(static_cast<Eigen::Index>(N));
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 2; ++k) u[static_cast<Eigen::Index>(2 * i + static_cast<std::size_t>(k))] = direction(i)[k];
    response = K * u;
    return [&](std::size_t i) {
      return rift::Vec<2>{response[static_cast<Eigen::Index>(2 * i)], response[static_cast<Eigen::Index>(2 * i + 1)]};
    };
  });
  ASSERT_TRUE(factored);
  const std::size_t M = 2 * coarse.aggregates();
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(M));
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k)
      P(static_cast<Eigen::Index>(2 * i + static_cast<std::size_t>(k)), static_cast<Eigen::Index>(2 * coarse.aggregate_of(i) + static_cast<std::size_t>(k))) = 1.0;
  const Eigen::MatrixXd galerkin = P.transpose() * K * P;
  const Eigen::MatrixXd expected = 0.5 * (galerkin + galerkin.transpose());
  const Eigen::MatrixXd assembled = Eigen::MatrixXd(coarse.matrix());
  const double largest = expected.cwiseAbs().maxCoeff();
  EXPECT_LT((assembled - expected).cwiseAbs().maxCoeff(), 1e-9 * largest);
}

}  // namespace

namespace {

// K_c is factored in nested dissection order (coarse_space.hpp dissection_order). On a 2D body of
// 11 x 7 aggregates with a notch of empty cells, from a nearest-neighbour spring lattice (springs
// between particles a spacing apart, and a soft tie of each particle to its place so that K is
// definite): the order holds every aggregate once, the halves of the first cut (across x, the longest
// axis, at its middle column of cells) come before that column (so no aggregate of one half
// neighbours one of the other); the coarse solution equals a dense solve of K_c to 1e-10.
TEST(StaticEquilibrium, CoarseSpaceInDissectionOrderSolvesAsTheDenseFactorization) {
  const double h = 1.0, edge = 3.0;  // three particles across an aggregate
  std::vector<rift::Vec<2>> x;
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 33; ++i)
      if (!(i >= 15 && i < 18 && j < 9)) x.push_back(rift::Vec<2>{i * h, j * h});  // the notch: cells (5, 0..2) empty
  const std::size_t n = x.size();
  rift::pd::CoarseSpace<2> coarse;
  ASSERT_TRUE(coarse.make_aggregates(x, edge));
  const std::size_t A = coarse.aggregates();
  ASSERT_EQ(A, 11u * 7u - 3u);
  auto cell = [&](std::uint32_t a) {
    for (std::size_t i = 0; i < n; ++i)
      if (coarse.aggregate_of(i) == a) return std::array<int, 2>{int(x[i][0] / edge), int(x[i][1] / edge)};
    return std::array<int, 2>{-1, -1};
  };
  const auto order = coarse.dissection_order();
  ASSERT_EQ(order.size(), A);
  std::vector<int> seen(A, 0);
  for (const auto a : order) ++seen[a];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(A));
  const int middle = 5;  // cells 0..10 across x
  std::size_t k = 0;
  for (; k < order.size() && cell(order[k])[0] < middle; ++k) {}
  for (; k < order.size() && cell(order[k])[0] > middle; ++k) {}
  for (; k < order.size() && cell(order[k])[0] == middle; ++k) {}
  EXPECT_EQ(k, order.size()) << "the first cut's halves, then its column";
  // K u: springs of stiffness 1 along the lattice's axes, and 0.01 to each particle's place
  auto K_times = [&](auto direction) {
    std::vector<rift::Vec<2>> f(n, rift::Vec<2>{});
    for (std::size_t i = 0; i < n; ++i) {
      const rift::Vec<2> u_i = direction(i);
      for (int q = 0; q < 2; ++q) f[i][q] += 0.01 * u_i[q];
      for (std::size_t j = 0; j < n; ++j) {
        const double d = std::hypot(x[j][0] - x[i][0], x[j][1] - x[i][1]);
        if (d > 1.01 * h || j == i) continue;
        const rift::Vec<2> u_j = direction(j);
        for (int q = 0; q < 2; ++q) f[i][q] += u_i[q] - u_j[q];
      }
    }
    return [f](std::size_t i) { return f[i]; };
  };
  ASSERT_TRUE(coarse.assemble([](std::size_t, int) { return false; }, K_times));
  std::vector<rift::Vec<2>> y(n);
  for (std::size_t i = 0; i < n; ++i) y[i] = rift::Vec<2>{std::sin(0.37 * double(i)), std::cos(0.11 * double(i) * double(i % 7))};
  const Eigen::VectorXd solution = coarse.solve([&](std::size_t i) { return y[i]; });
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * A));
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < 2; ++q) rhs[static_cast<Eigen::Index>(2 * coarse.aggregate_of(i) + static_cast<std::size_t>(q))] += y[i][q];
  const Eigen::VectorXd dense = Eigen::MatrixXd(coarse.matrix()).ldlt().solve(rhs);
  EXPECT_LT((solution - dense).cwiseAbs().maxCoeff(), 1e-10 * dense.cwiseAbs().maxCoeff());
}

}  // namespace
