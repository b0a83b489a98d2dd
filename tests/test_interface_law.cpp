// Pre-existing fractures ([[interfaces]], geomech/interface_law.hpp): the bonds across one fail in shear
// by Mohr-Coulomb on the interface traction and in tension past the interface's tensile strength;
// failed, each is a frictional contact. The outcome reader (geomech/interface_outcome.hpp) tells crossed,
// dilated and arrested apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "rift/hf/crack_junction.hpp"
#include "rift/hf/fluid_network.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/stress.hpp"
#include "rift/geomech/interface_stages.hpp"
#include "rift/geomech/interface_outcome.hpp"
#include "rift/scene/parse.hpp"
#include "rock_scene.hpp"

namespace {

using rift::operator-;

constexpr double E = 10e9, nu = 0.25, spacing = 0.001, horizon = 3.015 * spacing, half = 0.02;

/// The model of a scene with its interfaces' force stages, as the run's set-up gives them.
rift::pd::Model<2> discretize_with_interfaces(const rift::scene::Scene& s) {
  auto m = rift::pd::discretize<2>(s);
  rift::geomech::install_interface_stages<2>(m);
  return m;
}

// A 40 x 40 mm plane strain LPS block (rock that does not break), with an interface through its
// middle from `a` to `b` and whatever `extra` adds.
rift::scene::Scene block_with_interface(const std::string& a, const std::string& b, const std::string& law, const std::string& extra = "",
                                        const std::string& rock_critical_stretch = "1.0") {
  const std::string text = rift::test::plane_strain_rock("critical_stretch = " + rock_critical_stretch + "\n") + R"([regions.block]
shape = "box"
min = [-0.02, -0.02]
max = [0.02, 0.02]
[bodies.block]
material = "rock"
region = "block"
spacing = 0.001
horizon = 3.015
[solver]
type = "dynamic_relaxation"
[[interfaces]]
points = [)" + a + ", " + b + "]\n" + law + "\n" + extra;
  return rift::scene::parse_string(text, "interface.toml");
}

// Puts every particle at x = X + eps X (a homogeneous plane strain), evaluates the forces once with
// breaking off (dilatations, hence stresses), then the interface law alone.
void deform_and_apply_law(rift::pd::Model<2>& m, double exx, double eyy) {
  for (std::size_t i = 0; i < m.size(); ++i) {
    m.position[i][0] = m.reference_position[i][0] * (1.0 + exx);
    m.position[i][1] = m.reference_position[i][1] * (1.0 + eyy);
  }
  m.bodies[0].constants.breakable = false;
  rift::pd::compute_forces<2>(m, nullptr, 0.0);
  m.bodies[0].constants.breakable = true;
  rift::geomech::apply_interface_law<2>(m);
}

// Interface bonds with both ends two horizons and a spacing inside the block (whole families for
// them and for their neighbours, whose dilatations enter their stress) that `keep` accepts: how
// many, and how many failed.
template <class Keep>
std::pair<int, int> bulk_interface_bonds(const rift::pd::Model<2>& m, Keep keep) {
  const auto& ib = m.interface_bonds;
  int all = 0, failed = 0;
  auto inside = [&](std::size_t i) {
    const double margin = half - 2.0 * horizon - spacing;
    return std::abs(m.reference_position[i][0]) < margin && std::abs(m.reference_position[i][1]) < margin;
  };
  for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[k]);
      if (!inside(i) || !inside(j) || !keep(m.reference_position[j] - m.reference_position[i])) continue;
      ++all;
      failed += m.bonds.intact[k] == rift::pd::bond_interface_failed;
    }
  return {all, failed};
}

// Mohr-Coulomb slip (the thesis' EQ 4.1-4.2, tau > tau_0 + mu sigma_n). An interface at alpha = 30
// degrees to x under uniaxial compression S along y (plane strain: eps_yy = -S (1 - nu^2) / E,
// eps_xx = S nu (1 + nu) / E) carries sigma_n = S cos^2 alpha and tau = S sin alpha cos alpha, so it
// slips at S* = tau_0 / (cos alpha (sin alpha - mu cos alpha)) = 4.807 MPa for tau_0 = 1 MPa and
// mu = 0.3. In the bulk the bond-pair stress of a homogeneous deformation is the applied one, so
// no bond fails at 0.97 S* and every one fails at 1.03 S*.
TEST(InterfaceLaw, SlipsWhereTheShearTractionReachesCohesionPlusFriction) {
  const double alpha = M_PI / 6.0, tau0 = 1e6, mu = 0.3;
  const double critical = tau0 / (std::cos(alpha) * (std::sin(alpha) - mu * std::cos(alpha)));
  ASSERT_NEAR(critical, 4.807e6, 1e3);
  char a[64], b[64];
  std::snprintf(a, sizeof a, "[%.17g, %.17g]", -0.03 * std::cos(alpha), -0.03 * std::sin(alpha));
  std::snprintf(b, sizeof b, "[%.17g, %.17g]", 0.03 * std::cos(alpha), 0.03 * std::sin(alpha));
  for (double factor : {0.97, 1.03}) {
    auto s = block_with_interface(a, b, "tensile_strength = 1e9\ncohesion = 1e6\nfriction_coefficient = 0.3");
    auto m = discretize_with_interfaces(s);
    const double S = factor * critical;
    deform_and_apply_law(m, S * nu * (1 + nu) / E, -S * (1 - nu * nu) / E);
    const auto [all, failed] = bulk_interface_bonds(m, [](const rift::Vec<2>&) { return true; });
    ASSERT_GT(all, 100);
    EXPECT_EQ(failed, factor < 1.0 ? 0 : all) << "at " << factor << " of the slip load";
  }
}

// The interfaces enter a force evaluation through the model's force stages (pd/force_stages.hpp),
// which the run's set-up installs: a model with interfaces and none is a programming error, not a run
// whose interfaces hold whatever the load (the force evaluation and the bond-pair stress throw).
TEST(InterfaceLaw, AModelWithInterfacesAndNoForceStagesIsRefused) {
  auto m = rift::pd::discretize<2>(block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e6\nfriction_coefficient = 0.89"));
  ASSERT_FALSE(m.interface_bonds.laws.empty());
  EXPECT_THROW(rift::pd::compute_forces<2>(m, nullptr, 0.0), std::logic_error);
  EXPECT_THROW(rift::pd::particle_stress<2>(m), std::logic_error);
  rift::geomech::install_interface_stages<2>(m);
  EXPECT_NO_THROW(rift::pd::compute_forces<2>(m, nullptr, 0.0));
}

// Tension: a horizontal interface under uniaxial tension S across it (plane strain: eps_yy =
// S (1 - nu^2) / E, eps_xx = -S nu (1 + nu) / E) parts where the normal tension passes its strength
// T = 1 MPa: no bulk bond at 0.97 T, every one at 1.03 T (tau = 0 stays below the cohesion). Under
// the same strain's opposite, a compression, nothing parts though bonds along x then stretch.
TEST(InterfaceLaw, PartsWhereTheNormalTensionReachesItsStrength) {
  const double T = 1e6;
  for (double factor : {0.97, 1.03, -1.03}) {
    auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e6\ncohesion = 1e6\nfriction_coefficient = 0.89");
    auto m = discretize_with_interfaces(s);
    const double S = factor * T;
    deform_and_apply_law(m, -S * nu * (1 + nu) / E, S * (1 - nu * nu) / E);
    const auto [all, failed] = bulk_interface_bonds(m, [](const rift::Vec<2>&) { return true; });
    ASSERT_GT(all, 100);
    EXPECT_EQ(failed, factor > 0.0 && factor < 1.0 ? 0 : factor > 1.0 ? all : 0) << "at " << factor << " of the tensile strength";
  }
}

// A failed interface is a frictional contact (geomech/interface_contact.hpp). With the upper half of the
// block moved rigidly by (dx, dy) every bond across has the same jump, so: pulled 1 um apart it
// feels no force; pressed 1 um in, a normal force within 15% of the intact interface's (each bond
// keeps its stiffness along n; the intact LPS adds its Poisson coupling); pressed 1 um and slid
// 0.3 um it sticks (shear / normal = 0.3); slid 3 um it slides at shear / normal = mu = 0.5 exactly.
TEST(InterfaceLaw, FailedInterfaceIsAFrictionalContact) {
  auto force_on_upper_half = [](const rift::pd::Model<2>& m) {
    rift::Vec<2> f{0.0, 0.0};
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.reference_position[i][1] > 0) f[0] += m.force[i][0] * m.volume[i], f[1] += m.force[i][1] * m.volume[i];
    return f;
  };
  auto net_force_on_upper_half = [&](bool failed, double dx, double dy) {
    auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e9\ncohesion = 1e9\nfriction_coefficient = 0.5");
    auto m = discretize_with_interfaces(s);
    if (failed)
      for (auto k : m.interface_bonds.slot) m.bonds.intact.set(static_cast<std::size_t>(k), rift::pd::bond_interface_failed);
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.reference_position[i][1] > 0) m.position[i][0] += dx, m.position[i][1] += dy;
    rift::pd::compute_forces<2>(m, nullptr, 0.0);
    return force_on_upper_half(m);
  };
  EXPECT_LT(net_force_on_upper_half(false, 0.0, 1e-6)[1], -1.0) << "intact: pulled back";
  EXPECT_NEAR(net_force_on_upper_half(true, 0.0, 1e-6)[1], 0.0, 1e-12);
  const double intact = net_force_on_upper_half(false, 0.0, -1e-6)[1];
  const double pressed = net_force_on_upper_half(true, 0.0, -1e-6)[1];
  EXPECT_GT(intact, 1.0);
  EXPECT_NEAR(pressed / intact, 1.0, 0.15);
  const auto stuck = net_force_on_upper_half(true, 0.3e-6, -1e-6);
  EXPECT_NEAR(-stuck[0] / stuck[1], 0.3, 1e-9);
  const auto sliding = net_force_on_upper_half(true, 3e-6, -1e-6);
  EXPECT_NEAR(-sliding[0] / sliding[1], 0.5, 1e-9);
  // a step of explicit dynamics keeps the slip (2.5 um once slid 3 um against the cap mu g = 0.5 um):
  // moved back to 2.5 um the faces carry no shear; dynamic relaxation (history_dt = 0) holds the slip
  auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e9\ncohesion = 1e9\nfriction_coefficient = 0.5");
  auto m = discretize_with_interfaces(s);
  for (auto k : m.interface_bonds.slot) m.bonds.intact.set(static_cast<std::size_t>(k), rift::pd::bond_interface_failed);
  auto place_upper_half = [&](double dx) {
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.reference_position[i][1] > 0) m.position[i][0] = m.reference_position[i][0] + dx, m.position[i][1] = m.reference_position[i][1] - 1e-6;
  };
  place_upper_half(3e-6);
  rift::pd::compute_forces<2>(m, nullptr, 1e-7);
  place_upper_half(2.5e-6);
  rift::pd::compute_forces<2>(m, nullptr, 0.0);
  const auto held = force_on_upper_half(m);
  EXPECT_GT(held[1], 1.0);
  EXPECT_NEAR(held[0] / held[1], 0.0, 1e-9);
}

// The opening of a failed interface's faces leaves out the strain of the rock on either side
// (pd/bulk_strain.hpp, interface_contact.hpp interface_opening). Under the homogeneous strain
// eps_xx = -2e-4, eps_yy = -4e-4, eps_xy = 6.3e-4 (the shear of a 30 degree interface under 13 / 3 MPa),
// the correspondence strain of every particle is eps to round-off (a homogeneous deformation is
// exact on cut families too), so the faces of a failed 30 degree interface do not open anywhere:
// |opening| < 1e-9 of the bond's length. The bonds themselves stretch along n by up to
// eps_nn xi_n + eps_nt xi_t, more than a breaking rock bond's 1e-4 |xi|: read as an opening, that let
// the fluid into interfaces that had only slipped. Lifting the upper half 10 um along y then opens
// each bond's faces by 10 um n_y = 8.66 um (every bond's ends then part: no contact presses them).
TEST(InterfaceLaw, FaceOpeningLeavesOutTheStrainOfTheRock) {
  const double alpha = M_PI / 6.0, exx = -2e-4, eyy = -4e-4, exy = 6.3e-4;
  char a[64], b[64];
  std::snprintf(a, sizeof a, "[%.17g, %.17g]", -0.03 * std::cos(alpha), -0.03 * std::sin(alpha));
  std::snprintf(b, sizeof b, "[%.17g, %.17g]", 0.03 * std::cos(alpha), 0.03 * std::sin(alpha));
  auto s = block_with_interface(a, b, "tensile_strength = 1e9\ncohesion = 1e9\nfriction_coefficient = 0.89");
  auto m = discretize_with_interfaces(s);
  auto& ib = m.interface_bonds;
  for (auto k : ib.slot) m.bonds.intact.set(static_cast<std::size_t>(k), rift::pd::bond_interface_failed);
  auto place = [&](double lift) {
    for (std::size_t i = 0; i < m.size(); ++i) {
      const auto& X = m.reference_position[i];
      const bool upper = X[1] * std::cos(alpha) - X[0] * std::sin(alpha) > 0.0;
      m.position[i][0] = X[0] + exx * X[0] + exy * X[1];
      m.position[i][1] = X[1] + exy * X[0] + eyy * X[1] + (upper ? lift : 0.0);
    }
    rift::geomech::apply_interface_law<2>(m);
  };
  place(0.0);
  ASSERT_EQ(ib.strain.size(), ib.particles.size());
  double worst_strain = 0.0;
  for (const auto& e : ib.strain)
    worst_strain = std::max({worst_strain, std::abs(e[0] - exx), std::abs(e[4] - eyy), std::abs(e[1] - exy), std::abs(e[3] - exy)});
  EXPECT_LT(worst_strain, 1e-12);
  const double n_y = std::cos(alpha);
  for (double lift : {0.0, 1e-5}) {
    if (lift > 0.0) place(lift);
    double worst = 0.0, largest_stretch = 0.0;
    int bonds = 0;
    for (std::size_t r = 0; r < ib.particles.size(); ++r) {
      const auto i = static_cast<std::size_t>(ib.particles[r]);
      for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
        const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
        const auto j = static_cast<std::size_t>(m.bonds.neighbor[k]);
        const auto& law = ib.laws[0];
        const auto jump = rift::geomech::interface_jump<2>(m, i, j, law);
        largest_stretch = std::max(largest_stretch, jump.normal_stretch / m.bonds.length(k));
        worst = std::max(worst, std::abs(rift::geomech::interface_opening<2>(m, i, j, law) - lift * n_y) / m.bonds.length(k));
        ++bonds;
      }
    }
    ASSERT_GT(bonds, 200);
    EXPECT_LT(worst, 1e-9) << "lift " << lift;
    if (lift == 0.0) {
      EXPECT_GT(largest_stretch, 1e-4);
    }
  }
}

// The fluid weakens an interface (p in the law) only where it is inside it: at a particle with a
// failed interface bond whose faces are apart and wet (interface_law.hpp pressure_in_interface).
// A horizontal interface (T = 1 MPa) is pressed by S = 3 MPa across it, and every particle is wet at
// p = 5 MPa, as the broken bonds of a fracture wet every particle within a horizon of it. With
// p - sigma_n = 2 MPa > T the law would part the whole interface if the fluid next to it counted; it
// parts none. Then, on an interface that cannot fail, lifted 10 um and failed over |x| < 3 mm: the
// particles with failed, open bonds hold the fluid's pressure, the wet particles whose interface
// bonds are intact hold none.
TEST(InterfaceLaw, FluidWeakensTheInterfaceOnlyInsideIt) {
  const double S = 3e6, p = 5e6;
  auto wet = [&](rift::pd::Model<2>& m) {
    m.fluid_network.source.assign(m.size(), 0);
    m.fluid_network.pressure.assign(1, p);
  };
  {
    auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e6\ncohesion = 1e6\nfriction_coefficient = 0.89");
    auto m = discretize_with_interfaces(s);
    for (std::size_t i = 0; i < m.size(); ++i) {
      m.position[i][0] = m.reference_position[i][0] * (1.0 + S * nu * (1 + nu) / E);
      m.position[i][1] = m.reference_position[i][1] * (1.0 - S * (1 - nu * nu) / E);
    }
    wet(m);
    rift::geomech::apply_interface_law<2>(m);
    const auto [all, failed] = bulk_interface_bonds(m, [](const rift::Vec<2>&) { return true; });
    ASSERT_GT(all, 100);
    EXPECT_EQ(failed, 0) << "fluid beside an intact interface";
  }
  auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e9\ncohesion = 1e9\nfriction_coefficient = 0.89", "", "1e-3");
  auto m = discretize_with_interfaces(s);
  const auto& ib = m.interface_bonds;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m.reference_position[i][1] > 0.0) m.position[i][1] += 1e-5;
  std::vector<char> has_failed(m.size(), 0);
  for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
      const auto j = static_cast<std::size_t>(m.bonds.neighbor[k]);
      if (std::abs(m.reference_position[i][0]) < 0.003 && std::abs(m.reference_position[j][0]) < 0.003)
        m.bonds.intact.set(k, rift::pd::bond_interface_failed), has_failed[i] = 1;
    }
  wet(m);
  rift::geomech::apply_interface_law<2>(m);  // refreshes the strain the openings are measured against
  int holding = 0, dry = 0;
  for (auto r : ib.particles) {
    const auto i = static_cast<std::size_t>(r);
    const double in = rift::geomech::pressure_in_interface<2>(m, i);
    if (has_failed[i]) {
      EXPECT_EQ(in, p);
      ++holding;
    } else {
      EXPECT_EQ(in, 0.0);
      ++dry;
    }
  }
  EXPECT_GT(holding, 10);
  EXPECT_GT(dry, 100);
}

// The outcome reader. A borehole at (0, -12 mm) below a horizontal interface y = 0 (between lattice
// rows); a crack is made by hand from the borehole up the line x = 0 (rock bonds across it broken):
//   stopped 8 mm below the interface -> not reached; up to it, the interface bonds next to it failed -> arrested;
//   on to y = 10 mm -> crossed (9.5 mm, 3 horizons past the plane; 2 are needed);
//   up to it, the interface bonds failed over |x| < 8 mm, the fluid let in and the upper half lifted
//   10 um (more than the rock's critical stretch 1e-3 times any bond) -> dilated (open and wet along
//   17 mm, more than 3 horizons), and only while the fluid's 1 MPa exceeds the compression the in-situ
//   stresses put across the interface (Warpinski and Teufel's p > sigma_n, the thesis' EQ 4.7):
//   sigma_h = -0.9 MPa across it dilates, -1.1 MPa holds it shut (arrested).
TEST(InterfaceOutcome, CrossedDilatedArrestedFromTheBonds) {
  const std::string hole = R"([regions.hole]
shape = "cylinder"
center = [0.0, -0.012]
radius = 0.0015
[[boreholes]]
region = "hole"
pressure = 1e6
)";
  // wet: whether the fluid reaches the particle at (6.5 mm, 0.5 mm), on the interface 6.5 mm from the crack
  // failed_as: the state of the interface bonds within failed_half_length of the crack
  auto outcome = [&](double crack_top, double failed_half_length, double lift, bool* wet = nullptr, const std::string& in_situ = "",
                     std::uint8_t failed_as = rift::pd::bond_interface_failed) {
    auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e6\nfriction_coefficient = 0.89", hole + in_situ, "1e-3");
    auto m = discretize_with_interfaces(s);
    auto& b = m.bonds;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        const auto &p = m.reference_position[i], &q = m.reference_position[j];
        const double y = 0.5 * (p[1] + q[1]);
        if (p[0] * q[0] < 0 && y > -0.012 && y < crack_top) b.intact.set(k, rift::pd::bond_broken);
      }
    const auto& ib = m.interface_bonds;
    for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
      for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q)
        if (std::abs(m.reference_position[i][0]) < failed_half_length)
          b.intact.set(static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]), failed_as);
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.reference_position[i][1] > 0.0) m.position[i][1] += lift;
    m.fluid_network.pressure.assign(m.fluid_network.dry.size(), 1e6);
    rift::hf::update_fluid_network<2>(m);
    if (wet)
      for (std::size_t i = 0; i < m.size(); ++i)
        if (std::abs(m.reference_position[i][0] - 0.0065) < 1e-6 && std::abs(m.reference_position[i][1] - 0.0005) < 1e-6)
          *wet = m.fluid_network.source[i] >= 0;
    return rift::geomech::classify_interfaces<2>(m).at(0);
  };
  EXPECT_EQ(outcome(-0.008, 0.0, 0.0).name(), "not reached");
  EXPECT_EQ(outcome(0.0, 0.002, 0.0).name(), "arrested");
  const auto crossed = outcome(0.010, 0.002, 0.0);
  EXPECT_EQ(crossed.name(), "crossed");
  EXPECT_NEAR(crossed.crossing_distance, 0.0095, 0.001);
  // a failed but closed interface keeps the fluid out; lifted open, the fluid enters it
  bool wet = true;
  EXPECT_EQ(outcome(0.0, 0.008, 0.0, &wet).name(), "arrested");
  EXPECT_FALSE(wet);
  const auto dilated = outcome(0.0, 0.008, 1e-5, &wet);
  EXPECT_TRUE(wet);
  EXPECT_EQ(dilated.name(), "dilated");
  EXPECT_NEAR(dilated.opened_length, 0.017, 0.0011);  // failed rows |x| <= 7.5 mm, bonds reaching 2 mm on: midpoints to 8.5 mm
  // the same bonds broken as rock (a fracture through the interface breaks them so) are the
  // crossing fracture's: lifted open and wet, they are not the interface's opening
  const auto broken_as_rock = outcome(0.0, 0.008, 1e-5, nullptr, "", rift::pd::bond_broken);
  EXPECT_EQ(broken_as_rock.name(), "arrested");
  EXPECT_DOUBLE_EQ(broken_as_rock.opened_length, 0.0);
  auto in_situ = [](const char* sigma_h) { return std::string("[in_situ_stress]\nsigma_H = -3e6\nsigma_h = ") + sigma_h + "\n"; };
  EXPECT_EQ(outcome(0.0, 0.008, 1e-5, nullptr, in_situ("-0.9e6")).name(), "dilated");
  EXPECT_EQ(outcome(0.0, 0.008, 1e-5, nullptr, in_situ("-1.1e6")).name(), "arrested");
}

}  // namespace

namespace {

// Breakthrough is kept (pd/fluid_network.hpp broke_through): the block of the outcome test above
// with its interface failed along its whole length, from face to face, and the upper half lifted
// 10 um lets the borehole's fluid reach the outer surface (vented); shut again (the fluid at zero
// pressure, the faces pressed back), the interface keeps the fluid out and the network no longer
// vents, but the breakthrough that ends a laboratory test stays recorded.
TEST(InterfaceOutcome, BreakthroughThroughAnInterfaceIsKeptWhenItShuts) {
  const std::string hole = "[regions.hole]\nshape = \"cylinder\"\ncenter = [0.0, -0.012]\nradius = 0.0015\n"
                           "[[boreholes]]\nregion = \"hole\"\npressure = 1e6\n";
  auto s = block_with_interface("[-0.03, 0.0]", "[0.03, 0.0]", "tensile_strength = 1e6\nfriction_coefficient = 0.89", hole, "1e-3");
  auto m = discretize_with_interfaces(s);
  auto& b = m.bonds;
  for (std::size_t i = 0; i < m.size(); ++i)  // the crack from the borehole up to the interface
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const auto &p = m.reference_position[i], &q = m.reference_position[j];
      if (p[0] * q[0] < 0 && 0.5 * (p[1] + q[1]) > -0.012 && 0.5 * (p[1] + q[1]) < 0.0) b.intact.set(k, rift::pd::bond_broken);
    }
  const auto& ib = m.interface_bonds;
  for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q)
      b.intact.set(static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]), rift::pd::bond_interface_failed);
  m.fluid_network.pressure.assign(m.fluid_network.dry.size(), 1e6);
  const std::size_t source = s.cracks.size();  // the borehole
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m.reference_position[i][1] > 0.0) m.position[i][1] += 1e-5;
  rift::hf::update_fluid_network<2>(m);
  EXPECT_TRUE(m.fluid_network.vented.at(source));
  EXPECT_TRUE(m.fluid_network.broke_through.at(source));
  m.position = m.reference_position;
  rift::hf::update_fluid_network<2>(m);
  EXPECT_FALSE(m.fluid_network.vented.at(source));
  EXPECT_TRUE(m.fluid_network.broke_through.at(source));
}

}  // namespace

namespace {

// The record a run keeps (geomech/interface_outcome.hpp record_outcomes), as Zhou et al.'s cut blocks
// kept the fluid's path: an interface dilated at one load step and shut at the next reads dilated,
// crossing stays, and the lengths are the largest seen.
TEST(InterfaceOutcome, DilationIsKeptWhenTheInterfaceShuts) {
  rift::geomech::InterfaceOutcome open_and_wet, shut;
  open_and_wet.reached = open_and_wet.dilated = true;
  open_and_wet.opened_length = 0.025;
  shut.reached = true;
  shut.crossing_distance = 0.004;
  std::vector<rift::geomech::InterfaceOutcome> record;
  rift::geomech::record_outcomes(record, {shut});
  EXPECT_EQ(record.at(0).name(), "arrested");
  rift::geomech::record_outcomes(record, {open_and_wet});
  rift::geomech::record_outcomes(record, {shut});
  EXPECT_EQ(record.at(0).name(), "dilated");
  EXPECT_DOUBLE_EQ(record.at(0).opened_length, 0.025);
  EXPECT_DOUBLE_EQ(record.at(0).crossing_distance, 0.004);
  rift::geomech::InterfaceOutcome crossed = shut;
  crossed.crossed = true;
  crossed.crossing_distance = 0.02;
  rift::geomech::record_outcomes(record, {crossed});
  rift::geomech::record_outcomes(record, {shut});
  EXPECT_EQ(record.at(0).name(), "crossed+dilated");
  EXPECT_DOUBLE_EQ(record.at(0).crossing_distance, 0.02);
}

}  // namespace

namespace {

// An interface through a row of lattice sites (geometry/precrack.cpp): the row counts with the side
// to the line's left, so the interface cuts the bonds from the row to the other side, exactly the
// bonds a line a hair below the row cuts. (Counted on neither side, the row's bonds all stayed
// rock and bridged the interface: Zhou's 90-degree interfaces at 3 mm spacing, hf_zhou_crossing.)
TEST(InterfaceLaw, AnInterfaceThroughARowOfSitesCutsTheRowFromOneSide) {
  // sites at (i + 1/2, j + 1/2) mm: the row y = 0.5 mm lies on the first line
  auto on_row = discretize_with_interfaces(block_with_interface("[-0.02, 0.0005]", "[0.02, 0.0005]", "tensile_strength = 1e6\nfriction_coefficient = 0.89"));
  auto below = discretize_with_interfaces(block_with_interface("[-0.02, 0.0004999]", "[0.02, 0.0004999]", "tensile_strength = 1e6\nfriction_coefficient = 0.89"));
  ASSERT_FALSE(on_row.interface_bonds.empty());
  EXPECT_EQ(on_row.interface_bonds.slot, below.interface_bonds.slot);
  // every bond from the row (y = 0.5 mm) down across the line, and none from it up
  std::size_t down = 0, up = 0;
  const auto& ib = on_row.interface_bonds;
  for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto j = static_cast<std::size_t>(on_row.bonds.neighbor[static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)])]);
      if (std::abs(on_row.reference_position[i][1] - 0.0005) > 1e-9) continue;
      down += on_row.reference_position[j][1] < 0.0005;
      up += on_row.reference_position[j][1] > 0.0005;
    }
  EXPECT_GT(down, 0u);
  EXPECT_EQ(up, 0u);
}

// The junction (pd/crack_junction.hpp): a fluid-filled crack along y = 0 from a borehole to a
// 90-degree interface at x = 0 (between two columns), every interface bond failed, the block
// pressed across the interface and the crack's upper face lifted by w. A failed interface bond
// whose path crosses the crack itself (at x <= 0, the last patch's half spacing) joins the two
// faces the fluid holds apart: marked, and no contact force. The other failed bonds are frictional
// contacts, pressed and slid by w where they join the lifted face to the far side: they push.
TEST(InterfaceLaw, FailedInterfaceBondsAcrossTheFluidsCrackCarryNoContact) {
  const std::string hole = "[regions.hole]\nshape = \"cylinder\"\ncenter = [-0.012, 0.0]\nradius = 0.0015\n"
                           "[[boreholes]]\nregion = \"hole\"\npressure = 1e6\n";
  auto s = block_with_interface("[0.0, -0.02]", "[0.0, 0.02]", "tensile_strength = 1e6\nfriction_coefficient = 0.89", hole);
  auto m = discretize_with_interfaces(s);
  auto& b = m.bonds;
  const auto& ib = m.interface_bonds;
  ASSERT_FALSE(ib.empty());
  for (std::size_t i = 0; i < m.size(); ++i)  // the crack: rock bonds across y = 0 up to the interface
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto &p = m.reference_position[i], &q = m.reference_position[static_cast<std::size_t>(b.neighbor[k])];
      if (p[1] * q[1] < 0 && p[0] < 0 && q[0] < 0 && p[0] > -0.012 && q[0] > -0.012) b.intact.set(k, rift::pd::bond_broken);
    }
  for (auto k : ib.slot) b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_interface_failed);
  m.fluid_network.pressure.assign(m.fluid_network.dry.size(), 1e6);
  rift::hf::update_fluid_network<2>(m);  // the crack's surface, and the marks
  const double w = 10e-6;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& X = m.reference_position[i];
    m.position[i] = {X[0] * (1.0 - 1e-3), X[1]};  // pressed across the interface
    if (X[0] < 0.0 && X[1] > 0.0) m.position[i][1] += w;  // the crack's upper face, lifted
  }
  int across = 0, pushing = 0;
  for (std::size_t i = 0; i + 1 < ib.offset.size(); ++i)
    for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
      const auto k = ib.slot[static_cast<std::size_t>(q)];
      const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
      const auto &p = m.reference_position[i], &r = m.reference_position[j];
      // where the bond's path crosses y = 0, if it does
      const bool crosses_line = p[1] * r[1] < 0.0;
      const double x_at_line = crosses_line ? p[0] + (r[0] - p[0]) * p[1] / (p[1] - r[1]) : 1.0;
      const bool expected = crosses_line && x_at_line <= 1e-9 && x_at_line > -0.0115;
      EXPECT_EQ(rift::geomech::across_crack(ib, q), expected) << p[0] << "," << p[1] << " - " << r[0] << "," << r[1];
      const auto f = rift::geomech::interface_contact_force<2>(m, i, j, k, static_cast<std::size_t>(q), nullptr);
      const double force = std::hypot(f[0], f[1]);
      if (expected) {
        ++across;
        EXPECT_EQ(force, 0.0);
      } else if ((p[0] < 0.0 && p[1] > 0.0) != (r[0] < 0.0 && r[1] > 0.0) && std::abs(p[1]) < 0.005 && std::abs(r[1]) < 0.005) {
        pushing += force > 0.0;
      }
    }
  EXPECT_GE(across, 6);  // horizon 3 spacings: 1 + 2 + 3 bonds each way down from each face row
  EXPECT_GT(pushing, 0);
}

}  // namespace
