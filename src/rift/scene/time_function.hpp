// Load amplitude as a function of time: constant, ramp, step, piecewise-linear table.
#pragma once
#include "rift/scene/scene.hpp"

namespace rift::scene {

inline double evaluate(const TimeFunction& f, double t) {
  using K = TimeFunctionKind;
  switch (f.kind) {
    case K::constant: return 1.0;
    case K::ramp: return t <= f.start ? 0.0 : t >= f.end ? 1.0 : (t - f.start) / (f.end - f.start);
    case K::step: return t >= f.start ? 1.0 : 0.0;
    case K::table: {
      const auto& p = f.table;
      if (t <= p.front()[0]) return p.front()[1];
      if (t >= p.back()[0]) return p.back()[1];
      for (std::size_t k = 1; k < p.size(); ++k)
        if (t <= p[k][0]) {
          double a = (t - p[k - 1][0]) / (p[k][0] - p[k - 1][0]);
          return p[k - 1][1] + a * (p[k][1] - p[k - 1][1]);
        }
      return p.back()[1];
    }
  }
  return 1.0;
}

}  // namespace rift::scene
