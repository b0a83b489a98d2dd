// The material point method's processor grid (mpm/domain.hpp CellBoxes): which grid of boxes
// `mpirun -np N` takes, and that the boxes' nodes cover what their points reach. The runs on N ranks
// themselves are tests/test_mpi.sh (within 1e-12 of one rank).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "rift/core/error.hpp"
#include "rift/mpm/domain.hpp"

namespace {

/// A grid of `nodes` (unit cells) with one point at the centre of each cell.
template <int D>
rift::mpm::Model<D> uniform_model(std::array<long, 3> nodes) {
  rift::mpm::Model<D> m;
  m.grid.cell_size = 1.0;
  m.grid.nodes = nodes;
  for (long k = 0; k < (D == 3 ? nodes[2] - 1 : 1); ++k)
    for (long j = 0; j < nodes[1] - 1; ++j)
      for (long i = 0; i < nodes[0] - 1; ++i) {
        rift::Vec<D> x{};
        x[0] = double(i) + 0.5, x[1] = double(j) + 0.5;
        if constexpr (D == 3) x[2] = double(k) + 0.5;
        m.particles.position.push_back(x);
      }
  return m;
}

// The grid chosen is the one whose cuts cross the fewest nodes: (P_a - 1) planes of the other axes'
// nodes each.
TEST(MpmProcessorGrid, CutsCrossTheFewestNodes) {
  // 60 x 20 cells on 4 ranks: 4 x 1 crosses 3 x 21 = 63 nodes, 2 x 2 crosses 21 + 61 = 82
  EXPECT_EQ(rift::mpm::cut_into_boxes<2>(uniform_model<2>({61, 21, 1}), 4, "t.toml").ranks, (std::array<int, 3>{4, 1, 1}));
  // 40 x 40 on 4: 2 x 2 crosses 82, 4 x 1 123
  EXPECT_EQ(rift::mpm::cut_into_boxes<2>(uniform_model<2>({41, 41, 1}), 4, "t.toml").ranks, (std::array<int, 3>{2, 2, 1}));
  // 8 x 8 x 16 on 4: 1 x 2 x 2 crosses 17 x 9 + 9 x 9 = 234 nodes, 1 x 1 x 4 243 (x and y take 2 at most)
  EXPECT_EQ(rift::mpm::cut_into_boxes<3>(uniform_model<3>({9, 9, 17}), 4, "t.toml").ranks, (std::array<int, 3>{1, 2, 2}));
  // 2 and 3 ranks: slabs across the longest axis, as before the grids
  EXPECT_EQ(rift::mpm::cut_into_boxes<2>(uniform_model<2>({21, 41, 1}), 3, "t.toml").ranks, (std::array<int, 3>{1, 3, 1}));
  // --cut-along x cuts x alone, --processor-grid is taken as given
  EXPECT_EQ(rift::mpm::cut_into_boxes<2>(uniform_model<2>({41, 41, 1}), 4, "t.toml", 0).ranks, (std::array<int, 3>{4, 1, 1}));
  EXPECT_EQ(rift::mpm::cut_into_boxes<3>(uniform_model<3>({9, 9, 17}), 8, "t.toml", -1, {2, 2, 2}).ranks, (std::array<int, 3>{2, 2, 2}));
}

TEST(MpmProcessorGrid, RefusesGridsThatDoNotFit) {
  const auto block = uniform_model<3>({9, 9, 17});
  // a product other than the ranks, 3 boxes of 8 cells (a box needs 4), a 2D grid's third number
  EXPECT_THROW(rift::mpm::cut_into_boxes<3>(block, 4, "t.toml", -1, {2, 2, 2}), rift::SceneError);
  EXPECT_THROW(rift::mpm::cut_into_boxes<3>(block, 3, "t.toml", -1, {3, 1, 1}), rift::SceneError);
  EXPECT_THROW(rift::mpm::cut_into_boxes<2>(uniform_model<2>({41, 41, 1}), 4, "t.toml", -1, {2, 1, 2}), rift::SceneError);
  // 8 x 8 x 16 cells hold 2 x 2 x 4 boxes at most
  EXPECT_THROW(rift::mpm::cut_into_boxes<3>(block, 32, "t.toml"), rift::SceneError);
  EXPECT_NO_THROW(rift::mpm::cut_into_boxes<3>(block, 16, "t.toml"));
}

// Every node is one rank's own (gathered once for a checkpoint), and every rank's box of nodes holds
// the nodes c - 1 .. c + 2 (clipped to the grid) of each cell c it owns: what a point there reaches
// with every shape function.
TEST(MpmProcessorGrid, OwnNodesPartitionTheGridAndBoxesHoldTheStencils) {
  const std::array<long, 3> nodes{17, 13, 21};
  const auto boxes = rift::mpm::cut_into_boxes<3>(uniform_model<3>(nodes), 12, "t.toml", -1, {2, 2, 3});
  std::vector<int> owners(static_cast<std::size_t>(nodes[0] * nodes[1] * nodes[2]), 0);
  for (int r = 0; r < boxes.size(); ++r) {
    const auto own = boxes.own_nodes(r, nodes), box = boxes.node_box(r, nodes);
    for (long k = own[2].first; k <= own[2].second; ++k)
      for (long j = own[1].first; j <= own[1].second; ++j)
        for (long i = own[0].first; i <= own[0].second; ++i) ++owners[static_cast<std::size_t>((k * nodes[1] + j) * nodes[0] + i)];
    for (long k = 0; k + 1 < nodes[2]; ++k)
      for (long j = 0; j + 1 < nodes[1]; ++j)
        for (long i = 0; i + 1 < nodes[0]; ++i) {
          const std::array<long, 3> cell{i, j, k};
          if (boxes.owner(cell) != r) continue;
          for (std::size_t a = 0; a < 3; ++a) {
            EXPECT_LE(box[a].first, std::max(0L, cell[a] - 1));
            EXPECT_GE(box[a].second, std::min(nodes[a] - 1, cell[a] + 2));
          }
        }
  }
  for (const int count : owners) EXPECT_EQ(count, 1);
  // cells past the grid belong to the ranks at its ends
  EXPECT_EQ(boxes.owner({-1, -1, -1}), 0);
  EXPECT_EQ(boxes.owner({nodes[0], nodes[1], nodes[2]}), boxes.size() - 1);
}

}  // namespace
