// One step of the viscoelastic back extension (ves.hpp; Mitchell 2011, sec. 3): with the deviatoric
// extension e_d linear in time over the step dt, d e_b / dt = (e_d - e_b) / tau integrates exactly to
//   e_b(n+1) = e_d(n) (1 - decay) + e_b(n) decay + beta (e_d(n+1) - e_d(n)),
//   decay = exp(-dt / tau),  beta = 1 - tau (1 - decay) / dt.
// e_d(n) is not stored per directed bond: it is taken again from the pair's extension and the
// particle's dilatation of the step before (bonds.hpp last_extension, history_dilatation), 2 bytes a
// directed bond and 8 a particle instead of 4 a directed bond.
#pragma once
#include <cmath>
#include <cstddef>

#include "rift/pd/bond_slabs.hpp"
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

/// e_d(n) of the bond with history slot h (either direction) seen from its end i, at the history's
/// last advance (bonds.hpp last_extension, history_dilatation): e(n) - theta_i(n) |xi| / d.
template <int D>
double last_deviatoric_extension(const Bonds& b, std::size_t h, std::size_t i, double xi) {
  return b.last_extension[pair_slot(h)] - b.history_dilatation[i] * (xi / D);
}

}  // namespace rift::pd
