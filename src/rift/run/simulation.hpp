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
#include "rift/parallel/communicator.hpp"
#include "rift/hf/window_fluid.hpp"
#include "rift/pd/halo.hpp"
#include "rift/parallel/ordered_sum.hpp"
#include "rift/pd/contact.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/geomech/in_situ_strain.hpp"
#include "rift/geomech/interface_stages.hpp"
#include "rift/pd/static_equilibrium.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/velocity_verlet.hpp"
#include "rift/pd/window.hpp"
#include "rift/run/scene_loads.hpp"
#include "rift/run/time_step.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

template <int D>
struct Simulation {
  pd::Model<D> model;
  SceneLoads<D> loads;
  pd::Contact<D> contact;
  double stable_dt = 0.0, dt = 0.0;
  long steps = 0;  // explicit: time steps to end_time; relaxation: load steps

  /// Every scene error is raised here, before anything is written.
  explicit Simulation(const scene::Scene& s)
      : model(pd::discretize<D>(s)), loads(s, model), contact(s.contact, model), cracks_(s.cracks.size()), interfaces_(s.interfaces.size()) {
    geomech::install_interface_stages<D>(model);
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
  /// ghosts refreshed by a halo exchange. The processor grid (Options::processor_grid) is 1 x P in
  /// 2D and 1 x P x Q in 3D, each lattice line along x kept whole: 1 x 1 x N cuts slabs across the
  /// lattice's slowest axis, P > 1 pencils; chosen (pd::choose_pencils) where not given. Raises a
  /// SceneError (before anything is written) for another grid, a given grid that leaves a rank
  /// without particles, or a cut along another axis than the slowest (--cut-along).
  void distribute(const scene::Scene& s, const parallel::Communicator& comm, int cut_axis = -1, const std::vector<int>& processor_grid = {}) {
    const int ranks = comm.size();
    if (cut_axis >= 0 && cut_axis != D - 1)
      throw SceneError({s.file, 0, 0}, "--cut-along", std::string("a peridynamic run is cut across its lattice's slowest axis, ") +
                                                          (D == 3 ? "z, alone (or y and z: --processor-grid 1xPxQ)" : "y, alone") +
                                                          ": each lattice line along x stays whole, a range of the numbering");
    std::vector<int> grid = processor_grid;
    if (grid.empty()) {  // slabs, or pencils where their ranks hold fewer ghosts; across z alone with --cut-along z
      grid.assign(D, 1), grid.back() = ranks;
      if (D == 3 && cut_axis < 0) {
        const auto [across_y, across_z] = pd::choose_pencils<D>(model, ranks);
        grid[1] = across_y, grid[D - 1] = across_z;
      }
    }
    const std::string n = std::to_string(ranks);
    const std::string as = D == 3 ? "1x1x" + n + " or 1xPxQ with P Q = " + n : "the grid 1x" + n + " alone";
    int product = 1;
    for (const int g : grid) product *= g;
    if (static_cast<int>(grid.size()) != D || grid[0] != 1 || product != ranks)
      throw SceneError({s.file, 0, 0}, "--processor-grid",
                       "a peridynamic run on " + n + " ranks takes " + (D == 3 ? "a grid " : "") + as +
                           " (slabs or pencils: each lattice line along x stays whole, a range of the particles' numbering)");
    const std::size_t reaches = hf::fluid_reads_far<D>(model) ? hf::fluid_ghost_reaches : 1;
    if (D == 3 && grid[1] > 1) {
      partition = pd::partition_into_pencils<D>(model, grid[1], grid[D - 1], reaches);
      for (std::size_t r = 0; r < partition.owned.size() && grid[1] > 1; ++r) {
        if (count_of(partition.owned[r]) > 0) continue;
        if (processor_grid.empty()) grid[1] = 1, grid[D - 1] = ranks;  // chosen: slabs instead
        else
          throw SceneError({s.file, 0, 0}, "--processor-grid",
                           fmt::format("the grid 1x{}x{} leaves rank {} without particles: its lattice has too few lines across y or layers across z",
                                       grid[1], grid[D - 1], r));
      }
    }
    if (D == 2 || grid[1] == 1) partition = pd::partition_by_bonds<D>(model, ranks, reaches);
    processor_grid_ = grid;
    const auto r = static_cast<std::size_t>(comm.rank());
    loads.boundaries.restrict_to(pd::Numbering(partition.window[r]), partition.owned[r]);
    auto window = pd::window_of<D>(model, partition, comm.rank());
    hf::window_fluid<D>(model, pd::Numbering(partition.window[r]), window);
    model = std::move(window);
    halo = std::make_unique<pd::Halo>(comm.rank(), partition.owned, partition.window, model.numbering);
    model.ghosts = halo.get();
    contact = pd::Contact<D>(s.contact, model);  // its pairs among the window's particles and those beyond it within reach
  }
  pd::Partition partition;  // a distributed run's (empty on one rank)
  /// A distributed run's processor grid, 1 x .. (distribute).
  const std::vector<int>& processor_grid() const { return processor_grid_; }
  std::unique_ptr<pd::Halo> halo;
  /// The in-situ stage ([in_situ_stress]): static equilibrium under the far-field stresses and
  /// every other load at t = 0, with no bond allowed to break; the run starts from it at rest, its
  /// histories committed (pd::commit_at_equilibrium: EPS's plastic extensions), as a load step's.
  /// A stop signal ends it early (stopped = true): the run then starts again from the beginning.
  pd::RelaxationResult equilibrate_in_situ(const scene::InSituStress& in_situ) {
    pd::HeldBreaking<D> held(model);
    const auto r = solve_in_situ(in_situ);
    if (!r.stopped) pd::commit_at_equilibrium<D>(model, contact_ptr());
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
  /// One load step at time t: by dynamic relaxation, bonds breaking as [solver] breaking says, or
  /// by the static solver (solve_static), bonds breaking at each equilibrium. The load step ends
  /// with its equilibrium's histories committed (pd::commit_at_equilibrium).
  pd::RelaxationResult relax(pd::DynamicRelaxation<D>& dr, const scene::Solver& solver, double t) {
    pd::RelaxationResult r;
    if (solver.kind == scene::SolverKind::static_equilibrium)
      r = dr.breaking_at_equilibrium(model, loads, contact_ptr(), solver.max_breaking_passes, [&] { return solve_static(dr, solver, t); });
    else if (solver.breaking == scene::Solver::Breaking::at_equilibrium)
      r = dr.relax_breaking_at_equilibrium(model, loads, contact_ptr(), t, solver.max_iterations, solver.tolerance, solver.max_breaking_passes);
    else
      r = dr.relax(model, loads, contact_ptr(), t, solver.max_iterations, solver.tolerance);
    if (!r.stopped) pd::commit_at_equilibrium<D>(model, contact_ptr());
    return r;
  }
  /// One equilibrium of the static solver at time t, the bonds held by the caller: preconditioned
  /// conjugate gradients with the coarse space (pd/static_equilibrium.hpp) from the positions as
  /// they stand (the last load step's equilibrium); where they stop short of the tolerance with
  /// force evaluations left (forces that switch: a contact, an interface's friction), dynamic
  /// relaxation from the same start for the evaluations left, as the in-situ stage does. A stop in
  /// that relaxation goes on from there after a restart, bit for bit (DynamicRelaxation::unfinished,
  /// with the evaluations spent); one in the conjugate gradients solves again from the positions the
  /// checkpoint holds. Out of evaluations, the fluid still takes the pressures reached
  /// (loads.at_equilibrium), as relaxation's end does.
  pd::RelaxationResult solve_static(pd::DynamicRelaxation<D>& dr, const scene::Solver& solver, double t) {
    auto relax_for_the_rest = [&](int spent) {
      dr.unfinished().spent = spent;
      auto r = dr.relax(model, loads, contact_ptr(), t, solver.max_iterations - spent, solver.tolerance);
      if (!r.stopped) dr.unfinished().spent = 0;
      r.iterations += spent;
      return r;
    };
    if (dr.is_unfinished()) return relax_for_the_rest(dr.unfinished().spent);  // a stop came in it
    const auto start = model.position;
    const auto cg = pd::solve_static_equilibrium<D>(model, loads, contact_ptr(), t, dr.fictitious_density(), solver.max_iterations,
                                                    solver.tolerance, dr.observer());
    if (cg.converged || cg.stopped) return cg;
    if (cg.iterations >= solver.max_iterations) {
      loads.at_equilibrium(model);
      return cg;
    }
    model.position = start;
    return relax_for_the_rest(cg.iterations);
  }

 private:
  /// The in-situ stage's equilibrium, by conjugate gradients or dynamic relaxation (bonds held by the caller).
  pd::RelaxationResult solve_in_situ(const scene::InSituStress& in_situ) {
    const auto initial_velocity = model.velocity;
    pd::DynamicRelaxation<D> dr(model);
    if (in_situ.start == scene::InSituStress::Start::uniform_strain) {
      geomech::apply_in_situ_strain<D>(model, in_situ);
      dr.measure_damping_from_start(true);
    }
    pd::RelaxationResult cg;
    if (uses_conjugate_gradients(in_situ)) {
      const auto start = model.position;
      cg = pd::solve_static_equilibrium<D>(model, loads, contact_ptr(), 0.0, dr.fictitious_density(), in_situ.max_iterations,
                                           in_situ.tolerance);
      if (cg.converged || cg.stopped || cg.iterations >= in_situ.max_iterations) {
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
  std::size_t cracks_ = 0, interfaces_ = 0;  // the scene's pre-cracks and interfaces
  std::vector<int> processor_grid_;
};

}  // namespace rift::run
