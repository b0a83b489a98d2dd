// The shape functions of every material point for one step. Every transfer of an explicit MPM step
// (particles to grid, grid to particles, MUSL's remap of the new momenta and the stress update) uses S_ip
// and grad S_ip at the point's position at the start of the step, x_p^n (Sulsky et al. 1994), so they are
// taken once per step (stencil.hpp) and read by each transfer. Memory: support(shape)^D nodes per point,
// each its index (32 bits), weight and gradient (2D quadratic B-splines: 9 x 28 bytes). The products are
// stored, not formed in the transfers from each axis' 1D factors.
// Why, and what was measured: docs/decisions/method-notes.md and bench/README.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rift/mpm/shape_functions.hpp"
#include "rift/mpm/stencil.hpp"
#include "rift/parallel/shared_blocks.hpp"

namespace rift::mpm {

template <int D>
class StencilCache {
 public:
  /// Node numbers are 32-bit: discretize refuses grids with more nodes than this holds.
  using NodeIndex = std::uint32_t;

  /// One point's stencil, read in place: the members a Stencil<D> has, as pointers into the cache.
  struct View {
    int count = 0;
    const NodeIndex* node = nullptr;
    const double* weight = nullptr;
    const Vec<D>* gradient = nullptr;
  };

  /// Takes every point's stencil at positions[p], and copies the positions to *taken_at when given;
  /// a point whose stencil reaches past the grid raises a PhysicsError (stencil.hpp) after the loop.
  void fill(const Model<D>& m, const std::vector<Vec<D>>& positions, std::vector<Vec<D>>* taken_at = nullptr) {
    int nodes = 1;
    for (int a = 0; a < D; ++a) nodes *= support(m.shape);
    stride_ = static_cast<std::size_t>(nodes);
    const std::size_t n = positions.size();
    count_.resize(n);
    node_.resize(n * stride_);
    weight_.resize(n * stride_);
    gradient_.resize(n * stride_);
    if (taken_at) taken_at->resize(n);
    LostParticle lost;
    with_shape(m.shape, [&](auto shape) {
      rift::parallel::for_each_in_shared_blocks(n, [&](std::size_t p) {
        if (taken_at) (*taken_at)[p] = positions[p];
        const std::size_t base = p * stride_;
        const int count =
            make_stencil<decltype(shape)::value, D>(m, positions[p], node_.data() + base, weight_.data() + base, gradient_.data() + base);
        count_[p] = static_cast<std::uint8_t>(count);
        if (count == 0) lost.record(p);
      });
    });
    lost.raise(m.time);
  }

  View operator[](std::size_t p) const {
    const std::size_t base = p * stride_;
    return {count_[p], node_.data() + base, weight_.data() + base, gradient_.data() + base};
  }
  std::size_t size() const { return count_.size(); }

 private:
  std::size_t stride_ = 0;
  std::vector<std::uint8_t> count_;
  std::vector<NodeIndex> node_;
  std::vector<double> weight_;
  std::vector<Vec<D>> gradient_;
};

/// Runs body(p, stencil) for every point of the cache in parallel, or on the calling thread alone
/// for a few points (parallel/team.hpp). body must compute each point alone. Every pass over the
/// points in a step gives each thread the same block first (the scatter's, solver.cpp), so a
/// point's data stays in the cache of the core that used it last; a thread done early takes over
/// the rest of another's (parallel/shared_blocks.hpp). A dynamic schedule would move the blocks
/// between cores from pass to pass, and cost two threads their gain over one (bench/README.md).
template <int D, class Body>
void for_each_cached_stencil(const StencilCache<D>& cache, Body body) {
  rift::parallel::for_each_in_shared_blocks(cache.size(), [&](std::size_t p) { body(p, cache[p]); });
}

}  // namespace rift::mpm
