// State of a material point run: material points (SoA) and the background grid.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/material/constitutive.hpp"
#include "rift/mpm/shape_functions.hpp"

namespace rift::mpm {

template <int D>
using Tensor = material::Tensor<D>;

template <int D>
struct Particles {
  std::vector<Vec<D>> position, reference_position, velocity;
  std::vector<Vec<D>> external_force;  // N: tractions and body forces of the step
  std::vector<double> mass, volume, reference_volume;
  std::vector<Tensor<D>> deformation_gradient;  // F
  std::vector<Tensor<D>> affine_velocity;       // APIC C_p (zero for FLIP/PIC)
  std::vector<material::State<D>> state;
  std::vector<std::uint32_t> body;
  std::size_t size() const { return position.size(); }
};

/// Regular background grid: node (i, j, k) sits at origin + h (i, j, k) + h offset. Every node carries
/// `fields` velocity fields (one per body with multi-material contact, else one); the quantities of
/// field f at node n are at slot n * fields + f.
template <int D>
struct Grid {
  Vec<D> origin{};
  double cell_size = 0.0;
  std::array<long, 3> nodes{1, 1, 1};  // per axis
  int fields = 1;
  /// A distributed run's part of the whole grid (mpm/domain.hpp): the whole grid's index of node
  /// (0, 0, 0) along each axis; 0 for the whole grid, the one a checkpoint holds.
  std::array<long, 3> offset{0, 0, 0};
  std::vector<double> mass;
  std::vector<Vec<D>> momentum, force, velocity, velocity_start;  // velocity_start: before the force update
  std::vector<Vec<D>> mass_gradient;  // sum m_p grad S_ip per field (contact normals; empty with one field)
  std::vector<double> volume;         // sum V_p S_ip per field (contact detection; empty with one field)
  std::vector<Vec<D>> displacement;   // sum m_p u_p S_ip per field (crack contact detection; empty with one field)

  std::size_t size() const { return static_cast<std::size_t>(nodes[0] * nodes[1] * nodes[2]); }
  std::size_t slots() const { return size() * static_cast<std::size_t>(fields); }
  std::size_t index(long i, long j, long k) const { return index(nodes, i, j, k); }
  /// The same for a copy of `nodes` (a loop that stores through pointers that may alias the grid
  /// keeps its copy in registers, mpm/stencil.hpp).
  static std::size_t index(const std::array<long, 3>& nodes, long i, long j, long k) {
    return static_cast<std::size_t>((k * nodes[1] + j) * nodes[0] + i);
  }
  Vec<D> node_position(std::size_t n) const {
    Vec<D> x;
    long rest = static_cast<long>(n);
    const long i = rest % nodes[0];
    rest /= nodes[0];
    const long j = rest % nodes[1];
    const long k = rest / nodes[1];
    const long ijk[3] = {i, j, k};
    for (int a = 0; a < D; ++a) x[a] = origin[a] + cell_size * double(ijk[a] + offset[a]);
    return x;
  }
  void resize() {
    const std::size_t n = slots();
    mass.assign(n, 0.0);
    momentum.assign(n, Vec<D>{});
    force.assign(n, Vec<D>{});
    velocity.assign(n, Vec<D>{});
    velocity_start.assign(n, Vec<D>{});
    mass_gradient.assign(fields > 1 ? n : 0, Vec<D>{});
    volume.assign(fields > 1 ? n : 0, 0.0);
    displacement.assign(fields > 1 ? n : 0, Vec<D>{});
  }
};

struct BodyInfo {
  std::string name;
  std::size_t first = 0, last = 0;
  material::Constants constants;
};

template <int D>
struct Model {
  Particles<D> particles;
  Grid<D> grid;
  std::vector<BodyInfo> bodies;
  ShapeKind shape = ShapeKind::bspline2;
  double particle_half_width = 0.0;  // uGIMP l (half the particle spacing)
  double thickness = 1.0;            // 2D: out-of-plane thickness in the particle volumes and masses, m
  double time = 0.0;
};

}  // namespace rift::mpm
