// Runs a cracked MPM scene and samples J, G, K_I, K_II at every crack tip inside material.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "case.hpp"
#include "rift/mpm/discretize.hpp"
#include "rift/mpm/j_integral.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/scene/scene.hpp"

namespace rift::validation {

struct TipSample {
  double time = 0.0;
  std::vector<std::vector<mpm::CrackTipParameters>> contours;  // [contour][tip], tips in the order of interior_tips()
};

struct TipHistory {
  std::vector<mpm::CrackTip> tips;
  std::vector<TipSample> samples;
  std::size_t particles = 0;
  long steps = 0;
};

/// Runs `s` to its end time with `samples` evenly spaced samples, evaluating every contour at each.
inline TipHistory run_tip_history(const scene::Scene& s, int samples, const std::vector<mpm::JContour>& contours) {
  auto m = mpm::discretize<2>(s);
  mpm::Solver<2> solver(s, m);
  const double dt = s.solver.safety_factor * solver.stable_time_step(m);
  TipHistory h;
  h.tips = mpm::interior_tips(m, solver.cracks());
  h.steps = static_cast<long>(std::ceil(s.solver.end_time / dt));
  h.particles = m.particles.size();
  long next = 0;
  for (long k = 1; k <= h.steps; ++k) {
    solver.step(m, dt);
    if (k * samples >= next * h.steps) {
      TipSample sample{m.time, {}};
      for (const auto& contour : contours) {
        sample.contours.emplace_back();
        for (const auto& t : h.tips) sample.contours.back().push_back(mpm::crack_tip_parameters(m, solver, t, contour));
      }
      h.samples.push_back(sample);
      while (next * h.steps <= k * samples) ++next;
    }
  }
  return h;
}

/// Evenly spaced entries of a history of `count` samples for a report line, joined by spaces:
/// label(i) for i = 0, count/parts, 2 count/parts, ...
template <class Label>
std::string sampled_history(std::size_t count, std::size_t parts, Label label) {
  std::string out;
  for (std::size_t i = 0; i < count; i += std::max<std::size_t>(1, count / parts)) {
    if (!out.empty()) out += ' ';
    out += label(i);
  }
  return out;
}

}  // namespace rift::validation
