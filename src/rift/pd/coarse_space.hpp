// A coarse space for the in-situ stage's conjugate gradients (static_equilibrium.cpp): the two-level
// additive preconditioner M^-1 = D^-1 + P (P^T K P)^-1 P^T (Nicolaides 1987; Toselli and Widlund 2005,
// section 2.3; P by unsmoothed aggregation, Vanek, Mandel and Brezina 1996). Aggregates are cubes of
// edge H; P moves an aggregate's particles together (one coarse unknown per aggregate and axis). The
// coarse solve takes out the smooth modes, so the iterations go as H over the spacing instead of as the
// lattice's sites along the body.
// K_c = P^T K P is assembled by probing the forces, 3^D colours of aggregates times D axes, which needs
// H > 2 horizons (K couples particles up to two horizons apart). Its entries and the coarse right-hand
// sides are sums in fixed point (parallel/fixed_point_sums.hpp): their bits depend neither on the order
// of the particles nor on the ranks' cut. K_c is factored once (sparse LDL^T, Eigen's SimplicialLDLT,
// nested dissection order) at the first base of the Newton steps.
// Why: docs/decisions/method-notes.md.
#pragma once
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rift/core/index_range.hpp"
#include "rift/core/vec.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/parallel/fixed_point_sums.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

template <int D>
class CoarseSpace {
 public:
  static constexpr std::uint32_t none = 0xffffffffu;
  static constexpr int colours = D == 2 ? 9 : 27;  // also the neighbour slots of an aggregate

  /// Groups the particles at reference positions x into aggregates of edge `edge`, numbered in
  /// the order of their cells on the grid from the body's lowest corner. False where the body spans
  /// fewer than three aggregates on an axis (no coarse space: the diagonal alone serves). A
  /// distributed run's window (pd/window.hpp) gives its owned ranges (none: every particle) and
  /// the ranks' communicator: the aggregates are the whole body's on every rank, and
  /// every sum over particles (assemble, solve) adds every rank's owned particles' terms.
  bool make_aggregates(const std::vector<Vec<D>>& x, double edge, const parallel::Communicator& comm = parallel::Communicator::one(),
                       const std::vector<IndexRange>& owned = {}) {
    const std::size_t n = x.size();
    comm_ = &comm, owned_ = owned.empty() ? std::vector<IndexRange>{{0, x.size()}} : owned;
    if (!(edge > 0.0)) return false;
    Vec<D> low, high;
    for (int k = 0; k < D; ++k) low[k] = 1e300, high[k] = -1e300;
    for (const IndexRange& r : owned_)
      for (std::size_t i = r.first; i < r.last; ++i)
        for (int k = 0; k < D; ++k) low[k] = std::min(low[k], x[i][k]), high[k] = std::max(high[k], x[i][k]);
    for (int k = 0; k < D; ++k) low[k] = comm.min(low[k]), high[k] = comm.max(high[k]);
    if (!(low[0] <= high[0])) return false;  // no particle
    for (int k = 0; k < D; ++k) {
      cells_[k] = static_cast<std::int64_t>(std::floor((high[k] - low[k]) / edge)) + 1;
      if (cells_[k] < 3) return false;
    }
    std::size_t grid = 1;
    for (int k = 0; k < D; ++k) grid *= static_cast<std::size_t>(cells_[k]);
    auto cell_of = [&](const Vec<D>& p) {
      std::array<std::int64_t, D> c;
      for (int k = 0; k < D; ++k) c[k] = std::min(cells_[k] - 1, static_cast<std::int64_t>(std::floor((p[k] - low[k]) / edge)));
      return grid_index(c);
    };
    // the cells that hold a particle, every rank's owned ones, in grid order
    std::vector<std::uint64_t> occupied;
    for (const IndexRange& r : owned_)
      for (std::size_t i = r.first; i < r.last; ++i) occupied.push_back(cell_of(x[i]));
    auto sort_unique = [](std::vector<std::uint64_t>& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    sort_unique(occupied);
    if (comm.distributed()) occupied = comm.all_gather(occupied), sort_unique(occupied);
    of_cell_.assign(grid, none);
    cell_.clear();
    for (const std::uint64_t g : occupied) {
      of_cell_[g] = static_cast<std::uint32_t>(cell_.size());
      std::array<std::int64_t, D> c;
      std::uint64_t rest = g;
      for (int k = 0; k < D; ++k) c[k] = static_cast<std::int64_t>(rest % static_cast<std::uint64_t>(cells_[k])), rest /= static_cast<std::uint64_t>(cells_[k]);
      cell_.push_back(c);
    }
    aggregate_.resize(n);
    for (std::size_t i = 0; i < n; ++i) aggregate_[i] = of_cell_[cell_of(x[i])];
    blocks_.assign(cell_.size() * colours * D * D, 0.0);
    return true;
  }

  std::size_t aggregates() const { return cell_.size(); }
  std::uint32_t aggregate_of(std::size_t i) const { return aggregate_[i]; }
  int colour_of(std::uint32_t a) const {
    int c = 0, scale = 1;
    for (int k = 0; k < D; ++k) c += static_cast<int>(cell_[a][k] % 3) * scale, scale *= 3;
    return c;
  }

  /// Assembles K_c and factors it: for each colour and axis, stiffness_times(direction) applies K to
  /// the displacement direction(i) (a unit along the axis on that colour's aggregates, zero on held
  /// components) and returns the force response r(i) (N per unit displacement; zero on held
  /// components), which goes to K_c's block of (i's aggregate, that colour's aggregate among its
  /// neighbours), summed over the owned particles in fixed point (parallel/fixed_point_sums.hpp: the
  /// same bits on any number of ranks). False if the factorization fails.
  template <class Held, class StiffnessTimes>
  bool assemble(Held&& held, StiffnessTimes&& stiffness_times) {
    const std::size_t count = cell_.size();
    for (int colour = 0; colour < colours; ++colour)
      for (int axis = 0; axis < D; ++axis) {
        auto response = stiffness_times([&](std::size_t i) {
          Vec<D> u{};
          const std::uint32_t a = aggregate_[i];
          if (a != none && colour_of(a) == colour && !held(i, axis)) u[axis] = 1.0;
          return u;
        });
        // K_c's column (colour, axis): for each aggregate, its block with that colour's neighbour
        const auto column = sum_over_aggregates([&](std::size_t i) { return slot_of(aggregate_[i], colour) >= 0; }, response);
        for (std::size_t a = 0; a < count; ++a) {
          const int slot = slot_of(static_cast<std::uint32_t>(a), colour);
          if (slot < 0) continue;
          double* block = &blocks_[((a * colours + static_cast<std::size_t>(slot)) * D) * D];
          for (int row = 0; row < D; ++row) block[row * D + axis] = column[a * D + static_cast<std::size_t>(row)];
        }
      }
    return factor();
  }
  /// K_c as assembled (symmetrized, with the small diagonal factor() adds).
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

  /// Factors K_c (symmetrized; with 1e-10 of its largest diagonal added, for a free body's rigid
  /// translations, which the caller projects out).
  bool factor() {
    const std::size_t count = cell_.size();
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(blocks_.size());
    double largest = 0.0;
    for (std::size_t a = 0; a < count; ++a)
      for (int slot = 0; slot < colours; ++slot) {
        std::array<std::int64_t, D> c;
        int scale = 1;
        bool inside = true;
        for (int k = 0; k < D; ++k) {
          c[k] = cell_[a][k] + (slot / scale) % 3 - 1, scale *= 3;
          inside = inside && c[k] >= 0 && c[k] < cells_[k];
        }
        if (!inside) continue;
        const std::uint32_t b = of_cell_[grid_index(c)];
        if (b == none) continue;
        const double* block = &blocks_[((a * colours + static_cast<std::size_t>(slot)) * D) * D];
        for (int row = 0; row < D; ++row)
          for (int col = 0; col < D; ++col) {
            const auto r = static_cast<Eigen::Index>(a * D + static_cast<std::size_t>(row));
            const auto q = static_cast<Eigen::Index>(std::size_t{b} * D + static_cast<std::size_t>(col));
            entries.emplace_back(r, q, 0.5 * block[row * D + col]);
            entries.emplace_back(q, r, 0.5 * block[row * D + col]);
            if (r == q) largest = std::max(largest, block[row * D + col]);
          }
      }
    const auto size = static_cast<Eigen::Index>(count * D);
    for (Eigen::Index r = 0; r < size; ++r) entries.emplace_back(r, r, 1e-10 * largest);
    matrix_.resize(size, size);
    matrix_.setFromTriplets(entries.begin(), entries.end());
    const std::vector<std::uint32_t> order = dissection_order();
    dissection_.resize(size);
    for (std::size_t k = 0; k < order.size(); ++k)
      for (int axis = 0; axis < D; ++axis)
        dissection_.indices()[static_cast<Eigen::Index>(std::size_t{order[k]} * D + static_cast<std::size_t>(axis))] =
            static_cast<int>(k * D + static_cast<std::size_t>(axis));
    Eigen::SparseMatrix<double> ordered;
    ordered = matrix_.twistedBy(dissection_);
    solver_.compute(ordered);
    blocks_.clear();
    blocks_.shrink_to_fit();
    ready_ = solver_.info() == Eigen::Success && largest > 0.0;
    return ready_;
  }
  bool ready() const { return ready_; }

  /// The aggregates in nested dissection order (George 1973), found from the grid of cells: the box
  /// of cells is cut across its longest axis at the middle plane, the two halves are numbered first
  /// (recursively) and the plane last. K_c's LDL^T then fills far less than under Eigen's minimum
  /// degree ordering: the thesis-size coarse space (12,167 aggregates) factors in a quarter of the
  /// time, with L of 21 million entries instead of 35.
  std::vector<std::uint32_t> dissection_order() const {
    std::vector<std::uint32_t> order;
    order.reserve(cell_.size());
    std::array<std::int64_t, D> low{}, high = cells_;
    dissect(low, high, order);
    return order;
  }

  /// u_c = K_c^-1 P^T y, y(i) a particle's force (N; zero on held components); P^T y summed over
  /// the owned particles in fixed point (the same bits on any number of ranks).
  template <class Y>
  const Eigen::VectorXd& solve(Y&& y) {
    const auto sums = sum_over_aggregates([](std::size_t) { return true; }, y);
    rhs_.resize(static_cast<Eigen::Index>(sums.size()));
    for (std::size_t q = 0; q < sums.size(); ++q) rhs_[static_cast<Eigen::Index>(q)] = sums[q];
    solution_ = dissection_.transpose() * solver_.solve(dissection_ * rhs_);
    return solution_;
  }
  /// (P u_c)(i), the coarse solution at particle i (before its held components are zeroed).
  Vec<D> at(std::size_t i) const {
    Vec<D> u{};
    const std::uint32_t a = aggregate_[i];
    if (a == none) return u;
    for (int k = 0; k < D; ++k) u[k] = solution_[static_cast<Eigen::Index>(std::size_t{a} * D + static_cast<std::size_t>(k))];
    return u;
  }

 private:
  /// The slot among aggregate a's neighbours of the aggregate of this colour; -1 where that cell is
  /// off the grid or empty.
  int slot_of(std::uint32_t a, int colour) const {
    if (a == none) return -1;
    int slot = 0, scale = 1;
    std::array<std::int64_t, D> c;
    for (int k = 0; k < D; ++k) {
      const std::int64_t want = (colour / scale) % 3;
      std::int64_t o = -1;
      for (; o <= 1; ++o)
        if (((cell_[a][k] + o) % 3 + 3) % 3 == want) break;
      c[k] = cell_[a][k] + o;
      if (c[k] < 0 || c[k] >= cells_[k]) return -1;
      slot += static_cast<int>(o + 1) * scale, scale *= 3;
    }
    return of_cell_[grid_index(c)] == none ? -1 : slot;
  }
  /// dissection_order's recursion over the box of cells [low, high).
  void dissect(const std::array<std::int64_t, D>& low, const std::array<std::int64_t, D>& high, std::vector<std::uint32_t>& order) const {
    int longest = 0;
    for (int k = 0; k < D; ++k) {
      if (high[k] <= low[k]) return;
      if (high[k] - low[k] > high[longest] - low[longest]) longest = k;
    }
    if (high[longest] - low[longest] < 3) {  // a few cells: in grid order
      std::array<std::int64_t, D> c = low;
      while (true) {
        const std::uint32_t a = of_cell_[grid_index(c)];
        if (a != none) order.push_back(a);
        int k = 0;
        for (; k < D; ++k) {
          if (++c[k] < high[k]) break;
          c[k] = low[k];
        }
        if (k == D) return;
      }
    }
    const std::int64_t middle = low[longest] + (high[longest] - low[longest]) / 2;
    std::array<std::int64_t, D> below_high = high, above_low = low, plane_low = low, plane_high = high;
    below_high[longest] = middle, above_low[longest] = middle + 1, plane_low[longest] = middle, plane_high[longest] = middle + 1;
    dissect(low, below_high, order);
    dissect(above_low, high, order);
    dissect(plane_low, plane_high, order);
  }

  /// sum_{i in aggregate a, counts(i)} value(i) over every rank's owned particles, per aggregate and
  /// axis (D values per aggregate), in fixed point. The threads add their shares of the particles
  /// into sums of their own, merged after (integers: the same bits on any number of threads).
  template <class Counts, class Value>
  std::vector<double> sum_over_aggregates(Counts&& counts, Value&& value) const {
    std::vector<Vec<D>>& values = values_;  // read below only where written
    values.resize(aggregate_.size());
    double largest = 0.0;
    for (const IndexRange& r : owned_) {
#pragma omp parallel for if(rift::parallel::worth_a_team(r.last - r.first)) schedule(static) reduction(max : largest)
      for (std::size_t i = r.first; i < r.last; ++i) {
        if (aggregate_[i] == none || !counts(i)) continue;
        const Vec<D> v = value(i);
        values[i] = v;
        for (int k = 0; k < D; ++k) largest = std::max(largest, std::abs(v[k]));
      }
    }
    largest = comm_->max(largest);
    parallel::FixedPointSums sums(cell_.size() * D, largest);
    std::size_t particles = 0;
    for (const IndexRange& r : owned_) particles += r.last - r.first;
#pragma omp parallel if(rift::parallel::worth_a_team(particles))
    {
      parallel::FixedPointSums share(cell_.size() * D, largest);
      for (const IndexRange& r : owned_) {
#pragma omp for schedule(static) nowait
        for (std::size_t i = r.first; i < r.last; ++i) {
          if (aggregate_[i] == none || !counts(i)) continue;
          for (int k = 0; k < D; ++k) share.add(std::size_t{aggregate_[i]} * D + static_cast<std::size_t>(k), values[i][k]);
        }
      }
#pragma omp critical(rift_coarse_space_sums)
      sums.merge(share);
    }
    sums.add_over(*comm_);
    std::vector<double> out(sums.size());
    for (std::size_t q = 0; q < out.size(); ++q) out[q] = sums[q];
    return out;
  }

  std::size_t grid_index(const std::array<std::int64_t, D>& c) const {
    std::size_t g = 0, scale = 1;
    for (int k = 0; k < D; ++k) g += static_cast<std::size_t>(c[k]) * scale, scale *= static_cast<std::size_t>(cells_[k]);
    return g;
  }
  std::array<std::int64_t, D> cells_{};
  std::vector<std::uint32_t> aggregate_, of_cell_;
  std::vector<std::array<std::int64_t, D>> cell_;
  std::vector<double> blocks_;  // per aggregate, neighbour slot: the D x D block of K_c
  mutable std::vector<Vec<D>> values_;  // sum_over_aggregates's terms per particle, kept between calls
  const parallel::Communicator* comm_ = &parallel::Communicator::one();
  std::vector<IndexRange> owned_;  // the particles whose terms this rank adds
  Eigen::SparseMatrix<double> matrix_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> dissection_;  // an aggregate's unknowns to their place in it
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> solver_;  // of K_c in that order
  Eigen::VectorXd rhs_, solution_;
  bool ready_ = false;
};

}  // namespace rift::pd
