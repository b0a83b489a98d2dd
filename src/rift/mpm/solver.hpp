// Explicit updated-Lagrangian material point method (Sulsky et al. 1994; Bardenhagen and Kober
// 2004; Nairn 2003). One step:
//   particle-to-grid: mass, momentum (APIC: with the affine velocity), external and internal forces;
//   grid: momentum update with mass-proportional damping and the grid boundary conditions;
//   grid-to-particle: velocities (FLIP/PIC blend or APIC) and positions;
//   stress update with the velocity gradient from the grid, before the forces (USF), after the
//   grid update (USL), or after mapping the new particle momenta back to the grid (MUSL).
// Scatter to the grid goes through one buffer per thread, summed in thread order, so a run is
// bit-reproducible for a given thread count.
#pragma once
#include <optional>
#include <vector>

#include "rift/mpm/crack.hpp"
#include "rift/mpm/domain.hpp"
#include "rift/mpm/model.hpp"
#include "rift/mpm/stencil_cache.hpp"
#include "rift/parallel/shared_blocks.hpp"
#include "rift/scene/scene.hpp"

namespace rift::mpm {

template <int D>
class Solver {
 public:
  /// Selects grid nodes and particles for the scene's boundary conditions (SceneError when a region
  /// selects nothing).
  Solver(const scene::Scene& s, Model<D>& m);
  /// A distributed run (domain.hpp): from here on `part` is this rank's part of `whole`, the model
  /// the solver was made for; each step migrates its points and completes the shared nodes' sums.
  void distribute(const Model<D>& whole, const Model<D>& part, Domain<D>& domain);
  /// Largest stable step: cell size / (dilatational wave speed + fastest particle).
  double stable_time_step(const Model<D>& m) const;
  void step(Model<D>& m, double dt);
  /// Ask the next step to measure the time-centred energy at its start, t^n: kinetic
  /// 1/2 m v^{n-1/2} . v^{n+1/2} and strain U(x^n). For the explicit update (symplectic Euler, a
  /// leapfrog in disguise) this is the energy the scheme conserves; the plain 1/2 m v^2 + U at the
  /// end of a step oscillates by O(dt).
  void measure_energy() { measure_ = true; }
  struct Energy {
    double time = 0.0, kinetic = 0.0, strain = 0.0;
  };
  const Energy& measured_energy() const { return energy_; }
  /// Explicit cracks (2D), with their crack particles and surfaces moved every step.
  const CrackSet& cracks() const { return cracks_; }
  /// What lasts from one step to the next besides the model, for a checkpoint
  /// (mpm/checkpoint_state.hpp): the explicit cracks' particles and surfaces. Every other member
  /// is set up from the scene, or taken anew in each step before it is read.
  template <class A>
  void visit_state(A& a) {
    a("solver.cracks", cracks_.cracks());
  }
  /// A distributed run: the cracks rank 0 grew (every rank holds them all).
  void set_cracks(CrackSet cracks) { cracks_ = std::move(cracks); }
  /// Rank 0's solver of the whole model in a distributed run, for the crack-tip integrals
  /// (j_integral.hpp): the cracks and the points' accelerations and velocity gradients of the last
  /// step, gathered from the ranks.
  void mirror(const CrackSet& cracks, std::vector<Vec<D>> acceleration, std::vector<Tensor<D>> velocity_gradient) {
    cracks_ = cracks;
    acceleration_ = std::move(acceleration);
    velocity_gradient_ = std::move(velocity_gradient);
  }
  /// Crack propagation: a new crack particle at x beyond the given tip.
  void extend_crack(const CrackTip& tip, const Vec<2>& x) { cracks_.extend(tip, x); }
  /// With cracks: each material point's acceleration and velocity gradient in the last step (for
  /// the dynamic J-integral's area term); empty otherwise.
  const std::vector<Vec<D>>& accelerations() const { return acceleration_; }
  /// True when crack-face contact is on and the faces of crack c are closed at crack particle k by
  /// the contact test (the displacements of the two sides, extrapolated through the grid).
  bool faces_closed(const Model<D>& m, std::size_t c, std::size_t k) const;
  const std::vector<Tensor<D>>& velocity_gradients() const { return velocity_gradient_; }

 private:
  struct GridCondition {
    std::vector<std::size_t> nodes;
    std::array<std::optional<double>, 3> value;  // prescribed velocity per component (fixed: 0)
    scene::TimeFunction time;
  };
  struct ParticleLoad {
    std::vector<std::size_t> particles;
    std::vector<std::uint64_t> ids;    // the whole run's numbers of the particles (a distributed run's points migrate)
    std::array<double, 3> density{};  // force per unit volume (traction / layer depth, or body force)
    scene::TimeFunction time;
  };
  /// A scatter's work on each point before its shares: none.
  struct NoPointWork {
    void operator()(std::size_t, const typename StencilCache<D>::View&) const {}
  };
  /// Particles to grid (the sums over each node's points); see solver.cpp.
  template <class BeforePoint = NoPointWork>
  void scatter(Model<D>& m, bool momentum_only, bool internal_force, BeforePoint before_point = {});
  /// node_conditions_ of a grid of `nodes` nodes from conditions_.
  void index_conditions(std::size_t nodes);
  /// The loads' particles among this rank's points, by their whole run's numbers.
  void select_loads(const std::vector<std::uint64_t>& id);
  /// Grid velocities from the scattered momenta at time t, node by node (node_velocities);
  /// restore_stage: then the velocities grid_update kept at the nodes in contact.
  void grid_velocities(Model<D>& m, double t, bool record_start, bool contact = true, bool restore_stage = false);
  /// One node's velocities from its momenta (and velocity_start when record_start), contact
  /// between its fields, and the grid conditions at the given amplitudes.
  void node_velocities(Model<D>& m, std::size_t node, double tiny, bool record_start, bool contact, const std::vector<double>& amplitude);
  /// The grid part of a step, one pass over the nodes: velocities at t (recorded for FLIP), the
  /// momentum update to t + dt, velocities at t + dt; contact and conditions at both.
  void grid_update(Model<D>& m, double t, double dt);
  void update_stress(Model<D>& m, double dt);
  /// Prescribed grid velocities at a node (the momenta follow), amplitude[c] for condition c.
  void apply_grid_conditions(Model<D>& m, std::size_t node, const std::vector<double>& amplitude) const;
  std::vector<double> condition_amplitudes(double t) const;
  /// Contact between the fields of one node; true when they touch (and were corrected).
  bool apply_contact(Model<D>& m, std::size_t node) const;
  /// Velocity field of material point p at a node: crack side (CRAMP), body (multi-material
  /// contact) or the single shared field.
  /// (q: the node's place in the point's stencil, for the per-step crack-field cache)
  std::size_t field_of(const Model<D>& m, std::size_t p, int q) const;
  /// True when every point's field_of is 0: one velocity field (no cracks, one body or no contact).
  bool one_velocity_field(const Model<D>& m) const;
  void move_cracks(const Model<D>& m, double dt);
  /// Mass-weighted mean at x of a nodal quantity given per slot times its mass (weighted(slot)),
  /// over all fields (probe null) or the field of the material on the crack side of `probe`.
  template <class Weighted>
  std::optional<Vec<2>> side_mean(const Model<D>& m, const Vec<2>& x, const Vec<2>* probe, Weighted weighted) const;

  scene::Mpm settings_;
  Domain<D>* domain_ = nullptr;  // a distributed run's
  double tiny_mass_ = 0.0;       // grid slots lighter than this carry no material (velocity 0, not a contact field)
  std::vector<GridCondition> conditions_;
  struct NodeConditions {  // the conditions of each node, in scene order: condition[first[n] .. first[n + 1])
    std::vector<std::uint32_t> first, condition;
  } node_conditions_;
  std::vector<ParticleLoad> loads_;
  /// One thread's share of a particle-to-grid transfer: the grid quantities scatter() sums, valid
  /// over the slots [first, last) that the thread's points reach.
  struct ScatterBuffer {
    std::size_t first = 0, last = 0;
    std::vector<double> mass, volume;
    std::vector<Vec<D>> momentum, force, mass_gradient, displacement;
    void resize(std::size_t slots) {
      if (mass.size() == slots) return;
      for (auto* v : {&mass, &volume}) v->resize(slots);
      for (auto* v : {&momentum, &force, &mass_gradient, &displacement}) v->resize(slots);
    }
  };
  std::vector<ScatterBuffer> thread_buffers_;
  parallel::SharedBlocks slot_blocks_;  // the scatter's sum over the buffers, slot by slot
  std::vector<Vec<D>> start_position_;
  StencilCache<D> stencils_;  // every point's S_ip and grad S_ip at start_position_
  std::vector<Vec<D>> start_velocity_;
  CrackSet cracks_;
  std::vector<std::uint8_t> near_crack_;  // material points whose stencil may reach across a crack
  std::vector<std::uint8_t> crack_field_; // per point and stencil node: CRAMP field of the step
  std::vector<Vec<D>> acceleration_;
  std::vector<Vec<D>> stage_velocity_;   // MUSL with several fields: grid velocities the points moved with
  std::vector<std::uint8_t> touching_;   // per node: fields in contact this step (apply_contact)
  std::vector<Tensor<D>> velocity_gradient_;
  scene::Mpm::Contact crack_contact_ = scene::Mpm::Contact::frictionless;
  bool measure_ = false;
  double cell_volume_ = 0.0, contact_volume_ = 0.9;
  Energy energy_;  // x_p at the start of the step: every transfer of the step uses S_ip(x_p^n)
};

}  // namespace rift::mpm
