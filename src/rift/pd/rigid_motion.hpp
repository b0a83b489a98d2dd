// The rigid-body part of a force field over a free body: the acceleration A + alpha x (x - c) that
// the net force and torque of the forces f_i give the masses w_i (c their centre). It is the
// w-weighted projection of f_i / w_i onto the rigid motions, so f_i / w_i less it is w-orthogonal to
// every rigid motion, and f_i less w_i times it carries no net force or torque. A body held by
// tractions alone is in equilibrium only up to a rigid motion, and what the loads leave of force and
// torque cannot be taken up by any deformation: a compressed free body's rotation has a negative
// geometric stiffness under dead loads (a face's force keeps its direction while its point turns),
// so an iterative solver has to keep its iterates off these motions (dynamic_relaxation.cpp,
// static_equilibrium.cpp).
#pragma once
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/parallel/ordered_sum.hpp"

namespace rift::pd {

template <int D>
struct RigidAcceleration {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
  Vec<D> at(const Vec<D>& x) const {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int k = 0; k < D; ++k) r[k] = x[k] - centre[k];
    const Eigen::Vector3d a = linear + angular.cross(r);
    Vec<D> out;
    for (int k = 0; k < D; ++k) out[k] = a[k];
    return out;
  }
};

/// force(i): the force on particle i (N); mass(i): its mass w_i (any positive weight); position:
/// where the particles are. Sums in a fixed order (the same bits for any thread count) over the
/// `owned` ranges of `position`'s particles: with `comm`, a distributed run's owned ones
/// (pd/window.hpp), every rank's, exactly (parallel/exact_sum.hpp: the same bits as one rank);
/// without, every particle of `position`. continues(i): whether particle i is in the unit of the
/// sums of particle i - 1 (parallel/ordered_sum.hpp exact_sums; a model's lattice lines, line_of).
template <int D, class Mass, class Force, class Continues>
RigidAcceleration<D> rigid_acceleration(const std::vector<Vec<D>>& position, Mass&& mass, Force&& force, Continues&& continues,
                                        const parallel::Communicator* comm = nullptr, const std::vector<IndexRange>& owned = {}) {
  const std::vector<IndexRange> ranges = comm ? owned : std::vector<IndexRange>{{0, position.size()}};
  const auto& sums_over = comm ? *comm : parallel::Communicator::one();
  RigidAcceleration<D> out;
  auto first = parallel::exact_sums<1 + 2 * D>(sums_over, ranges, continues, [&](std::size_t i, std::array<double, 1 + 2 * D>& acc) {
    const Vec<D> f = force(i);
    const double w = mass(i);
    acc[0] += w;
    for (int k = 0; k < D; ++k) acc[1 + k] += w * position[i][k], acc[1 + D + k] += f[k];
  });
  if (!(first[0] > 0.0)) return out;
  for (int k = 0; k < D; ++k) out.centre[k] = first[1 + k] / first[0], out.linear[k] = first[1 + D + k] / first[0];
  // torque of f (3) and inertia tensor (6) of the masses about the centre
  auto second = parallel::exact_sums<9>(sums_over, ranges, continues, [&](std::size_t i, std::array<double, 9>& acc) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero(), f = r;
    const Vec<D> fi = force(i);
    for (int k = 0; k < D; ++k) r[k] = position[i][k] - out.centre[k], f[k] = fi[k];
    const Eigen::Vector3d torque = r.cross(f);
    for (int k = 0; k < 3; ++k) acc[k] += torque[k];
    const double w = mass(i), r2 = r.squaredNorm();
    acc[3] += w * (r2 - r[0] * r[0]), acc[4] += w * (r2 - r[1] * r[1]), acc[5] += w * (r2 - r[2] * r[2]);
    acc[6] -= w * r[0] * r[1], acc[7] -= w * r[1] * r[2], acc[8] -= w * r[0] * r[2];
  });
  if constexpr (D == 2) {
    if (second[5] > 0.0) out.angular[2] = second[2] / second[5];
  } else {
    Eigen::Matrix3d inertia;
    inertia << second[3], second[6], second[8], second[6], second[4], second[7], second[8], second[7], second[5];
    out.angular = inertia.ldlt().solve(Eigen::Vector3d(second[0], second[1], second[2]));
  }
  return out;
}

}  // namespace rift::pd
