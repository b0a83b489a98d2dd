// Hydraulic fracture validation: the KGD fracture driven by a viscous fluid
// (examples/hf_kgd_viscosity.toml). Plane strain LPS rock (E = 10 GPa, nu = 0.25, G0 = 50 J/m^2)
// under an isotropic in-situ stress sigma0 = 15 MPa; a fluid of viscosity mu = 0.675 Pa s injected at
// Q per unit height into a borehole with a short notch; the fluid flows along the crack by the cubic
// law (hf/viscous_fluid.hpp) and the rock relaxes with it at each load step.
// The zero-lag plane strain KGD solution (Detournay 2004; Garagash 2006) depends on one number, the
// dimensionless toughness K_m = K' / (E'^3 mu' Q)^(1/4), K' = sqrt(32 / pi) K_Ic, mu' = 12 mu,
// E' = E / (1 - nu^2):
//   l = gamma (E' Q^3 t^4 / mu')^(1/6),  w0 = Omega0 (mu' Q^3 t^2 / E')^(1/6),  p0 - sigma0 = Pi0 (mu' E'^2 / t)^(1/3),
// p0 the pressure at the inlet. K_m = 0 is the viscosity vertex (Adachi and Detournay 2002:
// gamma = 0.6152, Omega0 = 1.1265); a large K_m the toughness vertex of hf_kgd_toughness. The
// coefficients below were computed for this project by solving the zero-lag equations
// (lubrication, elasticity and the tip's K = K_Ic) numerically; the closed-form approximation of
// Dontsov (2017, Int J Fract 205:221) agrees within 0.55% on gamma and 0.8% on Omega0, and the
// K_m = 0 row within 0.1% of Adachi and Detournay's. The example's K_m is 1.0: l = 34.4 mm,
// w0 = 59.7 um and p0 - sigma0 = 5.41 MPa at t = 1 s.
// Zero lag: the confining stress fills the tip with fluid after t_om = mu' E'^2 / sigma0^3 = 0.27 s
// (Garagash and Detournay 2000), so the readings are at t = 0.5 s and 1 s (t / t_om = 1.8 and 3.7).
// Read as for the toughness case (kgd_reading.hpp): l the reach of the broken bonds across the
// crack line, w0 from a fit of w^(3/2) = w0^(3/2) - B x^2 (the M-vertex's opening is close to
// w0 (1 - x^2 / l^2)^(2/3)), p0 the borehole's pressure. Limits as for the toughness case: l 5%,
// w0 10%, p0 - sigma0 15%.
// Measured, 3 mm (quick, in CI): l 0.988 / 0.957 at t = 0.5 / 1 s (mean over the second half's
// load steps 0.963), w0 0.921 / 1.039, p0 - sigma0 1.013 / 1.013, every load step at equilibrium;
// 2 mm (the example, 6 min): l 0.944 / 0.948, just outside its 5% at both readings (mean over the
// second half 0.965), w0 1.047 / 1.083, p0 - sigma0 1.016 / 0.972, every load step at equilibrium.
// What it took (2026-11-24): the wet rock's pore shift only on the bonds that cross the crack or
// its extension at the tip (hf/crack_surface.hpp). With every particle the fluid reached wet
// (the rule before), the rock beside the faces read the net-pressure field of a crack only a few
// horizons long (tension p - sigma0 at infinity on a traction-free crack, 8 MPa here, against a
// strength of a few MPa) as a tension and split parallel to the crack: a band of damage five rows
// thick, l 0.576 / 0.631 at 2 mm and a mean of 0.516 at 3 mm, the faces no clean crack. Shifting
// only the crossing bonds was not enough while every broken bond extended the crack's surface: a
// bond that broke on the total stress just above a tip made a patch a row above the faces, and
// the surface then ran up a row per pass (nine rows in one load step at 3 mm); the crack now grows
// only by the bonds that break across it or its extension (and from the borehole's wall). Earlier
// probes, for the record: keeping the total stress within a horizon of the borehole's wall (the
// band stays); no effective stress at all (a sharp crack, but p0 - sigma0 1.27 at 0.5 s: under
// confinement the face pressure's -p I on the tip bonds, p sqrt(horizon) = 3 K_Ic here); the
// crossing read from each particle's mean direction of broken bonds (the toughness case's crack
// stepped off its line); wet only across bonds shorter than half a horizon (a grown tip needs 1.20
// K_Ic again).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "case.hpp"
#include "kgd_reading.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/pd/forces.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

// gamma, Omega0 and Pi0 of the zero-lag KGD fracture against K_m (the header).
struct ZeroLagKgd {
  double toughness, length, opening, pressure;
};
constexpr std::array<ZeroLagKgd, 7> zero_lag_kgd{{{0.0, 0.6154, 1.1259, 0.5449},
                                                  {0.5, 0.6133, 1.1277, 0.5461},
                                                  {1.0, 0.5992, 1.1416, 0.5559},
                                                  {1.5, 0.5677, 1.1815, 0.5859},
                                                  {2.0, 0.5240, 1.2553, 0.6478},
                                                  {3.0, 0.4343, 1.4818, 0.8768},
                                                  {4.0, 0.3660, 1.7461, 1.2048}}};

// The coefficients at K_m, linear between the table's rows.
ZeroLagKgd zero_lag_kgd_at(double K_m) {
  if (K_m < 0.0 || K_m > zero_lag_kgd.back().toughness) throw std::runtime_error("hf_kgd_viscosity: K_m outside the table (0 to 4)");
  std::size_t k = 1;
  while (k + 1 < zero_lag_kgd.size() && zero_lag_kgd[k].toughness < K_m) ++k;
  const auto &a = zero_lag_kgd[k - 1], &b = zero_lag_kgd[k];
  const double f = (K_m - a.toughness) / (b.toughness - a.toughness);
  auto mix = [f](double x, double y) { return x + f * (y - x); };
  return {K_m, mix(a.length, b.length), mix(a.opening, b.opening), mix(a.pressure, b.pressure)};
}

// The example with its spacing and horizon scaled by `coarsening` (coarsen_kgd_scene).
// `mean_length`: l judged by its mean over the second half's load steps (a coarse crack grows a
// column at a time), w0 and p at the two times.
Result viscous_kgd_case(const std::string& name, double coarsening, bool mean_length) {
  auto s = scene::parse_file(source_path("examples/hf_kgd_viscosity.toml"));
  const KgdRock rock = coarsen_kgd_scene(s, coarsening);
  const double spacing = rock.spacing, E_prime = rock.E_prime, K_prime = rock.K_prime, Q = rock.Q;
  const double mu_prime = 12.0 * s.boreholes[0].fluid_viscosity;
  const double K_m = K_prime / std::pow(E_prime * E_prime * E_prime * mu_prime * Q, 0.25);
  const double sigma0 = -s.in_situ.principal(1);  // the compression across the crack
  const ZeroLagKgd c = zero_lag_kgd_at(K_m);
  auto l_kgd = [&](double t) { return c.length * std::pow(E_prime * Q * Q * Q * std::pow(t, 4) / mu_prime, 1.0 / 6.0); };
  auto w0_kgd = [&](double t) { return c.opening * std::pow(mu_prime * Q * Q * Q * t * t / E_prime, 1.0 / 6.0); };
  auto p_kgd = [&](double t) { return c.pressure * std::pow(mu_prime * E_prime * E_prime / t, 1.0 / 3.0); };
  const double t_om = mu_prime * E_prime * E_prime / (sigma0 * sigma0 * sigma0);

  run::Simulation<2> sim(s);
  auto& m = sim.model;
  const auto in_situ = sim.equilibrate_in_situ(s.in_situ);
  pd::DynamicRelaxation<2> dr(m);
  const std::size_t source = s.cracks.size();  // the borehole's fluid
  const long steps = sim.steps;
  std::vector<KgdState> read;
  int unconverged = in_situ.converged ? 0 : 1;
  long iterations = 0;
  LengthRatios lengths;
  for (long step = 1; step <= steps; ++step) {
    const double t = s.solver.end_time * double(step) / double(steps);
    const auto r = sim.relax(dr, s.solver, t);
    unconverged += r.converged ? 0 : 1;
    iterations += r.iterations;
    if (step >= steps / 2) lengths.add(crack_reach(m, spacing) / l_kgd(t));
    if (step == steps / 2 || step == steps) {
      pd::update_damage<2>(m);
      read.push_back(read_kgd(m, spacing, m.fluid_network.pressure[source], 0.0, 1.5));
    }
  }
  KgdVerdict verdict{mean_length};
  std::string series;
  for (const auto& k : read) {
    const double rl = k.half_length / l_kgd(k.time), rw = k.inlet_opening / w0_kgd(k.time), rp = (k.pressure - sigma0) / p_kgd(k.time);
    verdict.judge(rl, rw, rp);
    char b[300];
    std::snprintf(b, sizeof b, "%st = %.2f s (t / t_om %.1f): l %.2f mm (%.3f), w0 %.2f um (%.3f), p0 - sigma0 %.3f MPa (%.3f)",
                  series.empty() ? "" : "; ", k.time, k.time / t_om, k.half_length * 1e3, rl, k.inlet_opening * 1e6, rw,
                  (k.pressure - sigma0) / 1e6, rp);
    series += b;
  }
  const double mean_l = lengths.mean();
  Result res;
  res.name = name;
  res.measured = verdict.measured(lengths);
  res.reference = 1.0;
  res.tolerance = 0.05;
  res.unit = mean_length ? "half-length / zero-lag KGD solution, mean over the second half's load steps"
                         : "half-length / zero-lag KGD solution, worse of two times";
  char buf[1200];
  std::snprintf(buf, sizeof buf, "%s (limits: l 5%%, w0 10%%, p0 - sigma0 15%%); K_m = %.3f (gamma %.4f, Omega0 %.4f, Pi0 %.4f), "
                "sigma0 %.3g MPa, t_om %.3f s; %zu particles, spacing %.2g mm; load steps without equilibrium: %d (%ld relaxation "
                "iterations in all); l / l_KGD over the %d load steps of the second half: mean %.3f, from %.3f to %.3f",
                series.c_str(), K_m, c.length, c.opening, c.pressure, sigma0 / 1e6, t_om, m.size(), spacing * 1e3, unconverged, iterations,
                lengths.count, mean_l, lengths.low, lengths.high);
  res.details = buf;
  res.source = "Zero-lag KGD fracture at the scene's K_m (Detournay 2004; Adachi and Detournay 2002 at K_m = 0)";
  res.pass = verdict.pass(lengths);
  return res;
}

}  // namespace

// Quick: 3 mm spacing (1.5 times the example's), the CI version.
Result hf_kgd_viscosity(const Settings& settings) { return viscous_kgd_case("hf_kgd_viscosity", settings.quick ? 1.5 : 1.0, settings.quick); }

}  // namespace rift::validation
