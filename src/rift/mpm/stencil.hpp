// Grid shape functions of one material point: the nodes it touches with weights S_ip and
// gradients grad S_ip (tensor products of the 1D functions in shape_functions.hpp).
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
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

/// Tensor-product shape functions of kind Shape (m.shape) of the particle at x, written to node[q]
/// (any unsigned type that holds the grid's node numbers: the cache's are 32-bit), weight[q] and
/// gradient[q] (room for Stencil<D>::capacity): nodes, weights S_ip, gradients grad S_ip. Returns
/// the number of nodes, or 0 when the particle's stencil reaches past the grid. The 1D factors stay
/// in registers and each product is stored once where it is read from: a copy through a
/// temporary (scalar stores read back as vectors) cost two threads sharing a core more than the
/// products themselves (bench/README.md). The shape is a template argument
/// so that its node count is a constant and the loops unroll (the 2D linear beam's stencils took
/// 241 instructions a point with the kind read at run time; with_shape picks the instance).
template <ShapeKind Shape, int D, class NodeIndex>
int make_stencil(const Model<D>& m, const Vec<D>& x, NodeIndex* node, double* weight, Vec<D>* gradient) {
  const auto& g = m.grid;
  // The whole grid's node numbers to this rank's part of it (mpm/domain.hpp). Each axis' factors
  // are built in place (an array of Stencil1 is zero-filled first, a rep stos as slow as the rest).
  auto along = [&](int a) __attribute__((always_inline)) {
    Stencil1 s1 = stencil_1d(Shape, x[a] - g.origin[a], g.cell_size, m.particle_half_width);
    s1.first -= g.offset[a];
    return s1;
  };
  auto inside = [&](const Stencil1& s1, int a) { return s1.first >= 0 && s1.first + s1.count <= g.nodes[a] && std::isfinite(x[a]); };
  const Stencil1 sx = along(0), sy = along(1);
  if (!inside(sx, 0) || !inside(sy, 1)) return 0;
  Stencil1 sz;
  sz.count = 1, sz.weight[0] = 1.0;
  if constexpr (D == 3) {
    sz = along(2);
    if (!inside(sz, 2)) return 0;
  }
  // The numbering in registers: the stores below may alias m, so g.index would read it again each
  // time.
  const std::array<long, 3> nodes = g.nodes;
  int count = 0;
  for (int k = 0; k < sz.count; ++k)
    for (int j = 0; j < sy.count; ++j)
      for (int i = 0; i < sx.count; ++i, ++count) {
        const auto q = static_cast<std::size_t>(count);
        const double wx = sx.weight[i], wy = sy.weight[j], wz = sz.weight[k];
        node[q] = static_cast<NodeIndex>(Grid<D>::index(nodes, sx.first + i, sy.first + j, sz.first + k));
        weight[q] = wx * wy * wz;
        gradient[q][0] = sx.gradient[i] * wy * wz;
        gradient[q][1] = wx * sy.gradient[j] * wz;
        if constexpr (D == 3) gradient[q][2] = wx * wy * sz.gradient[k];
      }
  return count;
}

/// Calls f(std::integral_constant<ShapeKind, kind>{}): code that takes many stencils picks the
/// instance of make_stencil for the model's shape once.
template <class F>
decltype(auto) with_shape(ShapeKind kind, F&& f) {
  switch (kind) {
    case ShapeKind::linear: return f(std::integral_constant<ShapeKind, ShapeKind::linear>{});
    case ShapeKind::gimp: return f(std::integral_constant<ShapeKind, ShapeKind::gimp>{});
    case ShapeKind::bspline2: return f(std::integral_constant<ShapeKind, ShapeKind::bspline2>{});
    case ShapeKind::bspline3: break;
  }
  return f(std::integral_constant<ShapeKind, ShapeKind::bspline3>{});
}

/// The same into a Stencil<D>; false (count 0) when the particle's stencil reaches past the grid.
template <int D>
bool make_stencil(const Model<D>& m, const Vec<D>& x, Stencil<D>& st) {
  st.count = with_shape(m.shape, [&](auto shape) {
    return make_stencil<decltype(shape)::value, D>(m, x, st.node.data(), st.weight.data(), st.gradient.data());
  });
  return st.count > 0;
}

}  // namespace rift::mpm
