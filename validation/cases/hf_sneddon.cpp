// Hydraulic fracture validation 1: Sneddon's pressurized line crack (examples/hf_sneddon.toml), 2D
// plane strain LPS, a = 10 mm in a 200 mm plate, p = 1 MPa carried by the bonds the crack cuts
// (hf/crack_pressure.hpp), no growth, adaptive dynamic relaxation. The opening
//   w(x) = 4 (1 - nu^2) p / E sqrt(a^2 - x^2)   (Sneddon 1946; plane strain)
// is read at the crack faces: each face's displacement extrapolated linearly from the two lattice
// rows next to it (at dx/2 and 3 dx/2; crack_face_opening.hpp). Its L2 error over |x| <= 0.9 a must be within 5% and the
// crack volume int w dx within 3% of 2 pi (1 - nu^2) p a^2 / E, both at horizon 3.015 mm (1 mm
// spacing), and both errors must fall as the horizon shrinks at horizon / spacing = 3.015:
// 6.03, 3.015, 1.5075 mm (quick: 6.03 and 3.015 mm). The finite plate (20 a wide) adds about 0.6%.
#include <cmath>
#include <cstdio>

#include "case.hpp"
#include "crack_face_opening.hpp"
#include "rift/pd/dynamic_relaxation.hpp"
#include "rift/run/simulation.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

struct Opening {
  double l2 = 0.0, volume = 0.0, centre = 0.0;  // L2 error (|x| <= 0.9 a), volume / Sneddon, w(0) / Sneddon
  std::size_t particles = 0;
  int iterations = 0;
};

Opening sneddon(double spacing) {
  auto s = scene::parse_file(source_path("examples/hf_sneddon.toml"));
  s.bodies[0].horizon *= spacing / s.bodies[0].spacing;  // the same horizon / spacing
  s.bodies[0].spacing = spacing;
  const double E = s.materials[0].youngs_modulus(), nu = s.materials[0].poisson_ratio();
  const double p = s.cracks[0].pressure, a = s.cracks[0].points[1][0];
  run::Simulation<2> sim(s);
  auto& m = sim.model;
  pd::DynamicRelaxation<2> dr(m);
  const auto relax = dr.relax(m, sim.loads, sim.contact_ptr(), s.solver.end_time, s.solver.max_iterations, s.solver.tolerance);
  const CrackFaceOpening opening(m, spacing, 0.5);  // sites at ((i + 1/2) dx, (j + 1/2) dx), the crack on y = 0
  const double scale = 4.0 * (1.0 - nu * nu) * p / E;
  double err2 = 0.0, ref2 = 0.0, volume = 0.0, centre = 0.0;
  const long half = std::lround(a / spacing);
  for (long i = -half; i < half; ++i) {
    const double x = (i + 0.5) * spacing;
    const double w = opening.at(i, 0), exact = scale * std::sqrt(a * a - x * x);
    volume += w * spacing;
    if (i == 0) centre = w / exact;
    if (std::abs(x) <= 0.9 * a) err2 += (w - exact) * (w - exact), ref2 += exact * exact;
  }
  Opening o;
  o.l2 = std::sqrt(err2 / ref2);
  o.volume = volume / (2.0 * M_PI * (1.0 - nu * nu) * p * a * a / E);
  o.centre = centre;
  o.particles = m.size();
  o.iterations = relax.iterations;
  return o;
}

}  // namespace

Result hf_sneddon(const Settings& settings) {
  const std::vector<double> spacings = settings.quick ? std::vector<double>{0.002, 0.001} : std::vector<double>{0.002, 0.001, 0.0005};
  std::vector<Opening> runs;
  for (double dx : spacings) runs.push_back(sneddon(dx));
  bool falls = true;
  std::string series;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (k > 0) falls = falls && runs[k].l2 < runs[k - 1].l2 && std::abs(runs[k].volume - 1.0) < std::abs(runs[k - 1].volume - 1.0);
    char b[160];
    std::snprintf(b, sizeof b, "%sdelta %.4g mm: L2 %.4f, volume %.4f, w(0) %.4f (%zu particles, %d iterations)", k ? "; " : "",
                  3.015 * spacings[k] * 1e3, runs[k].l2, runs[k].volume, runs[k].centre, runs[k].particles, runs[k].iterations);
    series += b;
  }
  const auto& at = runs[1];  // 1 mm spacing, horizon 3.015 mm
  Result r;
  r.name = "hf_sneddon";
  r.measured = at.l2;
  r.reference = 0.0;
  r.tolerance = 0.05;
  r.unit = "L2 error of the opening over |x| <= 0.9 a (horizon 3.015 mm)";
  char buf[700];
  std::snprintf(buf, sizeof buf, "%s; volume within 3%%: %s; errors fall with the horizon: %s", series.c_str(),
                std::abs(at.volume - 1.0) <= 0.03 ? "yes" : "NO", falls ? "yes" : "NO");
  r.details = buf;
  r.source = "Sneddon (1946) pressurized line crack, plane strain";
  r.decide();
  if (std::abs(at.volume - 1.0) > 0.03 || !falls) r.pass = false;
  return r;
}

}  // namespace rift::validation
