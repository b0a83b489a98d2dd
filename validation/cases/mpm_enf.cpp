// MPM validation 2 (mode II): the end-notched flexure beam of examples/mpm_enf.toml as Guo and Nairn
// 2006 build it (left end clamped, both arms loaded the same way), damped to rest. K_II from the
// J-integral and the opening/sliding partition must be within 5% of (seed eq. 24)
//   K_II = 3 P a / h^(3/2) sqrt(1 + 2 (1 + nu) / 5 (h / a)^2),
// with K_I below 2% of K_II.
// The constant: Euler-Bernoulli beams give the energy release rate at fixed loads
//   G = dU*/da = [2 (P a)^2 / (2 E h^3 / 12) - (2 P a)^2 / (2 E (2h)^3 / 12)] = 9 P^2 a^2 / (E h^3),
// i.e. K_II = sqrt(E G) = 3 P a / h^(3/2). Timoshenko shear energy, 3 V^2 / (5 mu A) per length,
// cancels exactly here (two arms with V = P, A = h against one with V = 2P, A = 2h), so the square
// root's term is not plain shear deflection: it is the shear correction Carlsson, Gillespie and Pipes
// (1986) fitted for ENF, 0.2 (E / mu) (h / a)^2 = 2 (1 + nu) / 5 (h / a)^2 (+1.5% on K_II here). The
// report also gives the ratio to the uncorrected 3 P a / h^(3/2) and to the crack-root-rotation
// correction of Wang and Williams (1992), a -> a + 0.42 chi h with chi = 0.64 (+6.5%).
// Mesh: Guo and Nairn found mode II converged only on 1 mm cells (mode I on 2 mm). Both the 1 mm
// run (full case; 1.025 when written) and the 2 mm CI run (1.021) must meet 5%.
// Load: P = 1 kN/m keeps the beam linear (end deflection 0.4 mm). At 10 kN/m the end moved 3.9 mm,
// two cells, and K_II read 1.05 with K_I 10% of it.
// Crack-face contact is frictionless; where the faces are closed behind the tip, K_I = 0.
#include <cstdio>

#include "case.hpp"
#include "cracked_beam.hpp"

namespace rift::validation {

Result mpm_enf(const Settings& settings) {
  const double h = 0.012, a = 0.05, nu = 0.33;
  const double cell = settings.quick ? 0.002 : 0.001, settle = settings.quick ? 0.012 : 0.02;
  const auto run = run_cracked_beam("examples/mpm_enf.toml", cell, 0.1 - a, settle);
  const double P = std::abs(run.P_upper);
  const double K_plain = 3.0 * P * a / std::pow(h, 1.5);
  const double K_ref = K_plain * std::sqrt(1.0 + 2.0 * (1.0 + nu) / 5.0 * (h / a) * (h / a));
  const double KII = std::abs(run.tip.KII);
  const double K_root = 3.0 * P * (a + 0.42 * 0.64 * h) / std::pow(h, 1.5);
  Result r;
  r.name = "mpm_enf";
  r.measured = KII / K_ref;
  r.reference = 1.0;
  r.tolerance = 0.05;
  r.unit = "|K_II| / beam theory with shear correction";
  char buf[500];
  std::snprintf(buf, sizeof buf,
                "K_II %.4g vs %.4g Pa m^0.5 (%.4f of 3 P a / h^1.5 without the correction, %.4f of the root-rotation correction); K_I/K_II %.1e; J_1 %.4g J/m2, J_1 area "
                "term %.2g; sliding %.3g m, opening %.3g m; cells %g m, %zu points, %ld steps",
                run.tip.KII, K_ref, KII / K_plain, KII / K_root, run.tip.KI / KII, run.tip.J1, run.tip.J1_area, run.tip.sliding, run.tip.opening, cell,
                run.particles, run.steps);
  r.details = buf;
  r.source = "beam theory with Carlsson et al. (1986) shear correction (seed eq. 24)";
  r.decide();
  r.pass = r.pass && std::abs(run.tip.KI) < 0.02 * KII;
  return r;
}

}  // namespace rift::validation
