// A discretized scene ready to step: model, loads, contact and the time step. Used by the
// command line runner and by validation cases that sample the state while it runs.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

#include "rift/load/boundary.hpp"
#include "rift/pd/contact.hpp"
#include "rift/pd/discretize.hpp"
#include "rift/pd/forces.hpp"
#include "rift/pd/velocity_verlet.hpp"
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
  explicit Simulation(const scene::Scene& s) : model(pd::discretize<D>(s)), loads(s, model), contact(s.contact, model) {
    stable_dt = pd::stable_time_step<D>(model);
    if (s.solver.kind == scene::SolverKind::explicit_dynamics) {
      if (s.solver.time_step) {
        if (*s.solver.time_step > stable_dt)
          throw SceneError(s.solver.time_step_where, "solver.time_step",
                           "time step " + std::to_string(*s.solver.time_step) + " s exceeds the stable limit " +
                               std::to_string(stable_dt) + " s (Silling and Askari 2005, eq. 29); use a smaller value or safety_factor");
        dt = *s.solver.time_step;
      } else {
        dt = s.solver.safety_factor * stable_dt;
      }
      steps = std::max(1L, static_cast<long>(std::ceil(s.solver.end_time / dt - 1e-9)));
      dt = s.solver.end_time / double(steps);
    } else {
      steps = s.solver.load_steps;
    }
  }
  pd::Contact<D>* contact_ptr() { return contact.enabled() ? &contact : nullptr; }
  /// Forces and loads of the initial state (call once before the first step).
  void start() {
    pd::compute_forces<D>(model, contact_ptr());
    loads.apply_body_forces(model, model.time);
  }
  void step() { pd::velocity_verlet_step<D>(model, loads, contact_ptr(), dt); }
};

}  // namespace rift::run
