// Influence functions omega(|xi|) (Silling et al. 2007, eq. 37 ff.). inverse_distance is
// delta/|xi|: LAMMPS peri/lps uses 1/|xi|, which differs by a constant that cancels in LPS.
#pragma once
#include "rift/scene/scene.hpp"

namespace rift::pd {

inline double influence(scene::Influence kind, double xi, double horizon) {
  return kind == scene::Influence::constant ? 1.0 : horizon / xi;
}

/// f.template operator()<Omega>() with the kind as a template argument: the passes' loops are
/// compiled for each influence function.
template <class F>
decltype(auto) with_influence(scene::Influence kind, F&& f) {
  if (kind == scene::Influence::constant) return f.template operator()<scene::Influence::constant>();
  return f.template operator()<scene::Influence::inverse_distance>();
}

/// Moments  int_0^delta omega(r) r^p dr  of the influence function.
inline double influence_moment(scene::Influence kind, double horizon, int p) {
  const double d = horizon;
  double dp1 = 1.0;
  for (int i = 0; i < p + 1; ++i) dp1 *= d;
  return kind == scene::Influence::constant ? dp1 / (p + 1) : d * dp1 / d / p;
}

/// The continuum moment  int_ball omega(|xi|) |xi|^p dV  over a whole family: 3D 4 pi int omega r^(p+2) dr,
/// 2D (a slab of `thickness`) 2 pi t int omega r^(p+1) dr. With p = 2 the weighted volume m of a
/// family cut by no surface (Silling et al. 2007, eq. 38).
inline double family_moment(int dimension, scene::Influence kind, double horizon, double thickness, int p) {
  constexpr double pi = 3.14159265358979323846;
  return dimension == 3 ? 4.0 * pi * influence_moment(kind, horizon, 2 + p) : 2.0 * pi * thickness * influence_moment(kind, horizon, 1 + p);
}

}  // namespace rift::pd
