#include "rift/mpm/crack_growth.hpp"

#include <cmath>

namespace rift::mpm {

double hoop_stress_angle(double KI, double KII) {
  if (KII == 0.0) return 0.0;
  return 2.0 * std::atan((KI - std::sqrt(KI * KI + 8.0 * KII * KII)) / (4.0 * KII));
}

double equivalent_mode_one(double KI, double KII, double theta) {
  const double c = std::cos(0.5 * theta);
  return c * (KI * c * c - 1.5 * KII * std::sin(theta));
}

std::optional<Vec<2>> growth_point(const scene::CrackGrowth& criterion, const CrackTipParameters& tip, double cell_size) {
  if (!tip.valid || tip.G <= 0.0) return std::nullopt;
  const double theta = hoop_stress_angle(tip.KI, tip.KII);
  const bool grows = criterion.criterion == scene::CrackGrowth::Criterion::max_hoop_stress
                         ? equivalent_mode_one(tip.KI, tip.KII, theta) >= criterion.toughness
                         : tip.G >= criterion.critical_energy_release_rate;
  if (!grows) return std::nullopt;
  const double length = criterion.increment > 0.0 ? criterion.increment : 0.5 * cell_size;
  const double direction = tip.angle + theta;
  return tip.position + length * Vec<2>{std::cos(direction), std::sin(direction)};
}

CrackPropagation::CrackPropagation(const scene::Scene& s, const Model<2>& m, const Solver<2>& solver)
    : settings_(s.crack_growth), contour_(contour_of(s.mpm)) {
  for (const auto& t : interior_tips(m, solver.cracks())) tips_.push_back({t, false});
}

int CrackPropagation::check(const Model<2>& m, Solver<2>& solver, long step) {
  if (!settings_.enabled || step % settings_.check_every != 0) return 0;
  int grown = 0;
  for (auto& t : tips_) {
    if (t.stopped) continue;
    const auto k = crack_tip_parameters(m, solver, t.tip, contour_);
    const auto next = growth_point(settings_, k, m.grid.cell_size);
    if (!next) continue;
    if (!material_near(m, *next, m.grid.cell_size)) {  // the new tip would leave the material
      t.stopped = true;
      continue;
    }
    solver.extend_crack(t.tip, *next);
    ++grown;
  }
  return grown;
}

}  // namespace rift::mpm
