// Validation 3: a free body (PMB and LPS, 3D and 2D, bonds breaking, contact on) given random
// velocities conserves linear and angular momentum to round-off under velocity-Verlet, because
// every bond force acts along the bond with equal and opposite ends (Silling 2000).
#include "case.hpp"
#include "momentum.hpp"

namespace rift::validation {

Result pd_momentum(const Settings& settings) {
  const int steps = settings.quick ? 200 : 1000;
  double worst = 0.0;
  for (const char* model : {"pmb", "lps"}) {
    worst = std::max(worst, momentum_drift<3>(model, steps));
    worst = std::max(worst, momentum_drift<2>(model, steps));
  }
  Result r;
  r.name = "pd_momentum";
  r.measured = worst;
  r.reference = 0.0;
  r.tolerance = 1e-11;
  r.unit = "max momentum drift / sum m|v|";
  r.details = std::to_string(steps) + " steps, PMB and LPS, 2D and 3D, random velocities that break bonds";
  r.source = "exact conservation (Silling 2000)";
  r.decide();
  return r;
}

}  // namespace rift::validation
