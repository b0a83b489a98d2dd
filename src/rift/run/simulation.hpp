// A discretized scene ready to step: model, loads, contact and the time step. Used by the
// command line runner and by validation cases that sample the state while it runs.
#pragma once
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "rift/core/error.hpp"
#include "rift/load/boundary.hpp"
#include "rift/parallel/communicator.hpp"
#include "rift/parallel/halo.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/pd/contact.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/in_situ_strain.hpp"
#include "rift/pd/static_equilibrium.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/velocity_verlet.hpp"
#include "rift/pd/window.hpp"
#include "rift/run/time_step.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

template <int D>
struct Simulation {
  pd::Model<D> model;
  load::Boundaries<D> loads;
  pd::Contact<D> contact;
  double stable_dt = 0.0, dt = 0.0;
  long steps = 0;  // explicit: time steps to end_time; relaxation: load steps

  /// Every scene error is raised here, before anything is written.
  explicit Simulation(const scene::Scene& s)
      : model(pd::discretize<D>(s)), loads(s, model), contact(s.contact, model), cracks_(s.cracks.size()), interfaces_(s.interfaces.size()) {
    stable_dt = pd::stable_time_step<D>(model);
    if (s.solver.kind == scene::SolverKind::explicit_dynamics) {
      const auto plan = explicit_steps(s.solver, stable_dt, "Silling and Askari 2005, eq. 29");
      dt = plan.dt;
      steps = plan.steps;
    } else {
      steps = s.solver.load_steps;
    }
  }
  pd::Contact<D>* contact_ptr() { return contact.enabled() ? &contact : nullptr; }
  /// `mpirun -np N`: keeps this rank's window of the model (pd/window.hpp) and of the loads, its
  /// ghosts refreshed by a halo exchange. Raises a SceneError (before anything is written) for a
  /// cut along another axis than the lattice's slowest (--cut-along, or a --processor-grid other
  /// than 1 x .. x N).
  /// cut_axis: Options::cut_axis (-1, or the lattice's slowest axis: the layers are contiguous in
  /// the particles' numbering, which keeps the run bitwise the one-rank run's).
  void distribute(const scene::Scene& s, const parallel::Communicator& comm, int cut_axis = -1, const std::vector<int>& processor_grid = {}) {
    if (cut_axis >= 0 && cut_axis != D - 1)
      throw SceneError({s.file, 0, 0}, "--cut-along", std::string("a peridynamic run is cut across its lattice's slowest axis, ") +
                                                          (D == 3 ? "z" : "y") + ", alone (its layers of particles are ranges of their numbering)");
    std::vector<int> slabs(D, 1);
    slabs.back() = comm.size();
    if (!processor_grid.empty() && processor_grid != slabs)
      throw SceneError({s.file, 0, 0}, "--processor-grid",
                       "a peridynamic run on " + std::to_string(comm.size()) + " ranks takes the grid " + (D == 3 ? "1x1x" : "1x") +
                           std::to_string(comm.size()) + " alone (slabs across its lattice's slowest axis, whose layers are ranges of their numbering)");
    // dynamic relaxation, the in-situ stage and a fluid's cavity volume sum over the owned
    // particles in blocks (parallel/ordered_sum.hpp): the ranks' ranges start at whole blocks
    const bool block_sums = s.solver.kind != scene::SolverKind::explicit_dynamics || s.in_situ.enabled || !model.crack_bonds.neighbor.empty();
    partition = pd::partition_by_bonds<D>(model, comm.size(), block_sums ? parallel::ordered_sum_block : 1,
                                          pd::fluid_reads_far<D>(model) ? pd::fluid_ghost_reaches : 1);
    const auto r = static_cast<std::size_t>(comm.rank());
    loads.restrict_to(pd::Numbering(partition.window[r]), partition.owned[r]);
    model = pd::window_of<D>(model, partition, comm.rank());
    halo = std::make_unique<parallel::Halo>(comm.rank(), partition.owned, partition.window, model.numbering);
    model.ghosts = halo.get();
    contact = pd::Contact<D>(s.contact, model);  // its pairs among the window's particles and those beyond it within reach
  }
  pd::Partition partition;  // a distributed run's (empty on one rank)
  std::unique_ptr<parallel::Halo> halo;
  /// The in-situ stage ([in_situ_stress]): static equilibrium under the far-field stresses and
  /// every other load at t = 0, with no bond allowed to break; the run starts from it at rest.
  pd::RelaxationResult equilibrate_in_situ(const scene::InSituStress& in_situ) {
    pd::HeldBreaking<D> held(model);
    const auto initial_velocity = model.velocity;
    pd::DynamicRelaxation<D> dr(model);
    if (in_situ.start == scene::InSituStress::Start::uniform_strain) {
      pd::apply_in_situ_strain<D>(model, in_situ);
      dr.measure_damping_from_start(true);
    }
    pd::RelaxationResult cg;
    if (uses_conjugate_gradients(in_situ)) {
      const auto start = model.position;
      cg = pd::solve_static_equilibrium<D>(model, loads, contact_ptr(), 0.0, dr.fictitious_density(), in_situ.max_iterations,
                                           in_situ.tolerance);
      if (cg.converged || cg.iterations >= in_situ.max_iterations) {
        model.velocity = initial_velocity;
        return cg;
      }
      model.position = start;  // stopped short: dynamic relaxation from the start
    }
    // its iterations go as the square root of the fictitious density: measured, not bounded
    const double factor = dr.measure_fictitious_density(model, loads, contact_ptr(), 0.0);
    auto r = dr.relax(model, loads, contact_ptr(), 0.0, in_situ.max_iterations - cg.iterations, in_situ.tolerance);
    r.iterations += cg.iterations;
    r.density_factor = factor;
    model.velocity = initial_velocity;
    return r;
  }
  /// [in_situ_stress] solver: automatic takes the conjugate gradients where the forces are smooth:
  /// pre-cracks' faces in contact and interfaces' friction switch, and the iterations then stall.
  bool uses_conjugate_gradients(const scene::InSituStress& in_situ) const {
    using S = scene::InSituStress::Solver;
    if (in_situ.solver != S::automatic) return in_situ.solver == S::conjugate_gradient;
    return cracks_ == 0 && interfaces_ == 0;
  }
  /// Forces and loads of the initial state (call once before the first step).
  void start() {
    pd::compute_forces<D>(model, contact_ptr());
    loads.apply_body_forces(model, model.time);
  }
  void step() { pd::velocity_verlet_step<D>(model, loads, contact_ptr(), dt); }
  /// One load step of dynamic relaxation at time t, bonds breaking as [solver] breaking says.
  pd::RelaxationResult relax(pd::DynamicRelaxation<D>& dr, const scene::Solver& solver, double t) {
    if (solver.breaking == scene::Solver::Breaking::at_equilibrium)
      return dr.relax_breaking_at_equilibrium(model, loads, contact_ptr(), t, solver.max_iterations, solver.tolerance,
                                              solver.max_breaking_passes);
    return dr.relax(model, loads, contact_ptr(), t, solver.max_iterations, solver.tolerance);
  }

 private:
  std::size_t cracks_ = 0, interfaces_ = 0;  // the scene's pre-cracks and interfaces
};

}  // namespace rift::run
