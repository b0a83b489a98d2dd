// Influence functions omega(|xi|) (Silling et al. 2007, eq. 37 ff.). inverse_distance is
// delta/|xi|: LAMMPS peri/lps uses 1/|xi|, which differs by a constant that cancels in LPS.
#pragma once
#include "rift/scene/scene.hpp"

namespace rift::pd {

inline double influence(scene::Influence kind, double xi, double horizon) {
  return kind == scene::Influence::constant ? 1.0 : horizon / xi;
}

/// Moments  int_0^delta omega(r) r^p dr  of the influence function.
inline double influence_moment(scene::Influence kind, double horizon, int p) {
  const double d = horizon;
  double dp1 = 1.0;
  for (int i = 0; i < p + 1; ++i) dp1 *= d;
  return kind == scene::Influence::constant ? dp1 / (p + 1) : d * dp1 / d / p;
}

}  // namespace rift::pd
