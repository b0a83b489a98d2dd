// Rigid loading platens of a true tri-axial frame ([in_situ_stress] faces = "platens"), as Zhou et al.
// (2008) loaded their blocks through lubricated steel plates. A plate keeps its face flat: the face's
// particles move together along its normal and freely in its plane (no shear). On each axis the plate
// at the low end is the frame's reaction (no normal displacement), the plate at the high end the
// servo-controlled ram, pushed with the in-situ stress times the face's area whatever the face does.
// A plate is one degree of freedom: its acceleration is sum_i F_i V_i / sum_i rho_i V_i (for dynamic
// relaxation, rho the fictitious density). Each integrator updates the particles as free ones and then
// moves them with the plate (move_with_platens): the mass-weighted mean of their normal velocity and
// displacement, which is the plate's update when they moved together before (it is linear in the force).
// Why: docs/decisions/method-notes.md.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/parallel/exact_sum.hpp"

namespace rift::pd {

struct Platen {
  int axis = 0;                        // the face's normal
  std::vector<std::size_t> particles;  // the face's outermost row, ascending (a window's: those in it)
};

/// Sums of K quantities over a platen's particles, values(i) particle i's, added exactly
/// (parallel/exact_sum.hpp): one rank's bits on any number of ranks, however they own the face.
template <std::size_t K, class Model, class Values>
std::array<double, K> platen_sums(const Model& m, const Platen& p, Values&& values) {
  std::array<parallel::ExactSum, K> total;
  for (const auto i : p.particles)
    if (m.ghosts == nullptr || m.owns(i)) {
      const std::array<double, K> v = values(i);
      for (std::size_t q = 0; q < K; ++q) total[q].add(v[q]);
    }
  return parallel::rounded_over_ranks<K>(m.ghosts ? parallel::Communicator::world() : parallel::Communicator::one(), total);
}

/// Moves each platen's particles together along its axis: their velocity and displacement
/// component become the mean weighted by mass(i) (density times volume).
template <class Model, class Mass>
void move_with_platens(Model& m, Mass mass) {
  for (const Platen& p : m.platens) {
    const int k = p.axis;
    const auto [total, momentum, displacement] = platen_sums<3>(m, p, [&](std::size_t i) {
      const double w = mass(i);
      return std::array<double, 3>{w, w * m.velocity[i][k], w * (m.position[i][k] - m.reference_position[i][k])};
    });
    if (!(total > 0.0)) continue;
    for (const auto i : p.particles) {
      m.velocity[i][k] = momentum / total;
      m.position[i][k] = m.reference_position[i][k] + displacement / total;
    }
  }
}

/// Marks the components that move with a platen (bit k of the particle's entry).
template <class Model>
std::vector<std::uint8_t> platen_components(const Model& m) {
  std::vector<std::uint8_t> bits(m.size(), 0);
  for (const Platen& p : m.platens)
    for (const auto i : p.particles) bits[i] |= std::uint8_t(1u << p.axis);
  return bits;
}

}  // namespace rift::pd
