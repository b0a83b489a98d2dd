// MPM validation 3 (mixed mode): the beam of examples/mpm_mixed_mode.toml with only the upper arm
// loaded (P upwards), damped to rest. It is the superposition of a DCB with P/2 on each arm and an
// ENF with P/2 on both arms, so K_I and K_II must each be within 5% of
//   K_I = 2 sqrt(3) (P/2) (a + chi h) / h^(3/2)  (chi = 0.64; Kanninen 1973, seed eq. 23),
//   |K_II| = 3 (P/2) a / h^(3/2) sqrt(1 + 2 (1 + nu) / 5 (h / a)^2)  (seed eq. 24).
// K_I : K_II comes from the interaction integral ([mpm] mode_partition default); the crack opening
// and sliding ratio read at the crack point next to the tip gave 0.78 and 1.29 on 1 mm cells. The
// full case (1 mm) must meet 5% (1.017, 1.042 when written); the 2 mm CI run is held to 8% (1.061,
// 1.051): Guo and Nairn found mode II converged only on 1 mm cells.
#include <cstdio>

#include "case.hpp"
#include "cracked_beam.hpp"

namespace rift::validation {

Result mpm_mixed_mode(const Settings& settings) {
  const double h = 0.012, a = 0.05, nu = 0.33, chi = 0.64;
  const double cell = settings.quick ? 0.002 : 0.001, settle = settings.quick ? 0.012 : 0.02;
  const auto run = run_cracked_beam("examples/mpm_mixed_mode.toml", cell, 0.1 - a, settle);
  const double half = 0.5 * run.P_upper;
  const double KI_ref = 2.0 * std::sqrt(3.0) * half * (a + chi * h) / std::pow(h, 1.5);
  const double KII_ref = 3.0 * half * a / std::pow(h, 1.5) * std::sqrt(1.0 + 2.0 * (1.0 + nu) / 5.0 * (h / a) * (h / a));
  const double ratio_I = run.tip.KI / KI_ref, ratio_II = std::abs(run.tip.KII) / KII_ref;
  Result r;
  r.name = "mpm_mixed_mode";
  r.measured = std::abs(ratio_I - 1.0) > std::abs(ratio_II - 1.0) ? ratio_I : ratio_II;  // the worse of the two
  r.reference = 1.0;
  r.tolerance = settings.quick ? 0.08 : 0.05;
  r.unit = "worse of K_I, |K_II| / superposed beam theory";
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "K_I %.4g vs %.4g (%.4f), K_II %.4g vs %.4g Pa m^0.5 (%.4f); mode mixity K_II/K_I %.3f vs %.3f; J_1 %.4g J/m2; cells %g m, "
                "%zu points, %ld steps",
                run.tip.KI, KI_ref, ratio_I, run.tip.KII, KII_ref, ratio_II, run.tip.KII / run.tip.KI, KII_ref / KI_ref, run.tip.J1, cell,
                run.particles, run.steps);
  r.details = buf;
  r.source = "superposition of corrected beam theory for DCB (seed eq. 23) and ENF (seed eq. 24)";
  r.decide();
  return r;
}

}  // namespace rift::validation
