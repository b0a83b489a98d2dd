// Kinetic and strain energy of the material points.
#pragma once
#include "rift/mpm/model.hpp"
#include "rift/parallel/ordered_sum.hpp"

namespace rift::mpm {

struct EnergySummary {
  double kinetic = 0.0, strain = 0.0;
};

template <int D>
EnergySummary summarize(const Model<D>& m) {
  const auto& ps = m.particles;
  auto sums = parallel::ordered_sums<2>(ps.size(), [&](std::size_t p, std::array<double, 2>& acc) {
    acc[0] += 0.5 * ps.mass[p] * dot<D>(ps.velocity[p], ps.velocity[p]);
    acc[1] += ps.volume[p] * material::strain_energy_density<D>(m.bodies[ps.body[p]].constants, ps.state[p],
                                                                ps.deformation_gradient[p]);
  });
  return {sums[0], sums[1]};
}

}  // namespace rift::mpm
