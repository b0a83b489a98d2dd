// Hydraulic fracture validation 3: breakdown of a pressurized borehole (examples/hf_breakdown.toml).
// Plane strain LPS, a = 10 mm in a 100 mm square, S_H = 10 MPa along x and S_h = 5 MPa along y
// (compression positive here), wall pressure raised slowly by dynamic relaxation load steps after
// the in-situ stage. Hubbert and Willis (1957): the wall breaks down at
//   p_b = 3 S_h - S_H + T,
// within 15%, and the fracture runs along sigma_H: the damage beyond r = 1.5 a lies within 10
// degrees of the x axis (its damage-weighted mean angle, folded into [0, 90]).
// The breakdown pressure is the one at which the fracture runs, as the peak of a laboratory
// pressure record: the first load step whose equilibrium cannot be found (dynamic relaxation does
// not converge) or whose damage reaches r = 2 a, taken midway between it and the step before.
// The first bonds break earlier, at the corners of the staircase the lattice makes of the wall
// (their stretch is 12-18% above that of a smooth wall and does not fall with the spacing); that
// damage stays put until the breakdown and is reported beside it.
// T is the tensile strength of the PD material in the wall's condition: plane strain, the hoop
// stress sigma and the radial stress -p of the fluid on the wall. The hoop bond breaks at
// e = s0 = s00 - alpha s_min (LAMMPS peri), its strain ((1 - nu^2) sigma + nu (1 + nu) p) / E, the
// smallest stretch in its family the radial strain -((1 - nu^2) p + nu (1 + nu) sigma) / E:
//   sigma = T0 + c p,  T0 = E s00 / ((1 - nu^2) - alpha nu (1 + nu)),
//   c = (alpha (1 - nu^2) - nu (1 + nu)) / ((1 - nu^2) - alpha nu (1 + nu)),
// T0 the strength in uniaxial tension; a strain criterion's strength falls with the lateral
// compression (Poisson's effect; c = -0.091 here). Hubbert and Willis's wall, whose hoop stress is
// p - (3 S_h - S_H), then breaks at p - (3 S_h - S_H) = T0 + c p:
//   p_b = (3 S_h - S_H + T0) / (1 - c),
// 8% below 3 S_h - S_H + T0 here. (The reference before 2026-11-24 took T0 for T, the uniaxial
// strength: the wall's first bonds broke at 0.76 of it, as this formula has them.)
#include <cmath>
#include <cstdio>

#include "case.hpp"
#include "rift/scene/time_function.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

/// The largest distance from the borehole's axis of a particle with damage, and the damage-weighted
/// mean angle from the x axis (degrees, folded into [0, 90]) of the damaged particles beyond `r_min`.
struct DamageExtent {
  double r_max = 0.0, angle_deg = 90.0;
};

DamageExtent damage_extent(const pd::Model<2>& m, double r_min) {
  DamageExtent e;
  double angle = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m.damage[i] <= 0.0) continue;
    const auto& x = m.reference_position[i];
    const double r = std::hypot(x[0], x[1]);
    e.r_max = std::max(e.r_max, r);
    if (r < r_min) continue;
    angle += m.damage[i] * std::atan2(std::abs(x[1]), std::abs(x[0]));
    weight += m.damage[i];
  }
  if (weight > 0.0) e.angle_deg = angle / weight * 180.0 / M_PI;
  return e;
}

}  // namespace

Result hf_breakdown(const Settings&) {
  auto s = scene::parse_file(source_path("examples/hf_breakdown.toml"));
  const auto& mat = s.materials[0];
  const double E = mat.youngs_modulus(), nu = mat.poisson_ratio(), s00 = *mat.critical_stretch, alpha = mat.alpha;
  const double S_H = -s.in_situ.sigma_H, S_h = -s.in_situ.sigma_h;  // compression positive
  const double T = E * s00 / ((1.0 - nu * nu) - alpha * nu * (1.0 + nu));
  const double lateral = (alpha * (1.0 - nu * nu) - nu * (1.0 + nu)) / ((1.0 - nu * nu) - alpha * nu * (1.0 + nu));
  const double expected = (3.0 * S_h - S_H + T) / (1.0 - lateral);
  const double a = 0.01;  // the borehole's radius (examples/hf_breakdown.toml)
  run::Simulation<2> sim(s);
  auto& m = sim.model;
  const auto in_situ = sim.equilibrate_in_situ(s.in_situ);
  const std::int64_t broken_by_in_situ = pd::summarize<2>(m).broken_bonds;
  pd::DynamicRelaxation<2> dr(m);
  auto pressure = [&](double t) { return s.boreholes[0].pressure * scene::evaluate(s.boreholes[0].pressure_time, t); };
  double breakdown = 0.0, step_width = 0.0, first_break = 0.0, stable_extent = 0.0;
  DamageExtent at_breakdown;
  for (long step = 1; step <= sim.steps; ++step) {
    const double t = s.solver.end_time * double(step) / double(sim.steps);
    const double before = pressure(s.solver.end_time * double(step - 1) / double(sim.steps));
    const auto r = sim.relax(dr, s.solver, t);
    pd::update_damage<2>(m);
    const auto extent = damage_extent(m, 1.5 * a);
    if (first_break == 0.0 && pd::summarize<2>(m).broken_bonds > 0) first_break = 0.5 * (before + pressure(t));
    if (!r.converged || extent.r_max > 2.0 * a) {
      breakdown = 0.5 * (before + pressure(t));
      step_width = pressure(t) - before;
      at_breakdown = extent;
      break;
    }
    stable_extent = extent.r_max;
  }
  Result res;
  res.name = "hf_breakdown";
  res.measured = breakdown / expected;
  res.reference = 1.0;
  res.tolerance = 0.15;
  res.unit = "breakdown pressure / Hubbert-Willis (3 S_h - S_H + T), T the strength at the wall";
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "p_b = %.3f MPa (+- %.2f, load steps), Hubbert-Willis %.3f MPa with T = %.3f %+.3f p MPa; the fracture runs at %.1f degrees "
                "from sigma_H (within 10: %s); first bonds broke at %.3f MPa (%.2f of Hubbert-Willis), damage within r = %.2f a "
                "until the breakdown; bonds broken by the in-situ stage: %lld; in-situ stage converged: %s",
                breakdown / 1e6, 0.5 * step_width / 1e6, expected / 1e6, T / 1e6, lateral, at_breakdown.angle_deg,
                at_breakdown.angle_deg <= 10.0 ? "yes" : "NO", first_break / 1e6, first_break / expected, stable_extent / a,
                static_cast<long long>(broken_by_in_situ), in_situ.converged ? "yes" : "NO");
  res.details = buf;
  res.source = "Hubbert and Willis (1957) breakdown pressure of a borehole under anisotropic in-situ stress";
  res.decide();
  if (breakdown <= 0.0 || at_breakdown.angle_deg > 10.0 || broken_by_in_situ != 0 || !in_situ.converged) res.pass = false;
  return res;
}

}  // namespace rift::validation
