// The small strain of the material around a particle, from its intact bonds: the correspondence
// deformation gradient (Silling et al. 2007, sec. 18, eqs. 131-132)
//   F = (sum_j omega V_j eta (x) xi) K^-1,  K = sum_j omega V_j xi (x) xi  (the shape tensor),
// over the bonds that still carry the rock's force (broken bonds and failed interface bonds are
// left out), and eps = (F + F^T) / 2 - I. Beside a pre-existing fracture this is the strain of the
// rock on the particle's own side: a bond across the fracture stretches by eps xi with the rock
// around it, and only what it stretches beyond that is the jump across the fracture's faces
// (interface_contact.hpp interface_opening).
#pragma once
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
  const auto& c = m.constants_of(i);
  const Bonds& b = m.bonds;
  double K[D][D] = {}, N[D][D] = {};
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
    if (b.intact[k] != bond_intact) continue;
    const auto j = static_cast<std::size_t>(b.neighbor[k]);
    const double w = influence(c.influence, b.length[k], c.horizon) * b.volume[k];
    for (int p = 0; p < D; ++p)
      for (int q = 0; q < D; ++q) {
        const double xi_q = m.reference_position[j][q] - m.reference_position[i][q];
        K[p][q] += w * (m.reference_position[j][p] - m.reference_position[i][p]) * xi_q;
        N[p][q] += w * (m.position[j][p] - m.position[i][p]) * xi_q;
      }
  }
  double inverse[D][D] = {};
  double det;
  if constexpr (D == 2) {
    det = K[0][0] * K[1][1] - K[0][1] * K[1][0];
    inverse[0][0] = K[1][1], inverse[0][1] = -K[0][1], inverse[1][0] = -K[1][0], inverse[1][1] = K[0][0];
  } else {
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) {  // cofactor transpose
        const int p1 = (q + 1) % 3, p2 = (q + 2) % 3, q1 = (p + 1) % 3, q2 = (p + 2) % 3;
        inverse[p][q] = K[p1][q1] * K[p2][q2] - K[p1][q2] * K[p2][q1];
      }
    det = K[0][0] * inverse[0][0] + K[0][1] * inverse[1][0] + K[0][2] * inverse[2][0];
  }
  std::array<double, 9> eps{};
  double scale = 0.0;  // the shape tensor's size, to judge its determinant against
  for (int p = 0; p < D; ++p) scale += K[p][p];
  if (!(std::abs(det) > 1e-8 * std::pow(scale / D, D))) return eps;
  double F[D][D] = {};
  for (int p = 0; p < D; ++p)
    for (int q = 0; q < D; ++q)
      for (int r = 0; r < D; ++r) F[p][q] += N[p][r] * inverse[r][q] / det;
  for (int p = 0; p < D; ++p)
    for (int q = 0; q < D; ++q) eps[3 * p + q] = 0.5 * (F[p][q] + F[q][p]) - (p == q ? 1.0 : 0.0);
  return eps;
}

}  // namespace rift::pd
