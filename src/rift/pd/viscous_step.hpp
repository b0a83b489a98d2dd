// One step of the viscoelastic back extension (ves.hpp; Mitchell 2011, sec. 3): with the deviatoric
// extension e_d linear in time over the step dt, d e_b / dt = (e_d - e_b) / tau integrates exactly to
//   e_b(n+1) = e_d(n) (1 - decay) + e_b(n) decay + beta (e_d(n+1) - e_d(n)),
//   decay = exp(-dt / tau),  beta = 1 - tau (1 - decay) / dt.
#pragma once
#include <cmath>

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

/// e_b(n+1) from the stored e_d(n), e_b(n) (single precision) and the new e_d, in double, stored in
/// single precision (6e-8 relative rounding).
[[gnu::always_inline]] inline float next_back_extension(double deviatoric_old, double back_old, double deviatoric, double one_minus_decay,
                                                        double decay, double beta) {
  return static_cast<float>(deviatoric_old * one_minus_decay + back_old * decay + beta * (deviatoric - deviatoric_old));
}

}  // namespace rift::pd
