// One step of the viscoelastic back extension (ves.hpp; Mitchell 2011, sec. 3): with the deviatoric
// extension e_d linear in time over the step dt, d e_b / dt = (e_d - e_b) / tau integrates exactly to
//   e_b(n+1) = e_d(n) (1 - decay) + e_b(n) decay + beta (e_d(n+1) - e_d(n)),
//   decay = exp(-dt / tau),  beta = 1 - tau (1 - decay) / dt.
// e_d(n) is not stored per bond: it is taken again from the positions and dilatations of the step
// before (bonds.hpp history_position), 24 + 8 bytes a particle instead of 4 a directed bond, and a
// stream of the force pass fewer.
#pragma once
#include <cmath>
#include <cstddef>

#include "rift/pd/bonds.hpp"

namespace rift::pd {

/// The step's coefficients; dt = 0 holds the history (dynamic relaxation's iterations).
struct ViscousStep {
  bool advance = false;
  double one_minus_decay = 0.0, decay = 1.0, beta = 0.0;
  ViscousStep() = default;
  ViscousStep(double dt, double relaxation_time) : advance(dt > 0.0) {
    if (!advance) return;
    const double ratio = dt / relaxation_time;
    one_minus_decay = -std::expm1(-ratio), decay = 1.0 - one_minus_decay;
    beta = 1.0 - one_minus_decay / ratio;
  }
};

/// e_b(n+1) from e_d(n), the stored e_b(n) and the new e_d, in double, stored in single precision
/// (6e-8 relative rounding).
[[gnu::always_inline]] inline float next_back_extension(double deviatoric_old, double back_old, double deviatoric, double one_minus_decay,
                                                        double decay, double beta) {
  return static_cast<float>(deviatoric_old * one_minus_decay + back_old * decay + beta * (deviatoric - deviatoric_old));
}

/// e_d(n) of bond i-j seen from i, at the positions and dilatation of the history's last advance
/// (bonds.hpp history_position): |y| - |xi| - theta_i |xi| / d then.
template <int D>
double last_deviatoric_extension(const Bonds& b, std::size_t i, std::size_t j, double xi) {
  double r2 = 0.0;
  for (std::size_t q = 0; q < D; ++q) {
    const double d = b.history_position[q][j] - b.history_position[q][i];
    r2 += d * d;
  }
  return std::sqrt(r2) - xi - b.history_dilatation[i] * (xi / D);
}

}  // namespace rift::pd
