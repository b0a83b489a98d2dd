// MPM validation 5: single edge notched plate under sudden tension (examples/mpm_sent.toml; Guo
// and Nairn 2006, seed 002, Fig. 9 and sec. 5): a = 5 mm, W = 20 mm, plane strain, sigma0 = 400 MPa.
// K_I(t)/K0 (K0 = sigma0 sqrt(pi a)) with 0.25, 0.5, 1 and 2 mm cells, dynamic J with the area term
// on a contour 2 cells from the tip, sampled 700 times over the 14 us. The 0.5 and 1 mm histories
// must be within 3% of the 0.25 mm one over the run, read as the root mean square over the run of
// |K_h(t) - K_0.25(t)| relative to the 0.25 mm peak. The largest single deviation is reported: it
// sits at the front that reaches the tip at about 13 us after three transits of the plate (60 mm);
// the lumped-mass grid's dispersion delays it by about 0.25 us on 1 mm cells, where the K history
// falls steeply. Guo and Nairn judged convergence by eye from plotted curves; 2 mm is reported.
// Quick: 1 mm against 0.5 mm.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "case.hpp"
#include "crack_tip_history.hpp"
#include "rift/scene/parse.hpp"

namespace rift::validation {

namespace {

/// K_I(t)/K0 of the SENT with `cell` cells, sampled 700 times.
std::vector<std::array<double, 2>> sent_history(double cell, std::size_t& particles) {
  auto s = scene::parse_file(source_path("examples/mpm_sent.toml"));
  s.mpm.cell_size = cell;
  // keep the crack midway between grid lines and the grid 3 cells beyond the plate
  const double rows = std::ceil(0.0215 / cell);
  (*s.mpm.grid_min)[1] = -(rows + 0.5) * cell;
  (*s.mpm.grid_min)[0] = -0.01 - 3 * cell;
  (*s.mpm.grid_max)[0] = 0.01 + 3 * cell;
  (*s.mpm.grid_max)[1] = 0.02 + 3 * cell;
  // the traction layer must hold whole rows of points: 0.5 mm, or one row where the points are
  // farther apart (2 mm cells: 1 mm), else T / layer_depth loads the row of 1 mm twice over
  const double depth = std::max(0.0005, cell / s.bodies[0].particles_per_cell);
  for (auto& region : s.regions) {
    if (region.name == "top") region.min[1] = 0.02 - depth;
    if (region.name == "bottom") region.max[1] = -0.02 + depth;
  }
  for (auto& b : s.boundaries) b.layer_depth = depth;
  const double K0 = 4.0e8 * std::sqrt(M_PI * 0.005);
  const auto h = run_tip_history(s, 700, {mpm::contour_of(s.mpm)});
  particles = h.particles;
  std::vector<std::array<double, 2>> out{{0.0, 0.0}};
  for (const auto& sample : h.samples) out.push_back({sample.time, sample.contours[0].at(0).KI / K0});
  return out;
}

double at(const std::vector<std::array<double, 2>>& curve, double t) {
  auto it = std::lower_bound(curve.begin(), curve.end(), t, [](const std::array<double, 2>& p, double x) { return p[0] < x; });
  if (it == curve.begin()) return curve.front()[1];
  if (it == curve.end()) return curve.back()[1];
  const auto& b = *it;
  const auto& a = *(it - 1);
  return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
}

}  // namespace

Result mpm_sent(const Settings& settings) {
  const std::vector<double> cells = settings.quick ? std::vector<double>{0.0005, 0.001} : std::vector<double>{0.00025, 0.0005, 0.001, 0.002};
  std::vector<std::vector<std::array<double, 2>>> curves;
  std::size_t particles = 0, finest = 0;
  for (double c : cells) {
    curves.push_back(sent_history(c, particles));
    if (c == cells.front()) finest = particles;
  }
  const auto& ref = curves.front();
  double peak = 0.0, t_peak = 0.0;
  for (const auto& p : ref)
    if (p[1] > peak) peak = p[1], t_peak = p[0];
  // deviation from the finest history at its sample times, relative to its peak
  std::vector<double> rms(cells.size(), 0.0), largest(cells.size(), 0.0), when(cells.size(), 0.0);
  for (std::size_t k = 1; k < cells.size(); ++k) {
    double sum = 0.0;
    for (const auto& p : ref) {
      const double d = std::abs(at(curves[k], p[0]) - p[1]) / peak;
      sum += d * d;
      if (d > largest[k]) largest[k] = d, when[k] = p[0];
    }
    rms[k] = std::sqrt(sum / static_cast<double>(ref.size()));
  }
  double worst = 0.0;
  std::string series;
  for (std::size_t k = 1; k < cells.size(); ++k) {
    if (cells[k] <= 0.001 + 1e-12) worst = std::max(worst, rms[k]);
    char b[96];
    std::snprintf(b, sizeof b, "%s%g mm %.3f (largest %.3f at %.1f us)", series.empty() ? "" : ", ", cells[k] * 1e3, rms[k], largest[k], when[k] * 1e6);
    series += b;
  }
  const std::string curve = sampled_history(ref.size(), 15, [&](std::size_t i) {
    char b[48];
    std::snprintf(b, sizeof b, "%.1f:%.2f", ref[i][0] * 1e6, ref[i][1]);
    return std::string(b);
  });
  Result r;
  r.name = "mpm_sent";
  r.measured = worst;
  r.reference = 0.0;
  r.tolerance = 0.03;
  r.unit = "RMS over the run of |K_h(t) - K_fine(t)| / peak, h <= 1 mm";
  char buf[800];
  std::snprintf(buf, sizeof buf,
                "against %g mm cells (%zu points, peak K_I/K0 %.3f at %.2f us): RMS deviation by cell %s; K_I/K0 (us:value) %s", cells.front() * 1e3,
                finest, peak, t_peak * 1e6, series.c_str(), curve.c_str());
  r.details = buf;
  r.source = "mesh convergence as Guo and Nairn (2006) report it for the SENT (Fig. 9): 1 mm already converged";
  r.decide();
  return r;
}

}  // namespace rift::validation
