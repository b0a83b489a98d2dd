#include "rift/pd/surface_correction.hpp"

#include <array>
#include <cmath>

#include "rift/pd/influence.hpp"

namespace rift::pd {

namespace {

/// Combine per-axis factors of both ends into one bond factor (ellipsoid rule).
template <int D>
float bond_factor(const std::array<double, D>& gi, const std::array<double, D>& gj, const Vec<D>& n) {
  double s = 0.0;
  for (int k = 0; k < D; ++k) {
    double g = 0.5 * (gi[k] + gj[k]);
    s += (n[k] / g) * (n[k] / g);
  }
  return static_cast<float>(1.0 / std::sqrt(s));
}

}  // namespace

template <int D>
void apply_surface_correction(Model<D>& m) {
  const std::size_t n = m.size();
  const Bonds& b = m.bonds;
  bool lps_any = false;
  for (const auto& body : m.bodies) lps_any = lps_any || body.constants.model == scene::ModelKind::lps;
  if (lps_any) m.dilatation_correction.assign(b.neighbor.size(), 1.0f);
  m.deviatoric_weighted_volume = m.weighted_volume;

  // g[i][k]: stiffness (PMB) or deviatoric (LPS) factor; gt[i][k]: LPS dilatation factor
  std::vector<std::array<double, D>> g(n), gt(n);
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    const int d = D;
#pragma omp parallel for schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) {
      for (int axis = 0; axis < D; ++axis) {
        g[i][axis] = gt[i][axis] = 1.0;
        if (!c.surface_correction) continue;
        // uniaxial strain eps = 1 along axis: bond extension e = |xi| n_axis^2
        double pmb_w = 0.0, theta_sum = 0.0, dev = 0.0;
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
          const double xi = b.length[k];
          const auto j = static_cast<std::size_t>(b.neighbor[k]);
          const double na = (m.reference_position[j][axis] - m.reference_position[i][axis]) / xi;
          const double w = influence(c.influence, xi, c.horizon) * b.volume[k];
          const double e = xi * na * na;
          pmb_w += w * e * e / xi;
          theta_sum += w * xi * e;
          const double ed = e - xi / d;  // deviatoric extension for the exact dilatation theta = 1
          dev += w * ed * ed;
        }
        if (c.model == scene::ModelKind::pmb) {
          // W_PD = (1/4) c sum omega s^2 |xi| V ; classical W = M/2 with the P-wave modulus of the
          // PMB body itself (nu = 1/4 in 3D and plane strain, 1/3 in plane stress): 9 kappa/5 or 3 kappa/2
          double classical = 0.5 * (d == 3 ? 1.8 * c.kappa : 1.5 * c.kappa);
          if (pmb_w > 0) g[i][axis] = classical / (0.25 * c.micromodulus * pmb_w);
        } else {
          double theta = d * theta_sum / m.weighted_volume[i];
          if (theta > 0) gt[i][axis] = 1.0 / theta;
          // deviatoric energy: classical G |dev eps|^2 = G (1 - 1/d); peridynamic alpha/2 sum omega (e^d)^2 V
          double alpha = c.lps_deviatoric_coefficient() / m.weighted_volume[i];
          double classical = c.shear_modulus * (1.0 - 1.0 / d);
          if (dev > 0) g[i][axis] = classical / (0.5 * alpha * dev);
        }
      }
    }
  }
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = m.constants_of(i);
    if (!c.surface_correction) continue;
    double mdev = 0.0;
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[k]);
      const Vec<D> dir = (1.0 / b.length[k]) * (m.reference_position[j] - m.reference_position[i]);
      m.bonds.correction[k] = bond_factor<D>(g[i], g[j], dir);
      if (c.model == scene::ModelKind::lps) {
        m.dilatation_correction[k] = bond_factor<D>(gt[i], gt[j], dir);
        mdev += m.bonds.correction[k] * influence(c.influence, b.length[k], c.horizon) * b.length[k] * b.length[k] * b.volume[k];
      }
    }
    if (c.model == scene::ModelKind::lps) m.deviatoric_weighted_volume[i] = mdev;
  }
}

template void apply_surface_correction<2>(Model<2>&);
template void apply_surface_correction<3>(Model<3>&);

}  // namespace rift::pd
