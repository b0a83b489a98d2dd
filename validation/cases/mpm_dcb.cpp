// MPM validation 1 (mode I): the double cantilever beam of examples/mpm_dcb.toml with its explicit
// crack (CRAMP), damped to rest, P = 1 kN/m. K_I from the J-integral (contour reaching 2 cells from
// the tip) and the interaction-integral partition must be
//  - within 4% of corrected beam theory (Kanninen 1973; seed eq. 23)
//      K_I = 2 sqrt(3) P (a + chi h) / h^(3/2),  chi = 0.64,
//  - within 3% of sqrt(E G) with G = (P^2 / 2) dC/da from the same model's compliance C = delta / P
//    at a - 2 mm and a + 2 mm (delta: load-point opening; plane stress, E' = E); 6% in the quick
//    (2 mm) run, where the compliance difference over one cell either side is itself 5% low
//    (1.054 when written; 1 mm: 1.000),
//  - with K_II below 2% of K_I, and the error against beam theory falling from 4 to 2 to 1 mm cells
//    (quick: 4 and 2 mm; the K and compliance checks then use 2 mm); when written: 4 mm 16%,
//    2 mm 2.1%, 1 mm 0.25%.
// Also checked: the load-point opening against the same beam theory, delta = 8 P (a + chi h)^3 / (E h^3),
// within 5%. 12 ms settles the 2 and 4 mm models (damping 1000 1/s); 1 mm runs 20 ms.
#include <cstdio>
#include <vector>

#include "case.hpp"
#include "cracked_beam.hpp"

namespace rift::validation {

Result mpm_dcb(const Settings& settings) {
  const std::string scene = "examples/mpm_dcb.toml";
  const double h = 0.012, a = 0.05, E = 2.3e9, chi = 0.64;
  const double fine = settings.quick ? 0.002 : 0.001, settle = settings.quick ? 0.012 : 0.02;
  const auto run = run_cracked_beam(scene, fine, 0.1 - a, settle);
  const double P = run.P_upper;
  const double K_beam = 2.0 * std::sqrt(3.0) * P * (a + chi * h) / std::pow(h, 1.5);
  const double delta_beam = 8.0 * P * std::pow(a + chi * h, 3) / (E * h * h * h);
  const double delta = run.upper_deflection - run.lower_deflection;
  // compliance method: G = (P^2 / 2) dC/da = (P / 2) d(delta)/da by a central difference
  const double da = 0.002;
  const auto shorter = run_cracked_beam(scene, fine, 0.1 - (a - da), settle);
  const auto longer = run_cracked_beam(scene, fine, 0.1 - (a + da), settle);
  const double dDelta_da = ((longer.upper_deflection - longer.lower_deflection) - (shorter.upper_deflection - shorter.lower_deflection)) / (2 * da);
  const double G_compliance = 0.5 * P * dDelta_da;
  const double K_compliance = std::sqrt(E * G_compliance);
  // mesh series
  std::vector<double> cells = settings.quick ? std::vector<double>{0.004, 0.002} : std::vector<double>{0.004, 0.002, 0.001};
  std::vector<double> errors;
  std::string series;
  for (double c : cells) {
    const double K = c == fine ? run.tip.KI : run_cracked_beam(scene, c, 0.1 - a, c == 0.001 ? 0.02 : 0.012).tip.KI;
    errors.push_back(std::abs(K / K_beam - 1.0));
    char b[64];
    std::snprintf(b, sizeof b, "%s%g mm %.4f", series.empty() ? "" : ", ", c * 1e3, K / K_beam);
    series += b;
  }
  bool falling = true;
  for (std::size_t k = 1; k < errors.size(); ++k) falling = falling && errors[k] < errors[k - 1];

  Result r;
  r.name = "mpm_dcb";
  r.measured = run.tip.KI / K_beam;
  r.reference = 1.0;
  r.tolerance = 0.04;
  r.unit = "K_I / corrected beam theory";
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "K_I %.4g vs %.4g Pa m^0.5 (beam), vs sqrt(E G_compliance) %.4g: ratio %.4f; K_II/K_I %.1e; J_1 %.4g J/m2, G from "
                "compliance %.4g J/m2; K_I/beam by cell: %s; load-point opening / beam theory %.4f; cells %g m, %zu points, %ld steps",
                run.tip.KI, K_beam, K_compliance, run.tip.KI / K_compliance, run.tip.KII / run.tip.KI, run.tip.J1, G_compliance,
                series.c_str(), delta / delta_beam, fine, run.particles, run.steps);
  r.details = buf;
  r.source = "corrected beam theory, chi = 0.64 (Kanninen 1973; seed eq. 23); compliance at a +- 2 mm";
  r.decide();
  r.pass = r.pass && std::abs(run.tip.KI / K_compliance - 1.0) <= (settings.quick ? 0.06 : 0.03) && std::abs(run.tip.KII) < 0.02 * run.tip.KI &&
           std::abs(delta / delta_beam - 1.0) <= 0.05 && falling;
  return r;
}

}  // namespace rift::validation
