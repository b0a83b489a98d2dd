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

/// `limit_source` names where the stable limit comes from, for the error message.
inline StepPlan explicit_steps(const scene::Solver& solver, double stable_dt, const std::string& limit_source) {
  double dt = solver.safety_factor * stable_dt;
  if (solver.time_step) {
    if (*solver.time_step > stable_dt)
      throw SceneError(solver.time_step_where, "solver.time_step",
                       fmt::format("time step {:.4g} s exceeds the stable limit {:.4g} s ({}); use a smaller value or safety_factor",
                                   *solver.time_step, stable_dt, limit_source));
    dt = *solver.time_step;
  }
  StepPlan plan;
  plan.steps = std::max(1L, static_cast<long>(std::ceil(solver.end_time / dt - 1e-9)));
  plan.dt = solver.end_time / double(plan.steps);
  return plan;
}

}  // namespace rift::run
