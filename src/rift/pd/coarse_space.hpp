// A coarse space for the in-situ stage's conjugate gradients (static_equilibrium.cpp): the two-level
// additive preconditioner M^-1 = D^-1 + P (P^T K P)^-1 P^T (Nicolaides 1987; Toselli and Widlund
// 2005, section 2.3; P by unsmoothed aggregation, Vanek, Mandel and Brezina 1996). The particles are
// grouped into cubes of edge H (aggregates), and P moves an aggregate's particles together: one
// coarse unknown per aggregate and axis. A diagonal preconditioner leaves the smooth modes, whose
// stiffness over the diagonal is of order (spacing / body)^2, to the iterations, which then go as the
// lattice's sites along the body; the coarse solve takes them out, and the iterations go as H over
// the spacing instead.
//
// The coarse operator K_c = P^T K P is assembled by probing the forces, 3^D colours of aggregates
// times D axes: K couples particles up to two horizons apart (a state-based force reads both ends'
// dilatations), so with H > 2 horizons the aggregates of one colour (two aggregates apart) reach no
// particle together, and a particle's response to a colour's probe comes from the one aggregate of
// that colour among its own and its 3^D - 1 neighbours. K_c is factored once (sparse LDL^T,
// Eigen's SimplicialLDLT) at the first base of the Newton steps: the geometric terms the later bases
// change are of the order of the strain.
#pragma once
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rift/core/vec.hpp"

namespace rift::pd {

template <int D>
class CoarseSpace {
 public:
  static constexpr std::uint32_t none = 0xffffffffu;
  static constexpr int colours = D == 2 ? 9 : 27;  // also the neighbour slots of an aggregate

  /// Groups the particles at reference positions x into aggregates of edge `edge`. False where the
  /// body spans fewer than three aggregates on an axis (no coarse space: the diagonal alone serves).
  bool make_aggregates(const std::vector<Vec<D>>& x, double edge) {
    const std::size_t n = x.size();
    if (n == 0 || !(edge > 0.0)) return false;
    Vec<D> low, high;
    for (int k = 0; k < D; ++k) low[k] = 1e300, high[k] = -1e300;
    for (const auto& p : x)
      for (int k = 0; k < D; ++k) low[k] = std::min(low[k], p[k]), high[k] = std::max(high[k], p[k]);
    for (int k = 0; k < D; ++k) {
      cells_[k] = static_cast<std::int64_t>(std::floor((high[k] - low[k]) / edge)) + 1;
      if (cells_[k] < 3) return false;
    }
    std::size_t grid = 1;
    for (int k = 0; k < D; ++k) grid *= static_cast<std::size_t>(cells_[k]);
    std::vector<std::uint32_t> of_cell(grid, none);
    aggregate_.assign(n, none);
    cell_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      std::array<std::int64_t, D> c;
      for (int k = 0; k < D; ++k) c[k] = std::min(cells_[k] - 1, static_cast<std::int64_t>(std::floor((x[i][k] - low[k]) / edge)));
      const std::size_t g = grid_index(c);
      if (of_cell[g] == none) of_cell[g] = static_cast<std::uint32_t>(cell_.size()), cell_.push_back(c);
      aggregate_[i] = of_cell[g];
    }
    of_cell_ = std::move(of_cell);
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
  /// neighbours). False if the factorization fails.
  template <class Held, class StiffnessTimes>
  bool assemble(std::size_t n, Held&& held, StiffnessTimes&& stiffness_times) {
    for (int colour = 0; colour < colours; ++colour)
      for (int axis = 0; axis < D; ++axis) {
        auto response = stiffness_times([&](std::size_t i) {
          Vec<D> u{};
          const std::uint32_t a = aggregate_[i];
          if (a != none && colour_of(a) == colour && !held(i, axis)) u[axis] = 1.0;
          return u;
        });
        for (std::size_t i = 0; i < n; ++i) add_response(i, colour, axis, response(i));
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
    solver_.compute(matrix_);
    blocks_.clear();
    blocks_.shrink_to_fit();
    ready_ = solver_.info() == Eigen::Success && largest > 0.0;
    return ready_;
  }
  bool ready() const { return ready_; }

  /// u_c = K_c^-1 P^T y, y(i) a particle's force (N; zero on held components); a sum in particle
  /// order.
  template <class Y>
  const Eigen::VectorXd& solve(std::size_t n, Y&& y) {
    rhs_.setZero(static_cast<Eigen::Index>(cell_.size() * D));
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t a = aggregate_[i];
      if (a == none) continue;
      const Vec<D> f = y(i);
      for (int k = 0; k < D; ++k) rhs_[static_cast<Eigen::Index>(std::size_t{a} * D + static_cast<std::size_t>(k))] += f[k];
    }
    solution_ = solver_.solve(rhs_);
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
  void add_response(std::size_t i, int colour, int axis, const Vec<D>& r) {
    const std::uint32_t a = aggregate_[i];
    if (a == none) return;
    int slot = 0, scale = 1;
    std::array<std::int64_t, D> c;
    for (int k = 0; k < D; ++k) {
      const std::int64_t want = (colour / scale) % 3;
      std::int64_t o = -1;
      for (; o <= 1; ++o)
        if (((cell_[a][k] + o) % 3 + 3) % 3 == want) break;
      c[k] = cell_[a][k] + o;
      if (c[k] < 0 || c[k] >= cells_[k]) return;
      slot += static_cast<int>(o + 1) * scale, scale *= 3;
    }
    if (of_cell_[grid_index(c)] == none) return;
    double* block = &blocks_[((static_cast<std::size_t>(a) * colours + static_cast<std::size_t>(slot)) * D) * D];
    for (int row = 0; row < D; ++row) block[row * D + axis] += r[row];
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
  Eigen::SparseMatrix<double> matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  Eigen::VectorXd rhs_, solution_;
  bool ready_ = false;
};

}  // namespace rift::pd
