// Validation 4: numerical fracture energy. A bar is cut in two halves by the plane x = 0 and the
// right half is pulled away rigidly in small increments until every bond across the plane has
// broken. The work done, integral of the force between the halves over the opening, divided by
// the new crack area must be G0 within 10% (the critical stretch is derived from G0 for the
// continuum; the discrete lattice, partial volumes and the surface correction make the rest).
// PMB and LPS, 2D (plane stress) and 3D.
#include <cstdio>

#include "case.hpp"
#include "separation_work.hpp"

namespace rift::validation {

Result pd_fracture_energy(const Settings& settings) {
  double worst = 0.0, worst_ratio = 1.0;
  std::string details;
  for (const char* model : {"pmb", "lps"})
    for (int dim : {2, 3}) {
      const double ratio = dim == 2 ? separation_work_ratio<2>(model, settings.quick) : separation_work_ratio<3>(model, settings.quick);
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s%s%dD %.3f", details.empty() ? "" : ", ", model, dim, ratio);
      details += buf;
      if (std::abs(ratio - 1.0) > worst) worst = std::abs(ratio - 1.0), worst_ratio = ratio;
    }
  Result r;
  r.name = "pd_fracture_energy";
  r.measured = worst_ratio;
  r.reference = 1.0;
  r.tolerance = 0.1;
  r.unit = "work / (area G0), worst case";
  r.details = "G/G0: " + details;
  r.source = "G0 (Silling and Askari 2005, eq. 24)";
  r.decide();
  return r;
}

}  // namespace rift::validation
