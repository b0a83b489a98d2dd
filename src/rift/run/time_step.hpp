// The explicit time step of a run: the scene's time_step (never above the stable limit) or the
// safety factor times the limit, shrunk so a whole number of steps reaches end_time.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "rift/core/error.hpp"
#include "rift/scene/scene.hpp"

namespace rift::run {

struct StepPlan {
  double dt = 0.0;
  long steps = 0;
};

/// `limit_source` names where the stable limit comes from, for the error message. A time step
/// below limits::smallest_time_step_fraction of the stable one, or more than limits::steps steps to
/// end_time, is a SceneError with the numbers.
inline StepPlan explicit_steps(const scene::Solver& solver, double stable_dt, const std::string& limit_source) {
  double dt = solver.safety_factor * stable_dt;
  if (solver.time_step) {
    if (*solver.time_step > stable_dt)
      throw SceneError(solver.time_step_where, "solver.time_step",
                       fmt::format("time step {:.4g} s exceeds the stable limit {:.4g} s ({}); use a smaller value or safety_factor",
                                   *solver.time_step, stable_dt, limit_source));
    if (*solver.time_step < scene::limits::smallest_time_step_fraction * stable_dt)
      throw SceneError(solver.time_step_where, "solver.time_step",
                       fmt::format("time step {:.4g} s is below {:g} of the stable limit {:.4g} s ({}): a unit or an exponent is likely "
                                   "wrong; leave it out to take safety_factor times the limit",
                                   *solver.time_step, scene::limits::smallest_time_step_fraction, stable_dt, limit_source));
    dt = *solver.time_step;
  }
  const double steps = std::ceil(solver.end_time / dt - 1e-9);
  if (!(steps <= double(scene::limits::steps)))
    throw SceneError(solver.end_time_where, "solver.end_time",
                     fmt::format("end time {:.4g} s takes {:.4g} steps of {:.4g} s, more than the {:g} a run may take; give a shorter end_time",
                                 solver.end_time, steps, dt, double(scene::limits::steps)));
  StepPlan plan;
  plan.steps = std::max(1L, static_cast<long>(steps));
  plan.dt = solver.end_time / double(plan.steps);
  return plan;
}

/// The scene's warning where it asks for more snapshots than its explicit run has steps (each step
/// then writes one); empty otherwise. `rift check` and `rift run` print it.
inline std::string snapshots_past_steps(const scene::Scene& s, long steps) {
  const auto& o = s.output;
  if (s.solver.kind != scene::SolverKind::explicit_dynamics || o.count <= steps || o.count_where.line == 0) return {};
  return fmt::format("{}:{}:{}: warning: 'output.snapshots': {} snapshots, but the run has {} steps: one each step ({} files)", o.count_where.file,
                     o.count_where.line, o.count_where.column, o.count, steps, steps + 1);
}

}  // namespace rift::run
