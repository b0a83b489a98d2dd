// The small strain of the material around a particle, from its intact bonds: the correspondence
// deformation gradient (Silling et al. 2007, sec. 18, eqs. 131-132)
//   F = (sum_j omega V_j eta (x) xi) K^-1,  K = sum_j omega V_j xi (x) xi  (the shape tensor),
// over the bonds that still carry the rock's force (broken bonds and failed interface bonds are
// left out), and eps = (F + F^T) / 2 - I. Beside a pre-existing fracture this is the strain of the
// rock on the particle's own side: a bond across the fracture stretches by eps xi with the rock
// around it, and only what it stretches beyond that is the jump across the fracture's faces
// (geomech/interface_contact.hpp interface_opening).
#pragma once
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstddef>

#include "rift/pd/influence.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

/// The 3 x 3 small strain of particle i, row-major (zero out of plane in 2D, and zero where the
/// intact bonds no longer span D dimensions).
template <int D>
std::array<double, 9> bulk_strain(const Model<D>& m, std::size_t i) {
  using Matrix = Eigen::Matrix<double, D, D>;
  using Vector = Eigen::Matrix<double, D, 1>;
  const auto& c = m.constants_of(i);
  const Bonds& b = m.bonds;
  Matrix K = Matrix::Zero(), N = Matrix::Zero();
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] != bond_intact) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    Vector xi, eta;
    for (int p = 0; p < D; ++p) {
      xi[p] = m.reference_position[j][p] - m.reference_position[i][p];
      eta[p] = m.position[j][p] - m.position[i][p];
    }
    const double w = influence(c.influence, b.length(k), c.horizon) * b.volume(k);
    K += w * xi * xi.transpose();
    N += w * eta * xi.transpose();
  }
  std::array<double, 9> eps{};
  // the shape tensor's determinant judged against its size
  if (!(std::abs(K.determinant()) > 1e-8 * std::pow(K.trace() / D, D))) return eps;
  const Matrix F = N * K.inverse();
  for (int p = 0; p < D; ++p)
    for (int q = 0; q < D; ++q) eps[3 * p + q] = 0.5 * (F(p, q) + F(q, p)) - (p == q ? 1.0 : 0.0);
  return eps;
}

}  // namespace rift::pd
