// The stiffness of a model at its current positions, dense, for tests on small lattices:
// K(r, c) = -V_r dF_r / dx_c (force density F, so K is the force's derivative) by central
// differences of the forces, every coordinate moved by +-h (no contact; hold the bonds first).
#pragma once
#include <Eigen/Dense>
#include <vector>

#include "rift/pd/forces.hpp"
#include "rift/pd/model.hpp"

namespace rift::test {

template <int D>
Eigen::MatrixXd dense_stiffness(pd::Model<D>& m, double h) {
  const std::size_t N = m.size() * D;
  const auto start = m.position;
  Eigen::MatrixXd K(N, N);
  for (std::size_t c = 0; c < N; ++c) {
    std::vector<Vec<D>> f[2];
    for (int side = 0; side < 2; ++side) {
      m.position = start;
      m.position[c / D][c % D] += side == 0 ? h : -h;
      pd::compute_forces<D>(m, nullptr);
      f[side] = m.force;
    }
    for (std::size_t r = 0; r < N; ++r)
      K(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = -m.volume[r / D] * (f[0][r / D][r % D] - f[1][r / D][r % D]) / (2 * h);
  }
  m.position = start;
  return K;
}

}  // namespace rift::test
