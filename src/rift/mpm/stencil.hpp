// Grid shape functions of one material point: the nodes it touches with weights S_ip and
// gradients grad S_ip (tensor products of the 1D functions in shape_functions.hpp).
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "rift/core/error.hpp"
#include "rift/mpm/model.hpp"

namespace rift::mpm {

template <int D>
struct Stencil {
  static constexpr int capacity = D == 3 ? 64 : 16;
  int count = 0;
  std::array<std::size_t, capacity> node{};
  std::array<double, capacity> weight{};
  std::array<Vec<D>, capacity> gradient{};
};

/// Records the first material point that left the grid inside a parallel loop (exceptions must
/// not cross an OpenMP region); raise() throws after the loop.
struct LostParticle {
  long index = -1;
  void record(std::size_t p) {
#pragma omp critical(rift_mpm_lost)
    if (index < 0 || static_cast<long>(p) < index) index = static_cast<long>(p);
  }
  void raise(double time) const {
    if (index >= 0)
      throw PhysicsError("material point " + std::to_string(index) + " left the background grid at t = " + std::to_string(time) +
                         " s; enlarge [mpm] grid_min / grid_max");
  }
};

/// Tensor-product shape functions of the particle at x: nodes, weights S_ip, gradients grad S_ip.
/// Returns false (count 0) when the particle's stencil reaches past the grid.
template <int D>
bool make_stencil(const Model<D>& m, const Vec<D>& x, Stencil<D>& st) {
  const auto& g = m.grid;
  std::array<Stencil1, 3> s;
  st.count = 0;
  for (int a = 0; a < 3; ++a) {
    if (a < D) {
      s[a] = stencil_1d(m.shape, x[a] - g.origin[a], g.cell_size, m.particle_half_width);
      s[a].first -= g.offset[a];  // the whole grid's node numbers to this rank's part of it (mpm/domain.hpp)
      if (s[a].first < 0 || s[a].first + s[a].count > g.nodes[a] || !std::isfinite(x[a])) return false;
    } else {
      s[a].first = 0, s[a].count = 1, s[a].weight = {1, 0, 0, 0}, s[a].gradient = {0, 0, 0, 0};
    }
  }
  st.count = 0;
  for (int k = 0; k < s[2].count; ++k)
    for (int j = 0; j < s[1].count; ++j)
      for (int i = 0; i < s[0].count; ++i) {
        const std::size_t q = static_cast<std::size_t>(st.count++);
        st.node[q] = g.index(s[0].first + i, s[1].first + j, s[2].first + k);
        const double wx = s[0].weight[i], wy = s[1].weight[j], wz = s[2].weight[k];
        st.weight[q] = wx * wy * wz;
        st.gradient[q][0] = s[0].gradient[i] * wy * wz;
        if constexpr (D >= 2) st.gradient[q][1] = wx * s[1].gradient[j] * wz;
        if constexpr (D == 3) st.gradient[q][2] = wx * wy * s[2].gradient[k];
      }
  return true;
}

}  // namespace rift::mpm
