// The fluid's load on the rock around the cracks it fills (pd/network_load.hpp) is defined by two
// force evaluations under a uniform expansion, F with the bonds as they are and F^s with the
// network's broken bonds held intact: g_s,i = (F_i - F^s_i) / (eps d kappa_i). rift evaluates the
// difference itself on the particles within reach of the network alone, under a unit expansion
// (every model is linear in it), or without the surface correction by the runs of bonds over the
// whole body (hf/network_load_runs.hpp); here g is made from the definition with the model's own passes over
// the whole body (pmb.hpp, lps.hpp: what hf/network_load.hpp did before), from the positions of the
// expansion eps = 0.5, on a 2D and a 3D block whose crack grew from a pressurized pre-crack, PMB, LPS
// with and without the surface correction and VES (by its LPS response). Tolerance 1e-12 of the
// largest |g|: the same formulas summed in another order, the rounding of the extensions
// |y| - |xi| magnified by 1/eps (at eps = 1e-6 the passes' g was 5e-10 from the exact one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rift/hf/fluid_network.hpp"
#include "rift/hf/network_load.hpp"
#include "rift/hf/crack_surface.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/scene/parse.hpp"

namespace {

std::string grown_crack_scene(int dim, const std::string& material) {
  std::ostringstream s;
  s << "[scene]\ndimension = " << dim << "\n" << (dim == 2 ? "plane = \"strain\"\nthickness = 0.001\n" : "")
    << "[materials.rock]\ndensity = 2500.0\nyoungs_modulus = 10e9\npoisson_ratio = 0.25\n" << material
    << "[regions.block]\nshape = \"box\"\nmin = [0.0, 0.0" << (dim == 3 ? ", 0.0]" : "]") << "\nmax = [0.024, 0.016"
    << (dim == 3 ? ", 0.008]" : "]") << "\n[bodies.block]\nmaterial = \"rock\"\nregion = \"block\"\nspacing = 0.001\nhorizon = 3.015\n"
    << "lattice_origin = [0.0, 0.0" << (dim == 3 ? ", 0.0]" : "]") << "\n[[cracks]]\n"
    << (dim == 3 ? "points = [[-0.01, 0.008, -0.01], [0.012, 0.008, -0.01], [0.012, 0.008, 0.02], [-0.01, 0.008, 0.02]]\n"
                 : "points = [[-0.01, 0.008], [0.012, 0.008]]\n")
    << "pressure = 2e6\n[solver]\nend_time = 1e-6\n";
  return s.str();
}

// g by the definition, with the passes over the whole model
template <int D>
std::vector<double> load_by_passes(rift::pd::Model<D>& m, const std::vector<std::int64_t>& network) {
  using I = rift::scene::Influence;
  const double eps = 0.5;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int q = 0; q < D; ++q) m.position[i][q] = (1.0 + eps) * m.reference_position[i][q];
  auto forces = [&] {
    const rift::pd::HeldBreaking<D> held(m);
    for (const auto& body : m.bodies) {
      const I omega = body.constants.influence;
      if (body.constants.model == rift::scene::ModelKind::pmb) {
        if (omega == I::constant) rift::pd::pmb_forces<D, I::constant>(m, body);
        else rift::pd::pmb_forces<D, I::inverse_distance>(m, body);
      } else if (omega == I::constant) {
        rift::pd::lps_dilatation<D, I::constant>(m, body), rift::pd::state_based_forces<D, I::constant, false>(m, body);
      } else {
        rift::pd::lps_dilatation<D, I::inverse_distance>(m, body), rift::pd::state_based_forces<D, I::inverse_distance, false>(m, body);
      }
    }
    return m.force;
  };
  const auto cracked = forces();
  const auto states = m.bonds.intact;
  for (const auto k : network) m.bonds.intact.set(static_cast<std::size_t>(k), rift::pd::bond_intact);
  const auto whole = forces();
  m.bonds.intact = states;
  std::vector<double> g(m.size() * D, 0.0);
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int q = 0; q < D; ++q)
      g[i * D + static_cast<std::size_t>(q)] = (cracked[i][q] - whole[i][q]) / (eps * D * m.constants_of(i).kappa);
  return g;
}

// Breaks the bonds across y = 8 mm that cross it at x in [from, to).
template <int D>
void grow_crack(rift::pd::Model<D>& m, double from, double to) {
  auto& b = m.bonds;
  const double line = 0.008;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto& xi = m.reference_position[i];
      const auto& xj = m.reference_position[static_cast<std::size_t>(b.neighbor[k])];
      if ((xi[1] - line) * (xj[1] - line) >= 0.0) continue;
      const double crossing = xi[0] + (line - xi[1]) * (xj[0] - xi[0]) / (xj[1] - xi[1]);
      if (crossing >= from && crossing < to) b.intact.set(k, rift::pd::bond_broken);
    }
}

template <int D>
void check(const std::string& material) {
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, material), "grown.toml"));
  // the crack grown along y = 8 mm beyond the pre-crack's end, to x = 20 mm
  grow_crack<D>(m, 0.012, 0.020);
  auto& b = m.bonds;
  rift::hf::update_fluid_network<D>(m);
  const auto network = rift::hf::network_bond_list<D>(m, 0);
  ASSERT_GT(network.size(), 20u);
  const auto state = b.intact;
  // without the surface correction g is made by the runs (hf/network_load_runs.hpp), else by the rows
  EXPECT_EQ(rift::hf::detail::load_by_runs<D>(m), material.find("surface_correction = false") != std::string::npos);
  rift::hf::update_network_load<D>(m);
  ASSERT_EQ(b.intact, state);  // the model as it was
  const auto local = m.fluid_network.network_load.at(0);
  const auto reference = load_by_passes<D>(m, network);
  double largest = 0.0, worst = 0.0;
  for (const double v : reference) largest = std::max(largest, std::abs(v));
  for (std::size_t q = 0; q < local.size(); ++q) worst = std::max(worst, std::abs(local[q] - reference[q]));
  std::string name = material;
  std::replace(name.begin(), name.end(), '\n', ' ');
  std::printf("%dD %s: %zu network bonds, largest |g| %.4g 1/m, largest difference %.2e of it\n", D, name.c_str(), network.size(),
              largest, worst / largest);
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(worst, 1e-12 * largest);
}

// The largest difference between two network loads, over the largest |g| of the second.
double load_difference(const std::vector<double>& incremental, const std::vector<double>& scratch) {
  double worst = 0.0, largest = 0.0;
  for (std::size_t q = 0; q < scratch.size(); ++q)
    worst = std::max(worst, std::abs(incremental[q] - scratch[q])), largest = std::max(largest, std::abs(scratch[q]));
  return largest > 0.0 ? worst / largest : worst;
}

// update_network_load evaluates g again only where the network or a bond's state changed since its
// last call (hf/network_load.hpp): on those particles by the sum made from scratch, on their neighbours
// by the change of the changed ends' terms. After the crack grew in two stages, with a dry bond
// broken near it in between (a state change outside the network), g is the one made from scratch
// within 1e-13 of its largest entry (the corrections' rounding: a few 1e-16 each).
template <int D>
void check_incremental(const std::string& material) {
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, material), "grown.toml"));
  grow_crack<D>(m, 0.012, 0.016);
  rift::hf::update_fluid_network<D>(m);
  rift::hf::update_network_load<D>(m);
  // a bond between two particles a few rows above the crack, dry: its own state change
  auto& b = m.bonds;
  std::size_t above = 0;
  double best = 1e9;
  for (std::size_t i = 0; i < m.size(); ++i) {
    double d = std::abs(m.reference_position[i][0] - 0.014) + std::abs(m.reference_position[i][1] - 0.0115);
    for (int q = 2; q < D; ++q) d += std::abs(m.reference_position[i][q] - 0.0035);
    if (d < best) best = d, above = i;
  }
  b.intact.set(static_cast<std::size_t>(b.offset[above]), rift::pd::bond_broken);
  grow_crack<D>(m, 0.016, 0.020);
  rift::hf::update_fluid_network<D>(m);
  rift::hf::update_network_load<D>(m);
  const auto incremental = m.fluid_network.network_load.at(0);
  auto& f = m.fluid_network;
  rift::hf::forget_network_load(f);
  rift::hf::update_network_load<D>(m);
  const auto& scratch = f.network_load.at(0);
  ASSERT_EQ(incremental.size(), scratch.size());
  std::size_t nonzero = 0;
  for (std::size_t q = 0; q < scratch.size(); ++q) nonzero += scratch[q] != 0.0;
  const double difference = load_difference(incremental, scratch);
  std::printf("%dD: %zu of %zu entries of g nonzero, largest difference %.2e of the largest\n", D, nonzero, scratch.size(), difference);
  EXPECT_GT(nonzero, 0u);
  EXPECT_LT(difference, 1e-13);
  // by the runs (no surface correction) the blocks made again are the whole pass's bits
  if (rift::hf::detail::load_by_runs<D>(m)) {
    EXPECT_EQ(incremental, scratch);
  }
}

// While a network only grows (bonds break, no failed interface, one fluid), update_fluid_network
// goes on from the particles whose bonds broke (hf/fluid_network.hpp): the labels, the immersed
// fragments, the crack surface (hf/crack_surface.hpp) and the network load follow from what changed.
// After the crack grew further, with a flake cut loose at its face and bonds broken beside it, they
// equal those made from scratch, bit for bit (the network load within 1e-13 of its largest entry,
// check_incremental).
template <int D>
void check_growth(const std::string& material) {
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, material), "grown.toml"));
  auto& b = m.bonds;
  auto grow_across = [&](double from, double to) {  // breaks them as crossing breaks (lps.hpp)
    const auto before = b.intact;
    grow_crack<D>(m, from, to);
    std::vector<std::pair<std::size_t, std::int64_t>> crossed;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
        if (before[static_cast<std::size_t>(k)] != b.intact[static_cast<std::size_t>(k)] && static_cast<std::size_t>(b.neighbor[k]) > i)
          crossed.emplace_back(i, k);
    rift::hf::record_crossing_breaks<D>(m, crossed);
  };
  grow_across(0.012, 0.016);
  rift::hf::update_fluid_network<D>(m);
  rift::hf::update_network_load<D>(m);
  const std::size_t patches = m.fluid_network.crack_surface.planes.size();
  grow_across(0.016, 0.020);
  // a flake: every bond of the particle just above the crack at x = 17 mm; and a bond a row higher
  auto nearest = [&](double x, double y) {
    std::size_t best = 0;
    double distance = 1e9;
    for (std::size_t i = 0; i < m.size(); ++i) {
      double d = std::abs(m.reference_position[i][0] - x) + std::abs(m.reference_position[i][1] - y);
      for (int q = 2; q < D; ++q) d += std::abs(m.reference_position[i][q] - 0.0035);
      if (d < distance) distance = d, best = i;
    }
    return best;
  };
  const std::size_t flake = nearest(0.017, 0.0085);
  for (auto k = b.offset[flake]; k < b.offset[flake + 1]; ++k) {
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
    for (auto r = b.offset[j]; r < b.offset[j + 1]; ++r)
      if (static_cast<std::size_t>(b.neighbor[r]) == flake) b.intact.set(static_cast<std::size_t>(r), rift::pd::bond_broken);
  }
  const std::size_t beside = nearest(0.014, 0.0095);
  b.intact.set(static_cast<std::size_t>(b.offset[beside]), rift::pd::bond_broken);
  auto& f = m.fluid_network;
  ASSERT_TRUE(rift::hf::fluid_network_grows(f, 0));
  rift::hf::update_fluid_network<D>(m);
  rift::hf::update_network_load<D>(m);
  ASSERT_TRUE(f.immersed[flake]);
  ASSERT_GT(f.crack_surface.planes.size(), patches);  // the crack's surface grew too
  auto scratch = m;
  auto& s = scratch.fluid_network;
  s.relabel = true;
  s.crack_surface = {};
  s.crack_surface.made = true;
  rift::hf::forget_network_load(s);
  rift::hf::update_fluid_network<D>(scratch);
  rift::hf::update_network_load<D>(scratch);
  EXPECT_EQ(f.source, s.source);
  EXPECT_EQ(f.in_crack, s.in_crack);
  EXPECT_EQ(f.immersed, s.immersed);
  EXPECT_EQ(f.has_network, s.has_network);
  ASSERT_EQ(f.network_load.size(), s.network_load.size());
  for (std::size_t q = 0; q < s.network_load.size(); ++q) {
    ASSERT_EQ(f.network_load[q].size(), s.network_load[q].size());
    EXPECT_LT(load_difference(f.network_load[q], s.network_load[q]), 1e-13);
  }
  // the same patches, each with the same plane
  auto planes_by_bond = [](const rift::pd::CrackSurface& c) {
    std::vector<std::pair<std::int64_t, std::array<double, 6>>> out;
    for (std::size_t p = 0; p < c.patches.size(); ++p) out.emplace_back(c.patches[p], c.planes[p]);
    std::sort(out.begin(), out.end());
    return out;
  };
  {
    const auto a = planes_by_bond(f.crack_surface), z = planes_by_bond(s.crack_surface);
    std::size_t differing = 0;
    for (std::size_t q = 0; q < std::min(a.size(), z.size()); ++q)
      if (a[q] != z[q]) {
        if (differing++ < 3) {
          std::printf("patch %ld: grown", static_cast<long>(a[q].first));
          for (double v : a[q].second) std::printf(" %.17g", v);
          std::printf(" | from scratch");
          for (double v : z[q].second) std::printf(" %.17g", v);
          std::printf("\n");
        }
      }
    EXPECT_EQ(a.size(), z.size());
    EXPECT_EQ(differing, 0u) << "patches whose plane differs from the surface made from scratch";
  }
  EXPECT_EQ(f.crack_surface.sorted_patches, s.crack_surface.sorted_patches);
  std::printf("%dD: %zu wet particles, %zu patches (%zu before the crack grew), %ld immersed\n", D,
              static_cast<std::size_t>(std::count_if(f.source.begin(), f.source.end(), [](int x) { return x >= 0; })),
              f.crack_surface.planes.size(), patches, static_cast<long>(std::count(f.immersed.begin(), f.immersed.end(), 1)));
}

TEST(FluidNetwork, UpdatesWhileItGrowsEqualTheNetworkMadeFromScratch) {
  for (const char* material : {"model = \"lps\"\n", "model = \"ves\"\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\n"}) {
    check_growth<2>(material);
    check_growth<3>(material);
  }
}

// The peeling of the fragments (hf/fluid_network.hpp peel_fragments) stops reading a row once a part
// of its shape tensor passes the test at the whole row's bound. Against the definition: after
// bonds near the crack broke at random (94% of them, both directions), every wet particle left
// not immersed has intact bonds to particles not immersed whose sum n n^T passes
// |det S| > 1e-6 (tr S / d)^d over the whole row, and every one peeled fails it (or lies in a
// closed piece, or was held only by such particles).
template <int D>
void check_peeling() {
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, "model = \"lps\"\n"), "grown.toml"));
  grow_crack<D>(m, 0.012, 0.020);
  rift::hf::update_fluid_network<D>(m);
  auto& b = m.bonds;
  std::mt19937_64 engine(12345);  // a fixed sequence (the standard's engine)
  auto coin = [&] { return engine() % 100 < 94; };
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (std::abs(m.reference_position[i][1] - 0.008) > 0.003) continue;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (j < i || !coin()) continue;
      b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
      for (auto r = b.offset[j]; r < b.offset[j + 1]; ++r)
        if (static_cast<std::size_t>(b.neighbor[r]) == i) b.intact.set(static_cast<std::size_t>(r), rift::pd::bond_broken);
    }
  }
  rift::hf::mark_immersed_fragments<D>(m);
  const auto& f = m.fluid_network;
  auto spans = [&](std::size_t i) {  // the definition, over the whole row
    Eigen::Matrix<double, D, D> shape = Eigen::Matrix<double, D, D>::Zero();
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (b.intact[static_cast<std::size_t>(k)] != rift::pd::bond_intact || f.immersed[j]) continue;
      Eigen::Matrix<double, D, 1> n;
      for (int q = 0; q < D; ++q) n[q] = m.reference_position[j][q] - m.reference_position[i][q];
      n.normalize();
      shape += n * n.transpose();
    }
    return std::abs(shape.determinant()) > 1e-6 * std::pow(shape.trace() / D, D);
  };
  long wet = 0, peeled = 0, left = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (f.source[i] < 0) continue;
    ++wet;
    if (f.immersed[i]) {
      peeled += spans(i) ? 0 : 1;
    } else {
      ++left;
      EXPECT_TRUE(spans(i)) << "particle " << i << " is left though its bonds do not span " << D << " dimensions";
    }
  }
  std::printf("%dD: %ld wet particles, %ld left, %ld immersed that fail the test\n", D, wet, left, peeled);
  EXPECT_GT(left, 0);
  EXPECT_GT(peeled, 0);
}

TEST(FluidNetwork, PeeledFragmentsFollowTheSpanningTestOverWholeRows) {
  check_peeling<2>();
  check_peeling<3>();
}

// Without the surface correction and interface laws, the ends' sums of the network load are made
// without a branch on a bond's state (hf/network_load.hpp uncorrected_network_end): the same bits as
// the rows' form (network_end) at every particle, an end or not, after the crack grew and bonds
// around it broke at random.
template <int D>
void check_uncorrected_ends(const std::string& material) {
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, material), "grown.toml"));
  grow_crack<D>(m, 0.012, 0.020);
  auto& b = m.bonds;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
      if ((i * 7 + static_cast<std::size_t>(k)) % 5 == 0 && std::abs(m.reference_position[i][1] - 0.008) < 0.002)
        b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
  rift::hf::update_fluid_network<D>(m);
  ASSERT_TRUE(rift::hf::detail::load_by_runs<D>(m));
  const auto terms = rift::hf::detail::family_terms<D>(m);
  const auto& f = m.fluid_network;
  long ends = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    bool row_end = false, end = false;
    auto z = rift::hf::detail::network_end<D>(
        m, i, true, [&](std::size_t p, std::int64_t k) { return rift::hf::network_of_bond(f, b, p, k) == 0; }, row_end);
    if (!row_end) z = {};
    const auto u = rift::hf::detail::uncorrected_network_end<D>(m, i, 0, terms, end);
    ASSERT_EQ(end, row_end) << "particle " << i;
    EXPECT_EQ(u.theta, z.theta);
    EXPECT_EQ(u.d_theta, z.d_theta);
    EXPECT_EQ(u.held, z.held);
    EXPECT_EQ(u.change, z.change);
    if (end) {
      EXPECT_EQ(u.a, z.a);
    }
    ends += end;
  }
  EXPECT_GT(ends, 20);
}

// The bonds that broke across the crack are recorded step by step (hf/crack_surface.hpp
// record_crossing_breaks): the latest kept apart, in a short list merged into the whole one once it
// is a 32nd of its length. Over 60 steps of a crack grown across y = 8 mm a sixtieth of its length
// at a time, every recorded bond's both entries (the reverse found by bond_slabs.hpp reverse_bond)
// read as crossed and no other entry does, the two lists together are the sorted list of them all,
// and the short list has been merged in along the way.
TEST(FluidNetwork, CrossingBreaksRecordedStepByStepAreTheWholeSortedList) {
  constexpr int D = 2;
  auto m = rift::pd::discretize<D>(rift::scene::parse_string(grown_crack_scene(D, "model = \"lps\"\n"), "grown.toml"));
  auto& b = m.bonds;
  const auto& f = m.fluid_network;
  std::vector<std::int64_t> expected;
  std::size_t merged = 0, kept_apart = 0;
  for (int step = 0; step < 60; ++step) {
    const auto before = b.intact;
    grow_crack<D>(m, 0.012 + 0.0002 * step, 0.012 + 0.0002 * (step + 1));
    std::vector<std::pair<std::size_t, std::int64_t>> crossed;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
        if (before[static_cast<std::size_t>(k)] != b.intact[static_cast<std::size_t>(k)] && static_cast<std::size_t>(b.neighbor[k]) > i) {
          crossed.emplace_back(i, k);
          expected.push_back(k), expected.push_back(rift::pd::reverse_bond(b, m.bodies[0], i, k));
        }
    rift::hf::record_crossing_breaks<D>(m, crossed);
    merged += !crossed.empty() && f.crossing_recent.empty();
    kept_apart += !f.crossing_recent.empty();
  }
  std::sort(expected.begin(), expected.end());
  ASSERT_GT(expected.size(), 100u);
  EXPECT_EQ(f.crossing_broken_whole(), expected);
  std::size_t wrong = 0;
  for (std::int64_t k = 0; k < b.size(); ++k)
    wrong += f.crossed_when_broken(k) != std::binary_search(expected.begin(), expected.end(), k);
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(merged, 1u);
  EXPECT_GT(kept_apart, 0u);
  EXPECT_LE(f.crossing_recent.size(), f.crossing_broken.size() / 32 + 1);
  m.fluid_network.settle_crossing_broken();
  EXPECT_EQ(f.crossing_broken, expected);
  EXPECT_TRUE(f.crossing_recent.empty());
}

TEST(NetworkLoad, EndsWithoutTheCorrectionEqualTheRowsSums) {
  for (const char* material : {"model = \"lps\"\nsurface_correction = false\n",
                               "model = \"ves\"\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\nsurface_correction = false\n"}) {
    check_uncorrected_ends<2>(material);
    check_uncorrected_ends<3>(material);
  }
}

TEST(NetworkLoad, IncrementalUpdateEqualsTheLoadMadeFromScratch) {
  for (const char* material : {"model = \"pmb\"\n", "model = \"lps\"\n", "model = \"ves\"\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\n",
                               "model = \"lps\"\nsurface_correction = false\n"}) {
    check_incremental<2>(material);
    check_incremental<3>(material);
  }
}

TEST(NetworkLoad, LocalEvaluationEqualsTheDefinitionOverTheWholeBody) {
  for (const char* material : {"model = \"pmb\"\n", "model = \"lps\"\n", "model = \"lps\"\nsurface_correction = false\n",
                               "model = \"ves\"\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\n",
                               "model = \"ves\"\nviscous_fraction = 0.5\nrelaxation_time = 1e-4\nsurface_correction = false\n"}) {
    check<2>(material);
    check<3>(material);
  }
}

}  // namespace
