// Short-range contact (pd/contact.hpp): the force on every particle equals the direct sum over every
// other particle that no intact bond joins to it, f = k V_j (d - r) / delta along the pair for
// r < d (Silling 2005, EMU theory manual p. 18; k = 15 c, d = 0.9 spacings, the defaults). The
// contact reads the broken bonds only in the rows that may touch and looks at the rows again as the
// particles move (a Verlet skin); the test moves the particles so that broken pairs come into reach
// long after the rows were first looked at, then moves three particles alone, far from their
// families, each pair they meet counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "cases/homogeneous.hpp"
#include "rift/pd/contact.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/material_constants.hpp"
#include "rift/scene/parse.hpp"

namespace {

using rift::operator-;

// The direct sum over all pairs: j ascending, as the contact adds them, so the sums agree to the
// last bit but for the order of two floating-point operations (1e-12 of the largest force asserted).
template <int D>
std::vector<rift::Vec<D>> all_pairs_contact(const rift::pd::Model<D>& m, double distance, double k) {
  const auto& b = m.bonds;
  std::vector<rift::Vec<D>> force(m.size(), rift::Vec<D>{});
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t j = 0; j < m.size(); ++j) {
      if (j == i) continue;
      const auto first = b.neighbor.begin() + b.offset[i], last = b.neighbor.begin() + b.offset[i + 1];
      const auto at = std::lower_bound(first, last, static_cast<std::int32_t>(j));
      if (at != last && *at == static_cast<std::int32_t>(j) && b.intact[static_cast<std::size_t>(at - b.neighbor.begin())] != rift::pd::bond_broken)
        continue;  // joined by an intact bond
      const rift::Vec<D> eta = m.position[j] - m.position[i];
      const double r = std::sqrt(rift::dot<D>(eta, eta));
      if (r >= distance) continue;
      for (int q = 0; q < D; ++q) force[i][q] += -k * m.volume[j] * (distance - r) / r * eta[q];
    }
  }
  return force;
}

// The largest force of the direct sum, and the largest difference of the contact's from it.
template <int D>
std::pair<double, double> largest_and_difference(const std::vector<rift::Vec<D>>& force, const std::vector<rift::Vec<D>>& expected) {
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < force.size(); ++i) {
    largest = std::max(largest, std::sqrt(rift::dot<D>(expected[i], expected[i])));
    const rift::Vec<D> e = force[i] - expected[i];
    difference = std::max(difference, std::sqrt(rift::dot<D>(e, e)));
  }
  return {largest, difference};
}

template <int D>
void contact_is_the_sum_over_all_unbonded_pairs() {
  const auto s = rift::scene::parse_string(
      rift::validation::box_scene(D, "pmb", 0.25, "", D == 2 ? "max = [0.014, 0.014]" : "max = [0.008, 0.008, 0.008]"), "c.toml");
  auto m = rift::pd::discretize<D>(s);
  const auto& c = m.bodies[0].constants;
  // c of the contact: the constant-influence PMB micromodulus of the body's P-wave modulus (its bulk
  // modulus 5/9 of it in 3D, 2/3 in 2D, where the PMB's Poisson's ratio is 1/4 and 1/3)
  const double kappa = (D == 3 ? 5.0 / 9.0 : 2.0 / 3.0) * c.p_wave_modulus();
  const double spacing = 0.001, distance = 0.9 * spacing,
               k = 15.0 * rift::pd::pmb_micromodulus(D, kappa, c.horizon, c.thickness, rift::scene::Influence::constant) / c.horizon;
  // half the bonds broken at random, each pair both ways
  std::mt19937 rng(11);
  auto& b = m.bonds;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto q = b.offset[i]; q < b.offset[i + 1]; ++q) {
      const auto j = static_cast<std::size_t>(b.neighbor[q]);
      if (j < i || rng() % 2) continue;
      b.intact.set(static_cast<std::size_t>(q), rift::pd::bond_broken);
      const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
      b.intact.set(static_cast<std::size_t>(std::lower_bound(first, last, static_cast<std::int32_t>(i)) - b.neighbor.begin()), rift::pd::bond_broken);
    }
  rift::pd::Contact<D> contact(s.contact, m);
  // a compression wave along x of up to 20% strain and a jitter of 0.03 spacings, grown over the steps
  std::vector<rift::Vec<D>> jitter(m.size());
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (auto& u : jitter)
    for (int q = 0; q < D; ++q) u[q] = 0.03 * spacing * unit(rng);
  const double length = D == 2 ? 0.014 : 0.008, amplitude = 0.2 * length / (2.0 * M_PI);
  const int steps = 120;
  std::size_t touching_most = 0;
  double worst = 0.0;
  for (int step = 1; step <= steps; ++step) {
    const double t = double(step) / steps;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto& x = m.reference_position[i];
      m.position[i] = x;
      m.position[i][0] += t * amplitude * std::sin(2.0 * M_PI * x[0] / length);
      for (int q = 0; q < D; ++q) m.position[i][q] += t * jitter[i][q];
      m.force[i] = rift::Vec<D>{};
    }
    contact.add_forces(m);
    const auto expected = all_pairs_contact<D>(m, distance, k);
    const auto [largest, difference] = largest_and_difference<D>(m.force, expected);
    std::size_t touching = 0;
    for (std::size_t i = 0; i < m.size(); ++i) touching += rift::dot<D>(expected[i], expected[i]) > 0.0;
    touching_most = std::max(touching_most, touching);
    if (largest > 0.0) worst = std::max(worst, difference / largest);
  }
  std::printf("%dD contact: at most %zu of %zu particles touching, largest difference %.2e of the largest force\n", D, touching_most, m.size(),
              worst);
  EXPECT_GT(touching_most, m.size() / 10);  // the wave pressed many broken pairs into reach
  EXPECT_LT(worst, 1e-12);
  // then three particles wander off, 0.15 spacings a step, the others held: every pair they meet
  // counts
  std::vector<std::size_t> wanderers;
  for (std::size_t q = 0; q < 3; ++q) wanderers.push_back((q + 1) * m.size() / 4);
  double worst_wandering = 0.0;
  std::size_t met = 0;
  for (int step = 1; step <= 40; ++step) {
    for (const std::size_t i : wanderers)
      for (int q = 0; q < D; ++q) m.position[i][q] += 0.15 * spacing * unit(rng);
    for (auto& f : m.force) f = rift::Vec<D>{};
    contact.add_forces(m);
    const auto expected = all_pairs_contact<D>(m, distance, k);
    const auto [largest, difference] = largest_and_difference<D>(m.force, expected);
    for (const std::size_t i : wanderers) met += rift::dot<D>(expected[i], expected[i]) > 0.0;
    if (largest > 0.0) worst_wandering = std::max(worst_wandering, difference / largest);
  }
  std::printf("%dD contact, three wandering: %zu of their steps touching, largest difference %.2e of the largest force\n", D, met,
              worst_wandering);
  EXPECT_GT(met, 10u);
  EXPECT_LT(worst_wandering, 1e-12);
  // one of them flung a thousand spacings off, another set half a spacing from the first particle
  // (a corner, outside the body): the grid of cells then far outnumbers the particles, and the list
  // is made by a sort and a search instead of a count (contact.cpp rebuild); still the direct sum
  m.position[wanderers[0]][0] += 1000.0 * spacing;
  m.position[wanderers[1]] = m.position[0];
  m.position[wanderers[1]][0] -= 0.5 * spacing;
  for (auto& f : m.force) f = rift::Vec<D>{};
  contact.add_forces(m);
  {
    const auto expected = all_pairs_contact<D>(m, distance, k);
    const auto [largest, difference] = largest_and_difference<D>(m.force, expected);
    EXPECT_GT(rift::dot<D>(expected[wanderers[1]], expected[wanderers[1]]), 0.0);
    ASSERT_GT(largest, 0.0);
    EXPECT_LT(difference / largest, 1e-12) << "with a particle flung far off";
  }
  // the rows' near bonds as a contact made now finds them (on one rank, by the body's runs): in each
  // row, the places of the bonds of any state shorter than d + s_f, ascending; a row with more than
  // seven is read whole
  rift::pd::Contact<D> fresh(s.contact, m);
  for (auto& f : m.force) f = rift::Vec<D>{};
  fresh.add_forces(m);
  double skin = -1.0;
  std::vector<std::pair<int, std::vector<int>>> found;  // per row: count, places
  auto read = [&](const char* name, auto& member) {
    using T = std::decay_t<decltype(member)>;
    if constexpr (std::is_same_v<T, double>) {
      if (std::string_view(name) == "contact.family_skin") skin = member;
    } else if constexpr (requires { member[0].place; }) {
      for (const auto& near : member) found.emplace_back(near.count, std::vector<int>(near.place.begin(), near.place.begin() + std::min<int>(near.count, 7)));
    }
  };
  fresh.visit_state(read);
  ASSERT_GT(skin, 0.0);
  ASSERT_EQ(found.size(), m.size());
  const double reach = distance + skin;
  std::size_t rows_near = 0, rows_whole = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    std::vector<int> places;
    for (auto q = b.offset[i]; q < b.offset[i + 1]; ++q) {
      const rift::Vec<D> eta = m.position[static_cast<std::size_t>(b.neighbor[q])] - m.position[i];
      if (!(rift::dot<D>(eta, eta) >= reach * reach)) places.push_back(static_cast<int>(q - b.offset[i]));
    }
    if (places.size() > 7) {
      EXPECT_EQ(found[i].first, 255) << "row " << i;
      ++rows_whole;
    } else {
      EXPECT_EQ(found[i].first, static_cast<int>(places.size())) << "row " << i;
      if (found[i].first == static_cast<int>(places.size())) {
        EXPECT_EQ(found[i].second, places) << "row " << i;
      }
      rows_near += !places.empty();
    }
  }
  std::printf("%dD contact: %zu rows with near bonds listed, %zu read whole\n", D, rows_near, rows_whole);
  EXPECT_GT(rows_near, m.size() / 10);
}

TEST(Contact, IsTheSumOverAllUnbondedPairsTwoD) { contact_is_the_sum_over_all_unbonded_pairs<2>(); }
TEST(Contact, IsTheSumOverAllUnbondedPairsThreeD) { contact_is_the_sum_over_all_unbonded_pairs<3>(); }

}  // namespace
