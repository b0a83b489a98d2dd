// Runs of bonds (pd/bond_runs.hpp) and the PMB pass that takes them in vectors (pd/pmb.hpp):
// (1) every forward bond belongs to exactly one run, and a run's bonds are what it says (3D block
//     with a borehole through it, 2D plate with a round hole and a crack);
// (2) forces, broken bonds and smallest stretches of the pass equal a straightforward evaluation of
//     Silling and Askari (2005) eq. 15-16 and 23 row by row (f = c omega s (g_i + g_j)/2 V_j along the
//     deformed bond; breaks where s > min(s0_i, s0_j)), with bonds already broken, bonds that break in
//     the pass, and the surface correction on; tolerance 1e-12 of the largest force (the sums are
//     made in another order; measured about 1e-16);
// (3) the same for the LPS passes (dilatation and forces) against Silling et al. (2007);
// (4) the SSE2, AVX2 and AVX-512 clones of the run kernels give the same bits (core/vector_isa.hpp),
//     PMB, LPS and VES (its history too);
// (5) a distributed run's window (pd/window.hpp) visits its rows in the passes that go row by row
//     (bond_slabs.hpp for_each_row_by_slabs) each once, in the one-rank run's order, and a window of
//     several ranges of the numbering gives its owned particles the whole model's PMB forces;
// (6) the strain energy densities in runs (pd/energy_runs.hpp) equal the row forms, and under a
//     uniform dilatation eps the state-based W of a particle whose family is whole is the continuum's
//     K (3 eps)^2 / 2;
// (7) the slabs' schedule (bond_slabs.hpp for_each_slab) on a team: no slab runs beside its
//     neighbours, each odd slab after its two even ones, and the passes' forces, bond states and VES
//     histories the same bits on one, two and four threads;
// (8) the rows of bond states kept with the bonds from pass to pass (bond_runs.hpp whole_rows,
//     pd/bond_states.hpp): over passes that break bonds and a change by hand between them, forces,
//     states and VES histories the same bits as passes that make every row afresh, and the kept rows
//     current after each pass without being made again, giving the fluid's counts of each row's
//     intact and broken bonds (hf/fluid_network.hpp count_bond_states) without its states;
// (9) the one-loop form of a PMB run whose upper ends are lower ends further on adds each bond to
//     its ends in the bonds' order, the bits of the bonds taken one at a time, on every clone.
// (10) a history row's damage (forces.hpp summarize_and_update_damage) from the kept rows' bits
//     equals Silling and Askari's (2005) eq. 25 summed over each row's bond states in the row's
//     order, to the bit, and so does its count of broken bonds.
// (11) the VES force kernel's skipping of spans of broken bonds gives the bits of every bond taken.
// (12) the slabs: no row's forward bonds past the next slab, and the last slab as heavy as the others.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <utility>

#include "rift/core/vector_isa.hpp"
#include "rift/hf/fluid_network.hpp"
#include "rift/pd/bond_runs.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/pmb.hpp"
#include "rift/pd/ves.hpp"
#include "rift/pd/window.hpp"
#include "rift/scene/parse.hpp"

namespace {

std::string block_scene(int dimension, bool surface_correction, const char* model = "pmb") {
  std::ostringstream s;
  s << "[scene]\ndimension = " << dimension << (dimension == 2 ? "\nplane = \"strain\"\nthickness = 0.001\n" : "\n")
    << "[materials.glass]\nmodel = \"" << model << "\"\ndensity = 2440.0\nyoungs_modulus = 72e9\npoisson_ratio = 0.25\n"
    << (std::string(model) == "ves" ? "viscous_fraction = 0.5\nrelaxation_time = 1e-6\n" : "")
    << (std::string(model) == "eps" ? "yield_stress = 1.0e5\n" : "")
    << (std::string(model) == "lps" ? "influence = \"inverse_distance\"\n" : "")
    << "critical_stretch = 2e-3\nalpha = 0.25\nsurface_correction = " << (surface_correction ? "true" : "false") << "\n";
  if (dimension == 3)
    s << "[regions.block]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.014, 0.011, 0.009]\n"
      << "[regions.hole]\nshape = \"cylinder\"\ncenter = [0.007, 0.0055, -0.005]\naxis = [0.0, 0.0, 0.02]\nradius = 0.002\n";
  else
    s << "[regions.block]\nshape = \"box\"\nmin = [0.0, 0.0]\nmax = [0.030, 0.021]\n"
      << "[regions.hole]\nshape = \"cylinder\"\ncenter = [0.012, 0.010]\nradius = 0.003\n";
  s << "[regions.body]\nshape = \"difference\"\nof = [\"block\", \"hole\"]\n"
    << "[bodies.b]\nmaterial = \"glass\"\nregion = \"body\"\nspacing = 0.001\nhorizon = 3.015\n";
  if (dimension == 2) s << "[[cracks]]\npoints = [[0.018, 0.0105], [0.026, 0.0105]]\n";
  s << "[contact]\nenabled = false\n[solver]\nend_time = 1e-6\n";
  return s.str();
}

template <int D>
rift::pd::Model<D> block(bool surface_correction, const char* model = "pmb") {
  return rift::pd::discretize<D>(rift::scene::parse_string(block_scene(D, surface_correction, model), "block.toml"));
}

// a smooth displacement with strains up to about 3e-3 (past s00 = 2e-3 on the right), and every
// fifth bond of the rows below the middle broken beforehand (both directions)
template <int D>
void deform_and_break(rift::pd::Model<D>& m) {
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto& x = m.reference_position[i];
    m.position[i][0] = x[0] + 1e-1 * x[0] * x[0] + 4e-4 * x[1];
    m.position[i][1] = x[1] + 2e-4 * x[0] - 1e-3 * x[1];
    if constexpr (D == 3) m.position[i][2] = x[2] + 5e-4 * x[2] + 1e-4 * x[0];
  }
  auto& b = m.bonds;
  const double middle = 0.5 * (0.011 + (D == 2 ? 0.010 : 0.0));
  for (std::size_t i = 0; i < m.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (j > i && m.reference_position[i][1] < middle && (i + j) % 5 == 0) {
        b.intact.set(k, rift::pd::bond_broken);
        for (auto q = b.offset[j]; q < b.offset[j + 1]; ++q)
          if (static_cast<std::size_t>(b.neighbor[q]) == i) b.intact.set(q, rift::pd::bond_broken);
      }
    }
}

template <int D>
void check_runs_cover_forward_bonds(const rift::pd::Model<D>& m) {
  const auto& b = m.bonds;
  for (const auto& body : m.bodies) {
    std::set<std::int64_t> seen;
    ASSERT_EQ(body.slab_runs.size(), body.slab_count + 1);
    for (std::size_t q = 0; q + 1 < body.slab_runs.size(); ++q)
      for (std::size_t r = body.slab_runs[q]; r < body.slab_runs[q + 1]; ++r) {
        const auto& run = body.runs[r];
        ASSERT_GE(run.length, 1u);
        ASSERT_LE(run.length, rift::pd::max_run_length);
        // inside slab q
        ASSERT_EQ(rift::pd::slab_of(body, static_cast<std::size_t>(run.i)), q);
        ASSERT_EQ(rift::pd::slab_of(body, static_cast<std::size_t>(run.i) + run.length - 1), q);
        for (std::size_t t = 0; t < run.length; ++t) {
          const auto k = rift::pd::run_bond(b, run, t);
          const auto i = static_cast<std::size_t>(run.i) + t;
          ASSERT_GE(k, b.offset[i]);
          ASSERT_LT(k, b.offset[i + 1]);
          ASSERT_EQ(b.neighbor[static_cast<std::size_t>(k)], run.j + static_cast<std::int32_t>(t));
          ASSERT_EQ(b.family[static_cast<std::size_t>(k)], run.family);
          ASSERT_TRUE(seen.insert(k).second) << "bond " << k << " in two runs";
        }
      }
    std::size_t forward = 0;
    for (std::size_t i = body.first; i < body.last; ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) forward += static_cast<std::size_t>(b.neighbor[k]) > i;
    EXPECT_EQ(seen.size(), forward);
    // the runs hold most bonds in long runs (lines of sites)
    EXPECT_LT(double(body.runs.size()), 0.25 * double(forward));
  }
}

// A window's runs (pd/window.hpp): every forward bond with an owned end in exactly one run, and no
// run across a jump of the numbering.
void check_runs_cover_owned_ends(const rift::pd::Model<3>& w) {
  const auto& b = w.bonds;
  std::set<std::int64_t> seen;
  for (const auto& run : w.bodies[0].runs)
    for (std::size_t t = 0; t < run.length; ++t) {
      const auto i = static_cast<std::size_t>(run.i) + t, j = static_cast<std::size_t>(run.j) + t;
      ASSERT_EQ(w.numbering.whole(i), w.numbering.whole(static_cast<std::size_t>(run.i)) + t);
      ASSERT_EQ(w.numbering.whole(j), w.numbering.whole(static_cast<std::size_t>(run.j)) + t);
      ASSERT_TRUE(seen.insert(rift::pd::run_bond(b, run, t)).second);
    }
  for (std::size_t i = 0; i < w.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (j > i && (w.owns(i) || w.owns(j))) {
        EXPECT_TRUE(seen.count(k)) << "bond " << i << "-" << j << " of an owned end in no run";
      }
    }
}

TEST(BondRuns, EveryForwardBondInExactlyOneRun) {
  check_runs_cover_forward_bonds(block<3>(false));
  check_runs_cover_forward_bonds(block<2>(true));
}

// The slabs (bond_slabs.hpp cut_into_slabs): every row's forward bonds end in its own slab or the
// next, which keeps the passes' even and odd slabs apart, and the last slab, which takes the rest of
// the body, has the forward bonds of an average other within 2% (its rows lose theirs past the
// body's end: cut equally, the last of the bench cube had two thirds of the others'), unless the
// others are as short as the farthest forward reach allows, and then it has fewer.
enum class SlabBalance { near_average, shortest, coarse };

template <int D>
void check_slabs_balanced(const rift::pd::Model<D>& m, SlabBalance balance) {
  const auto& b = m.bonds;
  const auto& body = m.bodies[0];
  ASSERT_GE(body.slab_count, 2u);
  std::vector<double> forward(body.slab_count, 0.0);
  std::size_t reach = 0;
  for (std::size_t i = body.first; i < body.last; ++i) {
    const std::size_t q = rift::pd::slab_of(body, i);
    ASSERT_EQ(q, std::min((i - body.first) / body.slab_length, body.slab_count - 1));
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (j <= i) continue;
      forward[q] += 1.0;
      reach = std::max(reach, j - i);
      ASSERT_LE(rift::pd::slab_of(body, j), q + 1) << "bond " << i << "-" << j << " reaches past the next slab";
    }
  }
  ASSERT_GT(body.last - body.first, (body.slab_count - 1) * body.slab_length);  // the last holds a particle or more
  const double others = std::accumulate(forward.begin(), forward.end() - 1, 0.0) / double(body.slab_count - 1);
  EXPECT_EQ(body.slab_length == reach, balance == SlabBalance::shortest);
  if (balance == SlabBalance::shortest) {
    EXPECT_LT(forward.back(), others);
  } else if (balance == SlabBalance::near_average) {
    EXPECT_NEAR(forward.back() / others, 1.0, 0.02);
  }
}

TEST(BondSlabs, LastSlabTakesTheRestAndHasTheForwardBondsOfAnAverageOther) {
  // the bench cube's lattice, smaller (bench/run: horizon 3.015 spacings, LAMMPS's partial volumes):
  // 30^3 particles, the reach 2,700 (three planes on), 10 reaches: 8 slabs
  const auto cube = rift::pd::discretize<3>(rift::scene::parse_string(
      "[scene]\ndimension = 3\n[materials.glass]\nmodel = \"pmb\"\ndensity = 2440.0\nbulk_modulus = 48e9\nshear_modulus = 28.8e9\n"
      "critical_stretch = 0.0005\n[regions.cube]\nshape = \"box\"\nmin = [-0.0005, -0.0005, -0.0005]\nmax = [0.0295, 0.0295, 0.0295]\n"
      "[bodies.cube]\nmaterial = \"glass\"\nregion = \"cube\"\nspacing = 0.001\nhorizon = 3.015\n"
      "lattice_origin = [-0.0005, -0.0005, -0.0005]\npartial_volume = \"lammps\"\n[solver]\nend_time = 1e-7\n",
      "cube.toml"));
  ASSERT_EQ(cube.size(), 30u * 30u * 30u);
  EXPECT_EQ(cube.bodies[0].slab_count, 8u);
  EXPECT_LT(cube.bodies[0].slab_length, 27000u / 8u);  // shorter than equal slabs
  check_slabs_balanced(cube, SlabBalance::near_average);
  check_slabs_balanced(block<3>(false), SlabBalance::shortest);  // the block's three slabs as short as they may be
  check_slabs_balanced(block<2>(true), SlabBalance::near_average);
  // a strip three particles wide and 1,000 long: the reach 9 (three lines on), 250 slabs of 12
  // rounded to 248 make slabs of 13, and only 231 of those. The last slab's start once lay
  // past the body's end (the 231st slab taken as the 248th).
  const auto strip = rift::pd::discretize<2>(rift::scene::parse_string(
      "[scene]\ndimension = 2\nplane = \"strain\"\nthickness = 0.001\n[materials.glass]\nmodel = \"pmb\"\ndensity = 2440.0\n"
      "youngs_modulus = 72e9\npoisson_ratio = 0.25\ncritical_stretch = 2e-3\n[regions.strip]\nshape = \"box\"\nmin = [0.0, 0.0]\n"
      "max = [0.003, 1.0]\n[bodies.b]\nmaterial = \"glass\"\nregion = \"strip\"\nspacing = 0.001\nhorizon = 3.015\n"
      "[solver]\nend_time = 1e-7\n",
      "strip.toml"));
  ASSERT_EQ(strip.size(), 3000u);
  EXPECT_EQ(strip.bodies[0].slab_length, 13u);
  EXPECT_EQ(strip.bodies[0].slab_count, 231u);
  check_slabs_balanced(strip, SlabBalance::coarse);  // its last slab of 10 particles nearer an average other than one of 240
}

// A rank's window starts inside one of the whole body's slabs (BodyInfo::origin < 0, its first slab
// cut short). That slab's start, before the window, once wrapped round as an unsigned number and
// the slab was skipped: the owned particles just past the cut lost their ghosts' terms in the
// normal-stress dilatation pass, and a 3D LPS bar on 2 ranks drifted 10% from one rank's in 45
// steps. Every window's rows must come once each, in the order one rank takes them.
TEST(BondRuns, RowsBySlabsVisitEachRowOfAWindowOnceInTheOneRankOrder) {
  // one thread: a team takes a parity's slabs in any order, and the lists below are not shared
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto m = block<3>(false);
  const auto& body = m.bodies[0];
  std::vector<std::size_t> whole_order;
  rift::pd::for_each_row_by_slabs(body, m.numbering, [&](std::size_t i) { whole_order.push_back(i); });
  EXPECT_EQ(whole_order.size(), m.size());
  constexpr int ranks = 3;
  const auto p = rift::pd::partition_by_bonds<3>(m, ranks);
  int cut_short = 0;  // windows whose first slab starts before them
  for (int r = 0; r < ranks; ++r) {
    const auto w = rift::pd::window_of<3>(m, p, r);
    ASSERT_EQ(p.window[static_cast<std::size_t>(r)].size(), 1u);  // slabs: one range each
    const std::size_t w0 = p.window[static_cast<std::size_t>(r)][0].first, w1 = p.window[static_cast<std::size_t>(r)][0].last;
    const auto& part = w.bodies[0];
    if (part.origin < 0 && static_cast<std::size_t>(-part.origin) % part.slab_length != 0) ++cut_short;
    std::vector<std::size_t> order, expected;
    rift::pd::for_each_row_by_slabs(part, w.numbering, [&](std::size_t i) { order.push_back(i + w0); });
    std::copy_if(whole_order.begin(), whole_order.end(), std::back_inserter(expected), [&](std::size_t i) { return i >= w0 && i < w1; });
    EXPECT_EQ(order, expected) << "rank " << r << "'s window [" << w0 << ", " << w1 << ")";
    std::vector<std::size_t> rows(w1 - w0);
    std::iota(rows.begin(), rows.end(), w0);
    std::sort(order.begin(), order.end());
    EXPECT_EQ(order, rows) << "rank " << r;
  }
  EXPECT_GE(cut_short, 1);  // else the case above is not tried
  omp_set_num_threads(threads);
}

// Each window of `p` over the deformed, partly broken model m: its rows by slabs come in the
// one-rank order, every bond with an owned end is in one run, and its owned particles' PMB forces
// and bond states after a pass are the whole model's to the bit.
void expect_windows_give_the_whole_forces(const rift::pd::Model<3>& m, const rift::pd::Partition& p, const char* what) {
  auto whole = m;
  rift::pd::compute_forces<3>(whole, nullptr);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  std::vector<std::size_t> whole_order;
  rift::pd::for_each_row_by_slabs(m.bodies[0], m.numbering, [&](std::size_t i) { whole_order.push_back(i); });
  omp_set_num_threads(threads);
  for (int r = 0; r < static_cast<int>(p.owned.size()); ++r) {
    auto w = rift::pd::window_of<3>(m, p, r);
    ASSERT_EQ(w.size(), rift::count_of(p.window[static_cast<std::size_t>(r)]));
    ASSERT_EQ(w.owned_count(), rift::count_of(p.owned[static_cast<std::size_t>(r)]));
    // the rows by slabs: the window's particles in the one-rank order
    omp_set_num_threads(1);
    std::vector<std::size_t> order, expected;
    rift::pd::for_each_row_by_slabs(w.bodies[0], w.numbering, [&](std::size_t a) { order.push_back(w.numbering.whole(a)); });
    omp_set_num_threads(threads);
    std::copy_if(whole_order.begin(), whole_order.end(), std::back_inserter(expected), [&](std::size_t i) { return w.numbering.holds(i); });
    EXPECT_EQ(order, expected) << "rank " << r;
    check_runs_cover_owned_ends(w);
    rift::pd::compute_forces<3>(w, nullptr);
    std::size_t compared = 0;
    for (const rift::IndexRange& owned : w.owned())
      for (std::size_t a = owned.first; a < owned.last; ++a, ++compared) {
        const std::size_t i = w.numbering.whole(a);
        ASSERT_EQ(std::memcmp(w.force[a].data(), whole.force[i].data(), sizeof(w.force[a])), 0)
            << "rank " << r << ": particle " << i << " force " << w.force[a][0] << " against " << whole.force[i][0];
        ASSERT_EQ(w.bonds.offset[a + 1] - w.bonds.offset[a], whole.bonds.offset[i + 1] - whole.bonds.offset[i]);
        for (auto k = w.bonds.offset[a]; k < w.bonds.offset[a + 1]; ++k)
          ASSERT_EQ(w.bonds.intact[static_cast<std::size_t>(k)], whole.bonds.intact[static_cast<std::size_t>(whole.bonds.offset[i] + (k - w.bonds.offset[a]))]);
      }
    EXPECT_GT(compared, 500u);
    std::printf("rank %d of %s: %zu owned, a window of %zu particles in %zu ranges, forces bitwise the whole model's\n", r, what,
                compared, w.size(), w.numbering.ranges().size());
  }
}

// A plate 61 x 41 sites and 7 layers thick (a run, at most 256 pairs, spans a few lattice lines),
// deformed and partly broken: the windows of several ranges below cut it.
// With `lammps_family`, LAMMPS's bonds to 3 spacings (122 offsets: RowStates has a bit per offset).
rift::pd::Model<3> deformed_plate(const char* model = "pmb", bool lammps_family = false) {
  std::string scene = block_scene(3, false, model);
  auto set = [&](const std::string& from, const std::string& to) { scene.replace(scene.find(from), from.size(), to); };
  if (lammps_family) set("horizon = 3.015\n", "horizon = 3.0\npartial_volume = \"lammps\"\n");
  set("max = [0.014, 0.011, 0.009]", "max = [0.060, 0.040, 0.006]");
  set("center = [0.007, 0.0055, -0.005]", "center = [0.020, 0.012, -0.005]");
  auto m = rift::pd::discretize<3>(rift::scene::parse_string(scene, "plate.toml"));
  deform_and_break(m);
  return m;
}

// A window of several ranges of the numbering (a box of a processor grid: the lattice lines of one
// side of a cut across y, in every layer, with their ghosts and the whole runs of its owned
// particles, window.hpp with_whole_runs): its owned particles' PMB forces and bond states after a
// pass are the whole model's to the bit (the runs made over the window with an owned end are the
// whole run's, and its slabs the whole body's), and its rows by slabs come in the one-rank order.
TEST(BondRuns, AWindowOfManyRangesGivesItsOwnedParticlesTheWholeRunsForces) {
  const auto m = deformed_plate();
  const double cut = 0.020, reach = 0.003015 + 1e-9;
  // the particles below the cut, and within the bonds' reach of it, as ranges of the numbering
  auto ranges_where = [&](auto&& keep) {
    std::vector<rift::IndexRange> out;
    for (std::size_t i = 0; i < m.size(); ++i)
      if (keep(m.reference_position[i])) {
        if (!out.empty() && out.back().last == i) ++out.back().last;
        else out.push_back({i, i + 1});
      }
    return out;
  };
  rift::pd::Partition p;
  p.owned = {ranges_where([&](const auto& x) { return x[1] < cut; }), ranges_where([&](const auto& x) { return x[1] >= cut; })};
  p.window = {ranges_where([&](const auto& x) { return x[1] < cut + reach; }), ranges_where([&](const auto& x) { return x[1] >= cut - reach; })};
  for (std::size_t r = 0; r < 2; ++r) p.window[r] = rift::pd::with_whole_runs<3>(m, p.owned[r], p.window[r]);
  ASSERT_GT(p.window[0].size(), 5u);  // a range a layer or so: jumps in the numbering
  ASSERT_GT(p.window[1].size(), 5u);
  expect_windows_give_the_whole_forces(m, p, "a cut across y");
}

// The pencils of a 1 x 2 x 2 processor grid (window.hpp partition_into_pencils) of the same plate:
// the owned particles of the 4 ranks are every particle once, about a quarter each (balanced by
// bonds), one range per layer of a box; every neighbour of an owned particle is in the window; and
// each window's owned particles get the whole model's PMB forces and bond states to the bit.
TEST(BondRuns, PencilsOfAOneByTwoByTwoGridGiveTheWholeRunsForces) {
  const auto m = deformed_plate();
  const auto p = rift::pd::partition_into_pencils<3>(m, 2, 2);
  ASSERT_EQ(p.owned.size(), 4u);
  std::vector<int> owner(m.size(), -1);
  for (std::size_t r = 0; r < 4; ++r) {
    for (const auto& range : p.owned[r])
      for (std::size_t i = range.first; i < range.last; ++i) {
        ASSERT_EQ(owner[i], -1) << "particle " << i << " owned twice";
        owner[i] = static_cast<int>(r);
      }
    // a quarter of the particles, to the lines and layers the cuts fall between (41 lines, 7 layers)
    EXPECT_NEAR(static_cast<double>(rift::count_of(p.owned[r])), m.size() / 4.0, 0.12 * m.size()) << "rank " << r;
    const rift::pd::Numbering window(p.window[r]);
    for (const auto& range : p.owned[r])
      for (std::size_t i = range.first; i < range.last; ++i)
        for (auto k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k)
          ASSERT_TRUE(window.holds(static_cast<std::size_t>(m.bonds.neighbor[static_cast<std::size_t>(k)]))) << "rank " << r << " particle " << i;
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0);
  expect_windows_give_the_whole_forces(m, p, "a 1 x 2 x 2 grid");
  // the grid a run chooses for this plate, 7 layers thick: cuts across y (about 2 (h + 256 / n_x)
  // n_x n_z = 6,200 ghosts a rank, against 2 h n_x n_y = 15,100 for slabs across z)
  EXPECT_EQ((rift::pd::choose_pencils<3>(m, 4)), (std::array<int, 2>{4, 1}));
  EXPECT_EQ((rift::pd::choose_pencils<3>(m, 2)), (std::array<int, 2>{2, 1}));
  EXPECT_EQ((rift::pd::choose_pencils<2>(block<2>(false), 4)), (std::array<int, 2>{1, 4}));
}

// The pass against Silling and Askari's formulas row by row.
template <int D>
void check_pmb_against_rows(bool surface_correction) {
  auto m = block<D>(surface_correction);
  deform_and_break(m);
  const auto before = m.bonds.intact;
  const auto& c = m.bodies[0].constants;
  const auto& b = m.bonds;
  const std::size_t n = m.size();
  std::vector<rift::Vec<D>> expected(n, rift::Vec<D>{});
  std::vector<double> smallest(n, std::numeric_limits<double>::max());
  std::vector<std::uint8_t> breaks(b.intact.size(), 0);
  std::size_t broken_here = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (before[static_cast<std::size_t>(k)] != rift::pd::bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      rift::Vec<D> eta;
      double r = 0.0;
      for (int q = 0; q < D; ++q) eta[q] = m.position[j][q] - m.position[i][q], r += eta[q] * eta[q];
      r = std::sqrt(r);
      const double xi = b.length(k), s = (r - xi) / xi;
      if (s > std::min(m.stretch_limit[i], m.stretch_limit[j])) {
        breaks[static_cast<std::size_t>(k)] = 1;
        broken_here += j > i;
        continue;
      }
      smallest[i] = std::min(smallest[i], s);
      // the influence-function factors are stored, and averaged, in single precision (bonds.hpp)
      const double g = 0.5f * (b.correction(i, k) + b.mirror_correction(j, k));
      const double f = c.micromodulus * s * g * b.volume(k) / r;  // constant influence function
      for (int q = 0; q < D; ++q) expected[i][q] += f * eta[q];
    }
  ASSERT_GT(broken_here, 20u);
  rift::pd::compute_forces<D>(m, nullptr);
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < D; ++q) largest = std::max(largest, std::abs(expected[i][q]));
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < D; ++q) worst = std::max(worst, std::abs(m.force[i][q] - expected[i][q]) / largest);
  std::printf("PMB runs, %dD, surface correction %d: largest force difference %.1e of the largest force, %zu bonds broken\n", D,
              int(surface_correction), worst, broken_here);
  EXPECT_LT(worst, 1e-12);
  for (std::size_t k = 0; k < b.intact.size(); ++k) {
    const bool was = before[k] == rift::pd::bond_intact;
    ASSERT_EQ(b.intact[k] == rift::pd::bond_intact, was && !breaks[k]) << "bond " << k;
  }
  // s0 = s00 - alpha s_min for the next step (eq. 23)
  for (std::size_t i = 0; i < n; ++i) {
    if (smallest[i] < std::numeric_limits<double>::max()) {
      ASSERT_DOUBLE_EQ(m.next_stretch_limit[i], c.critical_stretch - c.alpha * smallest[i]) << i;
    }
  }
}

// The rows of bond states the dilatation pass leaves for the force pass (bond_runs.hpp RowStates:
// those of the bonds it broke made again, refresh_rows) equal rows made afresh from every bond's
// state after it, bit for bit, with the intact counts of each row; and the pass broke bonds. With
// LAMMPS's bonds to 3 spacings (122 offsets: two words of bits per row) and the default's (250: four).
TEST(BondRuns, RowsLeftByTheDilatationPassEqualRowsMadeAfresh) {
  for (const bool lammps : {true, false})
    for (const char* model : {"lps", "ves"}) {
      std::string scene = block_scene(3, false, model);
      if (lammps) scene.replace(scene.find("horizon = 3.015\n"), 16, "horizon = 3.0\npartial_volume = \"lammps\"\n");
      auto m = rift::pd::discretize<3>(rift::scene::parse_string(scene, "block.toml"));
      deform_and_break(m);
      const auto& b = m.bonds;
      const auto& body = m.bodies[0];
      ASSERT_EQ(body.family_count, lammps ? 122u : 250u);
      const auto before = b.intact;
      rift::pd::RowStates left;
      if (std::string(model) == "lps") rift::pd::lps_dilatation<3, rift::scene::Influence::constant>(m, body, &left);
      else rift::pd::ves_dilatation<3, rift::scene::Influence::constant>(m, body, 1e-7, &left);
      std::size_t broke = 0;
      for (std::size_t k = 0; k < b.intact.size(); ++k) broke += before[k] != b.intact[k];
      ASSERT_GT(broke, 40u) << model;
      ASSERT_NE(left.intact, nullptr);
      ASSERT_EQ(left.words, lammps ? 2u : 4u);
      const std::vector<std::uint8_t> whole(left.whole, left.whole + m.size());
      const std::vector<std::uint64_t> words(left.intact, left.intact + left.words * left.stride);
      // the rows left are the ones kept with the bonds, current as the pass left the states
      ASSERT_EQ(left.whole, b.kept_rows.whole.data());
      ASSERT_EQ(b.kept_rows.made.size(), 1u);
      ASSERT_EQ(b.kept_rows.made[0].version, b.intact.version()) << model;
      rift::pd::Bonds copy = b;  // rows made afresh: no kept rows
      copy.kept_rows = {};
      const rift::pd::RowStates fresh = rift::pd::whole_rows(copy, body);
      for (std::size_t i = 0; i < m.size(); ++i) {
        ASSERT_EQ(whole[i], fresh.whole[i]) << model << " row " << i;
        std::int32_t intact = 0;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) intact += b.intact[static_cast<std::size_t>(k)] == rift::pd::bond_intact;
        ASSERT_EQ(rift::pd::intact_bond_count(b, fresh, i), intact) << model << " row " << i;
        if (whole[i] == rift::pd::bond_intact) continue;  // a whole row's bits are not read
        for (std::size_t w = 0; w < left.words; ++w) ASSERT_EQ(words[w * left.stride + i], fresh.intact[w * fresh.stride + i]) << model << " row " << i;
      }
      // the fluid's counts of each row's intact and broken bonds (hf/fluid_network.hpp
      // count_bond_states) from the rows kept (kept_row_count) equal those from the states
      std::vector<std::uint64_t> by_rows(m.size()), by_states(m.size());
      ASSERT_EQ(rift::hf::count_bond_states(b, 0, m.size(), by_rows, true), 0);
      ASSERT_EQ(rift::hf::count_bond_states(b, 0, m.size(), by_states, false), 0);
      EXPECT_EQ(by_rows, by_states) << model;
      EXPECT_GT(std::count_if(by_states.begin(), by_states.end(), [](std::uint64_t c) { return (c >> 32) > 0; }), 20) << model;
    }
}

TEST(BondRuns, PmbPassEqualsRowByRowFormulas) {
  check_pmb_against_rows<3>(false);
  check_pmb_against_rows<3>(true);
  check_pmb_against_rows<2>(true);
}

// The LPS passes (uncorrected, 3D) against Silling et al. (2007) eq. 37 and 39 row by row: theta_i =
// 3/m_i sum omega |xi| e V_j, t_i<j> = 3 K theta_i omega |xi| / m_i + 15 G omega (e - theta_i |xi| / 3)
// / m_i, f_i = sum (t_i<j> + t_j<i>) V_j along the deformed bond, omega = delta/|xi| (the scene's
// inverse_distance), with bonds already broken and bonds that break in the pass (e > |xi| s0);
// tolerance 1e-12 of the largest force.
TEST(BondRuns, LpsPassesEqualRowByRowFormulas) {
  auto m = block<3>(false, "lps");
  deform_and_break(m);
  const auto before = m.bonds.intact;
  const auto& c = m.bodies[0].constants;
  const auto& b = m.bonds;
  const std::size_t n = m.size();
  auto extension = [&](std::size_t i, std::size_t j, double xi, rift::Vec<3>& eta) {
    double r = 0.0;
    for (int q = 0; q < 3; ++q) eta[q] = m.position[j][q] - m.position[i][q], r += eta[q] * eta[q];
    return std::sqrt(r) - xi;
  };
  std::vector<std::uint8_t> alive(b.intact.size(), 0);
  std::vector<double> theta(n, 0.0);
  std::size_t broken_here = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (before[static_cast<std::size_t>(k)] != rift::pd::bond_intact) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      rift::Vec<3> eta;
      const double xi = b.length(k), e = extension(i, j, xi, eta);
      if (e > xi * std::min(m.stretch_limit[i], m.stretch_limit[j])) {
        broken_here += j > i;
        continue;
      }
      alive[static_cast<std::size_t>(k)] = 1;
      theta[i] += (c.horizon / xi) * xi * e * b.volume(k);
    }
  for (std::size_t i = 0; i < n; ++i) theta[i] *= 3.0 / m.weighted_volume[i];
  std::vector<rift::Vec<3>> expected(n, rift::Vec<3>{});
  const double K = c.kappa, G = c.shear_modulus;
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!alive[static_cast<std::size_t>(k)]) continue;
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      rift::Vec<3> eta;
      const double xi = b.length(k), e = extension(i, j, xi, eta), omega = c.horizon / xi;
      auto t = [&](std::size_t p) {
        return 3 * K * theta[p] * omega * xi / m.weighted_volume[p] + 15 * G * omega * (e - theta[p] * xi / 3) / m.weighted_volume[p];
      };
      const double r = e + xi;
      for (int q = 0; q < 3; ++q) expected[i][q] += (t(i) + t(j)) * b.volume(k) * eta[q] / r;
    }
  ASSERT_GT(broken_here, 20u);
  rift::pd::compute_forces<3>(m, nullptr);
  double largest = 0.0, worst = 0.0, worst_theta = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int q = 0; q < 3; ++q) largest = std::max(largest, std::abs(expected[i][q]));
  for (std::size_t i = 0; i < n; ++i) {
    for (int q = 0; q < 3; ++q) worst = std::max(worst, std::abs(m.force[i][q] - expected[i][q]) / largest);
    worst_theta = std::max(worst_theta, std::abs(m.dilatation[i] - theta[i]));
  }
  std::printf("LPS runs: largest force difference %.1e of the largest force, dilatation %.1e, %zu bonds broken\n", worst, worst_theta,
              broken_here);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_theta, 1e-15);
  for (std::size_t k = 0; k < b.intact.size(); ++k)
    ASSERT_EQ(b.intact[k] == rift::pd::bond_intact, alive[k] == 1) << "bond " << k;
}

// Every instruction set the processor has gives the bits of the SSE2 build (PMB, LPS, VES with two
// steps of history).
template <int D>
void check_same_bits(bool surface_correction, const char* model = "pmb") {
  auto run = [&](rift::VectorIsa isa) {
    const auto before = rift::set_vector_isa(isa);
    auto m = block<D>(surface_correction, model);
    deform_and_break(m);
    rift::pd::compute_forces<D>(m, nullptr, 1e-7);
    for (std::size_t i = 0; i < m.size(); ++i) m.position[i][0] += 1e-6 * m.reference_position[i][1];
    rift::pd::compute_forces<D>(m, nullptr, 1e-7);
    rift::set_vector_isa(before);
    return m;
  };
  const auto best = rift::widest_vector_isa();
  const auto wide = run(best), narrow = run(rift::VectorIsa::sse2);
  ASSERT_EQ(wide.bonds.intact, narrow.bonds.intact);
  ASSERT_EQ(0, std::memcmp(wide.force.data(), narrow.force.data(), wide.force.size() * sizeof(wide.force[0])));
  ASSERT_EQ(0, std::memcmp(wide.next_stretch_limit.data(), narrow.next_stretch_limit.data(), wide.size() * sizeof(double)));
  ASSERT_EQ(0, std::memcmp(wide.dilatation.data(), narrow.dilatation.data(), wide.size() * sizeof(double)));
  ASSERT_EQ(0, std::memcmp(wide.dilatation_coupling.data(), narrow.dilatation_coupling.data(), wide.size() * sizeof(double)));
  ASSERT_EQ(wide.bonds.back_extension, narrow.bonds.back_extension);
  if (best == rift::VectorIsa::avx512) {
    const auto middle = run(rift::VectorIsa::avx2);
    ASSERT_EQ(0, std::memcmp(wide.force.data(), middle.force.data(), wide.force.size() * sizeof(wide.force[0])));
  }
}

const char* isa_name(rift::VectorIsa isa) {
  return isa == rift::VectorIsa::avx512 ? "AVX-512" : isa == rift::VectorIsa::avx2 ? "AVX2" : "SSE2";
}

TEST(BondRuns, VectorClonesGiveTheSameBits) {
  std::printf("vector instructions here: %s, the kernels' %s\n", isa_name(rift::widest_vector_isa()), isa_name(rift::vector_isa()));
  const auto chosen = rift::vector_isa();
  for (const char* model : {"pmb", "lps", "ves"}) {
    check_same_bits<3>(false, model);
    check_same_bits<2>(true, model);
    ASSERT_EQ(rift::vector_isa(), chosen) << "set_vector_isa sets the one before back";
  }
}

// The energy densities in runs against the rows (pmb.hpp, lps.hpp energy_density): PMB, LPS, VES
// (two steps of history) and EPS (two steps of plastic flow), 3D without the surface correction and 2D with it, bonds broken
// beforehand and by the passes. The sums are made in another order: 1e-12 of the largest W.
template <int D>
void check_energy_runs_against_rows(bool surface_correction, const char* model) {
  auto m = block<D>(surface_correction, model);
  deform_and_break(m);
  rift::pd::compute_forces<D>(m, nullptr, 1e-7);
  for (std::size_t i = 0; i < m.size(); ++i) m.position[i][0] += 1e-6 * m.reference_position[i][1];
  rift::pd::compute_forces<D>(m, nullptr, 1e-7);
  std::vector<double> runs(m.size());
  rift::pd::strain_energy_densities<D>(m, runs.data());
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i) largest = std::max(largest, std::abs(rift::pd::strain_energy_density<D>(m, i)));
  for (std::size_t i = 0; i < m.size(); ++i) worst = std::max(worst, std::abs(runs[i] - rift::pd::strain_energy_density<D>(m, i)) / largest);
  std::printf("%s %dD: energy densities in runs against the rows, largest difference %.1e of the largest\n", model, D, worst);
  ASSERT_GT(largest, 0.0);
  EXPECT_LT(worst, 1e-12) << model << " " << D << "D";
}

TEST(BondRuns, StrainEnergyDensitiesEqualRowByRowFormulas) {
  for (const char* model : {"pmb", "lps", "ves", "eps"}) {
    check_energy_runs_against_rows<3>(false, model);
    check_energy_runs_against_rows<2>(true, model);
  }
}

// Uniform dilatation eps of the LPS and VES (Silling et al. 2007 eq. 88: theta = 3 eps and no
// deviatoric extension where the family is whole): W = K (3 eps)^2 / 2, the continuum's, to 1e-9.
TEST(BondRuns, StrainEnergyDensityOfAUniformDilatationIsTheContinuums) {
  for (const char* model : {"lps", "ves"}) {
    std::string scene = block_scene(3, false, model);  // the block without its hole
    scene.replace(scene.find("of = [\"block\", \"hole\"]"), std::string("of = [\"block\", \"hole\"]").size(), "of = [\"block\"]");
    scene.replace(scene.find("\"difference\""), std::string("\"difference\"").size(), "\"union\"");
    auto m = rift::pd::discretize<3>(rift::scene::parse_string(scene, "block.toml"));
    const double eps = 1e-4;
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int q = 0; q < 3; ++q) m.position[i][q] = (1.0 + eps) * m.reference_position[i][q];
    rift::pd::compute_forces<3>(m, nullptr, 1e-7);
    std::vector<double> w(m.size());
    rift::pd::strain_energy_densities<3>(m, w.data());
    const auto& b = m.bonds;
    const auto& body = m.bodies[0];
    const double expected = 0.5 * body.constants.kappa * 9.0 * eps * eps;
    std::size_t whole = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]) != body.family_count) continue;
      ++whole;
      worst = std::max(worst, std::abs(w[i] - expected) / expected);
    }
    std::printf("%s: W of a uniform dilatation against K (3 eps)^2 / 2 over %zu whole families: %.1e\n", model, whole, worst);
    ASSERT_GT(whole, 50u);
    EXPECT_LT(worst, 1e-9) << model;
  }
}

}  // namespace

namespace {

// (7) for_each_slab on a team of four: slab q writes its own particles and those of q + 1, so it
// must never run beside q - 1 or q + 1, and an odd slab (whole-body parity) must start after its
// even neighbours have ended (the order one sweep of the even slabs and then one of the odd ones
// gives: the sums' order on any thread count). Each slab takes a few microseconds, so that a team
// that broke the rule would be caught running two neighbours at once.
TEST(BondRuns, SlabsRunBesideNoNeighbourAndEachOddSlabAfterItsEvenOnes) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(4);
  for (const std::size_t count : {3u, 4u, 12u, 13u, 40u})
    for (const std::size_t first_slab : {0u, 1u, 6u, 7u}) {
      std::vector<std::atomic<int>> running(count), ended(count), visits(count);
      std::atomic<int> clashes{0}, early{0};
      rift::pd::for_each_slab(count, first_slab, true, [&](std::size_t q) {
        const auto neighbours_running = [&] { return (q > 0 && running[q - 1].load()) || (q + 1 < count && running[q + 1].load()); };
        if ((first_slab + q) % 2 == 1 && ((q > 0 && !ended[q - 1].load()) || (q + 1 < count && !ended[q + 1].load()))) ++early;
        running[q].store(1);
        if (neighbours_running()) ++clashes;
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(20 + 7 * (q % 5));
        while (std::chrono::steady_clock::now() < until) {
        }
        if (neighbours_running()) ++clashes;
        running[q].store(0);
        ended[q].store(1);
        ++visits[q];
      });
      for (std::size_t q = 0; q < count; ++q) EXPECT_EQ(visits[q].load(), 1) << count << " slabs from " << first_slab << ": slab " << q;
      EXPECT_EQ(clashes.load(), 0) << count << " slabs from " << first_slab;
      EXPECT_EQ(early.load(), 0) << count << " slabs from " << first_slab;
    }
  omp_set_num_threads(threads);
}

// Whether two arrays hold the same bits (PMB and LPS have no VES history: an empty array's data()
// may be null, which memcmp must not get).
template <class A, class B>
bool same_bits(const A& a, const B& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// (7) The passes over a deformed, partly broken plate of 17,000 particles (a team's size: the slabs
// run on the team), three of them, stretched more before each (each breaks bonds): PMB, LPS and
// VES forces, the bonds that break and the VES histories and row sums (the bonds each pass broke
// taken out of both ends' sums by the team, ves.hpp) the same bits on one, two and four threads
// (the slabs and their order depend on the bonds alone).
TEST(BondRuns, PassesGiveTheSameBitsOnOneTwoAndFourThreads) {
  const int threads = omp_get_max_threads();
  for (const char* model : {"pmb", "lps", "ves"}) {
    const auto deformed = deformed_plate(model);
    ASSERT_TRUE(rift::parallel::worth_a_team(deformed.size()));
    auto pass = [&](int team) {
      omp_set_num_threads(team);
      auto m = deformed;
      for (int step = 0; step < 3; ++step) {
        for (std::size_t i = 0; i < m.size(); ++i) m.position[i][0] += 2e-3 * m.reference_position[i][0] * m.reference_position[i][0];
        rift::pd::compute_forces<3>(m, nullptr, 1e-8);
      }
      return m;
    };
    const auto one = pass(1);
    std::size_t broken = 0;
    for (const auto state : one.bonds.intact) broken += state != rift::pd::bond_intact;
    EXPECT_GT(broken, 0u);
    for (const int team : {2, 4}) {
      const auto many = pass(team);
      EXPECT_TRUE(same_bits(many.force, one.force)) << model << " on " << team << " threads: forces";
      EXPECT_TRUE(same_bits(many.bonds.intact, one.bonds.intact)) << model << " on " << team << " threads: bond states";
      EXPECT_TRUE(same_bits(many.bonds.back_extension, one.bonds.back_extension)) << model << " on " << team << " threads: VES history";
      EXPECT_TRUE(same_bits(many.bonds.deviatoric_sum, one.bonds.deviatoric_sum)) << model << " on " << team << " threads: VES sums";
      EXPECT_TRUE(same_bits(many.bonds.back_sum, one.bonds.back_sum)) << model << " on " << team << " threads: VES sums";
      EXPECT_TRUE(same_bits(many.bonds.summed_bonds, one.bonds.summed_bonds)) << model << " on " << team << " threads: VES sums";
    }
  }
  omp_set_num_threads(threads);
}

// (11) The VES force kernel skips the spans of a masked run whose bonds are all broken (bond_runs.hpp
// RunSpans, cut at the history's cache lines, which a dead span then leaves unread and unwritten):
// over three passes of a plate stretched more before each, with bands across it whose every bond is
// broken (so runs along x hold long dead spans beside intact bonds) and bonds broken by the passes,
// forces, dilatations, stretch limits, bond states, VES histories and row sums are the bits of the
// kernel taking every bond; 3D without the surface correction and 2D with it (LPS, which takes every
// bond either way, as a check of the test).
template <int D>
void check_broken_spans_skipped(const char* model) {
  rift::pd::Model<D> start = [&]() -> rift::pd::Model<D> {
    if constexpr (D == 3) {
      return deformed_plate(model);
    } else {
      auto m = block<2>(true, model);
      deform_and_break(m);
      return m;
    }
  }();
  // a part of the deformation (the 2D block is half as long), so that the bonds along x break in
  // the passes only on the right
  const double share = D == 3 ? 0.3 : 0.6;
  for (std::size_t i = 0; i < start.size(); ++i)
    for (int q = 0; q < D; ++q) start.position[i][q] = start.reference_position[i][q] + share * (start.position[i][q] - start.reference_position[i][q]);
  auto& b = start.bonds;
  // bands across x, every bond of their particles broken (both directions)
  const double period = 0.030, width = 0.020;  // 20 particles along x, at least one whole span of 16
  auto in_band = [&](std::size_t i) { return std::fmod(start.reference_position[i][0] + 0.004, period) < width; };
  for (std::size_t i = 0; i < start.size(); ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      if (in_band(i) || in_band(j)) b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
    }
  // the runs with both a span of broken bonds and intact bonds, as the first pass finds them
  std::size_t mixed = 0, mixed_overlapping = 0;  // the latter: runs whose ends overlap (through buffers)
  const auto& body = start.bodies[0];
  const rift::pd::RowStates rows = rift::pd::whole_rows(start.bonds, body);
  for (const auto& run : body.runs) {
    alignas(64) double alive[rift::pd::max_run_length];
    if (!rift::pd::mask_run(start.bonds, run, rows, alive)) continue;
    rift::pd::RunSpans spans;
    rift::pd::cut_run_spans(alive, run.length, 16, 16, spans);
    mixed += spans.count > 1;
    mixed_overlapping += spans.count > 1 && !rift::pd::ends_apart_in_vectors(run);
  }
  auto passes = [&](bool skip) {
    const bool before = rift::pd::skip_broken_spans();
    rift::pd::skip_broken_spans() = skip;
    auto m = start;
    for (int step = 0; step < 3; ++step) {
      for (std::size_t i = 0; i < m.size(); ++i) m.position[i][0] += 2e-3 * m.reference_position[i][0] * m.reference_position[i][0];
      rift::pd::compute_forces<D>(m, nullptr, 1e-8);
    }
    rift::pd::skip_broken_spans() = before;
    return m;
  };
  const auto skipped = passes(true), every = passes(false);
  std::size_t broke = 0;
  for (std::size_t k = 0; k < b.intact.size(); ++k) broke += skipped.bonds.intact[k] != b.intact[k];
  std::printf("%s %dD: %zu runs with spans of broken bonds beside intact ones (%zu with overlapping ends), %zu bonds broken by the passes\n",
              model, D, mixed, mixed_overlapping, broke);
  EXPECT_GT(mixed, 100u);
  EXPECT_GT(mixed_overlapping, 5u);
  EXPECT_GT(broke, 0u);
  const std::string what = std::string(model) + " " + std::to_string(D) + "D: ";
  EXPECT_TRUE(same_bits(skipped.force, every.force)) << what << "forces";
  EXPECT_TRUE(same_bits(skipped.bonds.intact, every.bonds.intact)) << what << "bond states";
  EXPECT_TRUE(same_bits(skipped.dilatation, every.dilatation)) << what << "dilatations";
  EXPECT_TRUE(same_bits(skipped.dilatation_coupling, every.dilatation_coupling)) << what << "P";
  EXPECT_TRUE(same_bits(skipped.next_stretch_limit, every.next_stretch_limit)) << what << "stretch limits";
  EXPECT_TRUE(same_bits(skipped.bonds.back_extension, every.bonds.back_extension)) << what << "VES history";
  EXPECT_TRUE(same_bits(skipped.bonds.last_extension, every.bonds.last_extension)) << what << "VES history";
  EXPECT_TRUE(same_bits(skipped.bonds.deviatoric_sum, every.bonds.deviatoric_sum)) << what << "VES sums";
  EXPECT_TRUE(same_bits(skipped.bonds.back_sum, every.bonds.back_sum)) << what << "VES sums";
}

TEST(BondRuns, SpansOfBrokenBondsSkippedGiveTheBitsOfEveryBondTaken) {
  for (const char* model : {"lps", "ves"}) {
    check_broken_spans_skipped<3>(model);
    check_broken_spans_skipped<2>(model);
  }
}

// (8) Four steps of a plate stretched more each time (each pass breaks bonds), with every bond of one
// row broken by hand before the third: the model whose rows are kept from pass to pass gets the
// bits of one whose rows are made afresh for every pass, and after each pass its kept rows are
// current (made at the states' version) and equal rows made afresh.
TEST(BondRuns, RowsKeptFromPassToPassGiveTheBitsOfRowsMadeAfresh) {
  const auto broken_bonds = [](const rift::pd::Bonds& b) {
    std::size_t broken = 0;
    for (const auto state : b.intact) broken += state != rift::pd::bond_intact;
    return broken;
  };
  for (const bool lammps : {true, false})
  for (const char* model : {"pmb", "lps", "ves"}) {
    auto kept = deformed_plate(model, lammps);
    auto afresh = kept;
    const auto& body = kept.bodies[0];
    std::size_t broke = 0;
    for (int step = 0; step < 4; ++step) {
      for (auto* m : {&kept, &afresh}) {
        for (std::size_t i = 0; i < m->size(); ++i) m->position[i][0] += 4e-3 * m->reference_position[i][0] * m->reference_position[i][0];
        if (step == 2) {
          const std::size_t i = m->size() / 2;
          auto& b = m->bonds;
          for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
            b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_broken);
            b.intact.set(static_cast<std::size_t>(rift::pd::reverse_bond(b, body, i, k)), rift::pd::bond_broken);
          }
        }
      }
      afresh.bonds.kept_rows = {};
      const std::size_t before = broken_bonds(kept.bonds);
      rift::pd::compute_forces<3>(kept, nullptr, 1e-8);
      rift::pd::compute_forces<3>(afresh, nullptr, 1e-8);
      const std::size_t now = broken_bonds(kept.bonds) - before;
      EXPECT_GT(now, 0u) << model << " step " << step << ": the pass broke no bond";
      broke += now;
      EXPECT_TRUE(same_bits(kept.force, afresh.force)) << model << " step " << step << ": forces";
      EXPECT_TRUE(kept.bonds.intact == afresh.bonds.intact) << model << " step " << step << ": bond states";
      EXPECT_TRUE(same_bits(kept.bonds.back_extension, afresh.bonds.back_extension)) << model << " step " << step << ": VES history";
      const auto& made = kept.bonds.kept_rows.made;
      ASSERT_EQ(made.size(), 1u);
      EXPECT_EQ(made[0].version, kept.bonds.intact.version()) << model << " step " << step << ": kept rows not current";
      const rift::pd::RowStates rows = rift::pd::whole_rows(kept.bonds, body);
      rift::pd::Bonds copy = kept.bonds;
      copy.kept_rows = {};
      const rift::pd::RowStates fresh = rift::pd::whole_rows(copy, body);
      ASSERT_NE(rows.intact, nullptr);
      for (std::size_t i = 0; i < kept.size(); ++i) {
        ASSERT_EQ(rows.whole[i], fresh.whole[i]) << model << " step " << step << " row " << i;
        if (rows.whole[i] == rift::pd::bond_intact) continue;  // a whole row's bits are not read
        for (std::size_t w = 0; w < rows.words; ++w)
          ASSERT_EQ(rows.intact[w * rows.stride + i], fresh.intact[w * fresh.stride + i]) << model << " step " << step << " row " << i;
      }
    }
    EXPECT_GT(broke, 1000u) << model;
    std::printf("%s, %zu offsets: %zu bonds broken in four passes, kept rows current after each\n", model, body.family_count, broke);
  }
}

}  // namespace

// (9) The one-loop form of a PMB run (pmb.hpp pmb_run_to_ends), whose upper ends are lower ends of
// the same run further on (j - i = 8 to 13, 64 bonds): on every clone the forces and smallest
// stretches are the bits of the bonds taken one at a time in the run's order (each bond's force
// +g to f_i, -g to f_j, as Silling and Askari's pair force c omega s V_j along the deformed bond),
// and a bond past its limit adds nothing and is marked for the caller. Exact: the same IEEE
// operations in the same order (vector_isa.hpp); a vector that held an end twice would lose a term.
TEST(BondRuns, OneLoopFormAddsToOverlappingEndsInTheBondsOrder) {
  constexpr std::size_t length = 64;
  const double spacing = 1e-3, coefficient = 2.5e20, volume = 1e-9;
  const rift::VectorIsa best = rift::widest_vector_isa();
  for (std::size_t distance : {8u, 9u, 13u}) {
    const std::size_t n = length + distance;
    const double bond_length = distance * spacing, inverse_length = 1.0 / bond_length;
    std::array<std::vector<double>, 3> x;
    for (int q = 0; q < 3; ++q) {
      x[q].resize(n);
      for (std::size_t p = 0; p < n; ++p)  // a line along x, stretched and bent unevenly (stretches about 1e-5)
        x[q][p] = q == 0 ? p * spacing + 1e-7 * std::sin(0.7 * static_cast<double>(p)) : 1e-7 * std::cos(1.3 * static_cast<double>(p) + q);
    }
    std::vector<double> limit(n, 5e-4);
    limit[20] = -1.0;  // bonds 20 (lower end 20) and 20 - distance (upper end 20) pass their limit
    // the reference: bond t of the run joins t and t + distance
    // forces before the run of the bonds' own size, so that the order of the terms shows in the bits
    std::array<std::vector<double>, 3> f_before;
    for (int q = 0; q < 3; ++q)
      for (std::size_t p = 0; p < n; ++p) f_before[q].push_back(3.3e6 * std::sin(1.7 * static_cast<double>(p) + q));
    auto f_one = f_before;
    std::vector<double> smallest_one(n, std::numeric_limits<double>::max());
    std::vector<int> past_one(length, 0);
    for (std::size_t t = 0; t < length; ++t) {
      const std::size_t i = t, j = t + distance;
      const double ex = x[0][j] - x[0][i], ey = x[1][j] - x[1][i], ez = x[2][j] - x[2][i];
      const double r = std::sqrt(ex * ex + ey * ey + ez * ez);
      const double s = (r - bond_length) * inverse_length;
      if (s > std::min(limit[i], limit[j])) {
        past_one[t] = 1;
        continue;
      }
      const double scalar = coefficient * s * volume / r;
      const double g[3] = {scalar * ex, scalar * ey, scalar * ez};
      for (int q = 0; q < 3; ++q) f_one[q][i] += g[q], f_one[q][j] -= g[q];
      smallest_one[i] = std::min(smallest_one[i], s), smallest_one[j] = std::min(smallest_one[j], s);
    }
    ASSERT_EQ(std::count(past_one.begin(), past_one.end(), 1), 2) << "distance " << distance;
    for (const auto isa : {rift::VectorIsa::sse2, rift::VectorIsa::avx2, rift::VectorIsa::avx512}) {
      if (static_cast<int>(isa) > static_cast<int>(best)) continue;
      auto f = f_before;
      std::vector<double> smallest(n, std::numeric_limits<double>::max()), flagged(length, 0.0);
      rift::pd::PmbRun a;
      a.length = length;
      a.xa = x[0].data(), a.ya = x[1].data(), a.za = x[2].data();
      a.xb = x[0].data() + distance, a.yb = x[1].data() + distance, a.zb = x[2].data() + distance;
      a.limit_a = limit.data(), a.limit_b = limit.data() + distance;
      a.bond_length = bond_length, a.inverse_length = inverse_length, a.coefficient = coefficient, a.volume = volume;
      a.fxa = f[0].data(), a.fya = f[1].data(), a.fza = f[2].data();
      a.fxb = f[0].data() + distance, a.fyb = f[1].data() + distance, a.fzb = f[2].data() + distance;
      a.smallest_a = smallest.data(), a.smallest_b = smallest.data() + distance;
      a.may_break = flagged.data();
      a.breakable = true;
      a.ends_apart = rift::pd::ends_apart_in_vectors({0, static_cast<std::int32_t>(distance), 0, 0, static_cast<std::uint16_t>(length)});
      ASSERT_TRUE(a.ends_apart) << "distance " << distance;
      EXPECT_TRUE((rift::pd::pmb_run_kernel<3, false, rift::pd::StretchLimit, false>(isa)(a))) << "distance " << distance;
      for (std::size_t t = 0; t < length; ++t) ASSERT_EQ(flagged[t] != 0.0, past_one[t] == 1) << "distance " << distance << " bond " << t;
      for (int q = 0; q < 3; ++q) EXPECT_TRUE(same_bits(f[q], f_one[q])) << "distance " << distance << " component " << q << " isa " << static_cast<int>(isa);
      EXPECT_TRUE(same_bits(smallest, smallest_one)) << "distance " << distance << " isa " << static_cast<int>(isa);
    }
  }
}

// A change of bond states takes a version no other states have (pd/bond_states.hpp): a copy keeps its
// original's version until either changes, and two states changed apart never share one, even where
// each made the same number of changes (a cache made from one, as the fluid network's counts of
// bonds are, is then never taken for the other's).
TEST(BondStates, AChangeTakesAVersionNoOtherStatesHave) {
  rift::pd::BondStates a;
  a.replace().assign(16, rift::pd::bond_intact);
  rift::pd::BondStates b = a;
  EXPECT_EQ(a.version(), b.version());
  a.set(3, rift::pd::bond_broken);
  b.set(5, rift::pd::bond_broken);
  EXPECT_NE(a.version(), b.version());
  rift::pd::BondStates c, d;
  c.replace().assign(16, rift::pd::bond_intact);
  d.replace().assign(16, rift::pd::bond_intact);
  EXPECT_NE(c.version(), d.version());
  const auto before = c.version();
  c.changed();
  EXPECT_NE(c.version(), before);
}

// A family of more offsets than the rows hold bits for (bond_runs.hpp max_row_words) has none: its
// runs then find each bond's state in its row. The passes with rows without bits give the bits of
// the passes with them: the dilatation pass (dilatations, couplings, smallest stretches and the
// bonds it broke) and the force pass, on the deformed block with the default's 250 offsets (four
// words of bits), with and without the surface correction, and a row of failed interface bonds.
TEST(BondRuns, RowsWithoutBitsGiveTheBitsOfRowsWithThem) {
  using Influence = rift::scene::Influence;
  for (const bool corrected : {false, true}) {
    auto with = rift::pd::discretize<3>(rift::scene::parse_string(block_scene(3, corrected, "lps"), "block.toml"));
    deform_and_break(with);
    const auto& body = with.bodies[0];
    {  // a row whose bonds are all failed interface bonds (its state's bits all 0: none intact)
      auto& b = with.bonds;
      const std::size_t i = with.size() / 3;
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        b.intact.set(static_cast<std::size_t>(k), rift::pd::bond_interface_failed);
        b.intact.set(static_cast<std::size_t>(rift::pd::reverse_bond(b, body, i, k)), rift::pd::bond_interface_failed);
      }
      ASSERT_EQ(rift::pd::intact_bond_count(b, rift::pd::whole_rows(b, body), i), 0);
    }
    auto without = with;
    ASSERT_EQ(body.constants.surface_correction, corrected);
    struct Pass {
      std::vector<double> coupling, smallest;
      rift::pd::BreakLog log;
    };
    auto dilatation = [&](rift::pd::Model<3>& m, bool bits, Pass& p) {
      rift::pd::RowStates rows = rift::pd::whole_rows(m.bonds, body);
      ASSERT_NE(rows.intact, nullptr);
      if (!bits) rows.intact = nullptr;
      p.coupling.assign(m.size(), 0.0), p.smallest.assign(m.size(), 1e300);
      std::fill(m.dilatation.begin(), m.dilatation.end(), 0.0);
      if (corrected)
        rift::pd::dilatation_runs<3, Influence::constant, true, true>(m, body, rows, p.coupling.data(), p.smallest.data(), p.log);
      else
        rift::pd::dilatation_runs<3, Influence::constant, true, false>(m, body, rows, p.coupling.data(), p.smallest.data(), p.log);
      m.bonds.intact.changed();
      std::sort(p.log.broken.begin(), p.log.broken.end());
    };
    Pass a, z;
    dilatation(with, true, a);
    dilatation(without, false, z);
    EXPECT_GT(a.log.broken.size(), 0u);
    EXPECT_EQ(a.log.broken, z.log.broken);
    EXPECT_TRUE(same_bits(with.dilatation, without.dilatation));
    EXPECT_TRUE(same_bits(a.coupling, z.coupling));
    EXPECT_TRUE(same_bits(a.smallest, z.smallest));
    EXPECT_TRUE(with.bonds.intact == without.bonds.intact);
    auto forces = [&](rift::pd::Model<3>& m, bool bits) {
      rift::pd::RowStates rows = rift::pd::whole_rows(m.bonds, body);
      if (!bits) rows.intact = nullptr;
      rift::pd::state_based_forces<3, Influence::constant, false>(m, body, 0.0, &rows);
    };
    forces(with, true);
    forces(without, false);
    EXPECT_TRUE(same_bits(with.force, without.force)) << "surface correction " << corrected;
  }
}

// (10) A block with LAMMPS's partial volumes (122 offsets, two words of bits) and with the default
// (250, four words), bonds broken by hand and by a dilatation pass: every particle's damage from
// summarize_and_update_damage equals 1 - sum(intact V) / sum(V) over its row in the row's order
// (Silling and Askari 2005, eq. 25), the same bits, rows of the whole family and rows at the
// surface alike; the broken directed bonds are those counted from the states.
TEST(BondRuns, HistoryDamageFromTheKeptRowsEqualsTheRowsSums) {
  for (const bool lammps : {true, false}) {
    std::string scene = block_scene(3, false, "lps");
    if (lammps) scene.replace(scene.find("horizon = 3.015\n"), 16, "horizon = 3.0\npartial_volume = \"lammps\"\n");
    scene.replace(scene.find("max = [0.014, 0.011, 0.009]"), 27, "max = [0.016, 0.016, 0.016]");  // rows of the whole family
    auto m = rift::pd::discretize<3>(rift::scene::parse_string(scene, "block.toml"));
    deform_and_break(m);
    auto& b = m.bonds;
    for (auto k = b.offset[7]; k < b.offset[8]; ++k) {  // a row all broken, both entries of each bond
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      b.intact.set(k, rift::pd::bond_broken);
      for (auto q = b.offset[j]; q < b.offset[j + 1]; ++q)
        if (b.neighbor[q] == 7) b.intact.set(q, rift::pd::bond_broken);
    }
    const auto& body = m.bodies[0];
    rift::pd::lps_dilatation<3, rift::scene::Influence::constant>(m, body);  // breaks more; the rows kept as it leaves them
    ASSERT_EQ(b.kept_rows.made.size(), 1u);
    ASSERT_EQ(b.kept_rows.made[0].version, b.intact.version());
    std::vector<double> expected(m.size());
    double failed = 0.0;
    std::size_t partial_whole_family = 0, partial_surface = 0;
    for (std::size_t i = 0; i < m.size(); ++i) {
      double all = 0.0, intact = 0.0;
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const double v = b.families[b.family[static_cast<std::size_t>(k)]].volume;
        all += v;
        if (b.intact[static_cast<std::size_t>(k)] == rift::pd::bond_intact) intact += v;
        else failed += 1.0;
      }
      expected[i] = 1.0 - intact / all;
      if (expected[i] > 0.0 && expected[i] < 1.0)
        ++(static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]) == body.family_count ? partial_whole_family : partial_surface);
    }
    EXPECT_GT(partial_whole_family, 20u);
    EXPECT_GT(partial_surface, 20u);
    EXPECT_EQ(expected[7], 1.0);
    const auto e = rift::pd::summarize_and_update_damage<3>(m, false);
    EXPECT_EQ(e.failed_directed, failed) << "lammps " << lammps;
    EXPECT_TRUE(same_bits(m.damage, expected)) << "lammps " << lammps;
  }
}
