#include "rift/pd/critical_stretch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/pd/laws/registry.hpp"

namespace rift::pd {
namespace {

constexpr double pi = 3.14159265358979323846;

// 8-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 8> gl_x{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                     0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> gl_w{0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                     0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

/// Integrate f (returning a value or a std::array) over [a, b] split at the breakpoints, with
/// `panels` Gauss panels per piece.
template <class T, class F>
T integrate(F&& f, double a, double b, std::vector<double> breaks, int panels) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  T sum{};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    double lo = std::max(a, breaks[k]), hi = std::min(b, breaks[k + 1]);
    if (!(hi > lo)) continue;
    double h = (hi - lo) / panels;
    for (int p = 0; p < panels; ++p) {
      double c = lo + (p + 0.5) * h;
      for (int q = 0; q < 8; ++q) {
        T v = f(c + 0.5 * h * gl_x[q]);
        if constexpr (std::is_arithmetic_v<T>) {
          sum += 0.5 * h * gl_w[q] * v;
        } else {
          for (std::size_t i = 0; i < v.size(); ++i) sum[i] += 0.5 * h * gl_w[q] * v[i];
        }
      }
    }
  }
  return sum;
}

/// Integrals over bond directions mu = |cos(angle to the plane normal)| in [a, b] of mu^k, with the
/// direction measure of the dimension (3D: dmu; 2D: two half-planes, dmu / sqrt(1 - mu^2)).
std::array<double, 3> mu_moments(int dim, double a, double b) {
  if (!(b > a)) return {0.0, 0.0, 0.0};
  if (dim == 3) return {b - a, 0.5 * (b * b - a * a), (b * b * b - a * a * a) / 3.0};
  auto sa = std::sqrt(std::max(0.0, 1.0 - a * a)), sb = std::sqrt(std::max(0.0, 1.0 - b * b));
  double i0 = std::asin(b) - std::asin(a);
  return {2.0 * i0, 2.0 * (sa - sb), (i0 - (b * sb - a * sa))};
}

}  // namespace

double separation_work_per_stretch2(const MaterialConstants& mc, bool state_based) {
  const int d = mc.dimension;
  const double delta = mc.horizon;
  const double t = d == 2 ? mc.thickness : 1.0;
  // radial measure: 3D  2 pi xi^2 dxi ; 2D  t xi dxi (the factor 2 of the two half-planes is in mu_moments)
  auto radial = [&](double xi) { return d == 3 ? 2.0 * pi * xi * xi : t * xi; };
  auto omega = [&](double xi) { return influence(mc.influence, xi, delta); };
  const bool lps = state_based;
  const double m = family_moment(d, mc.influence, delta, t, 2);
  const double alpha = mc.lps_deviatoric_coefficient() / m;

  // Strain energy density at height z above the plane for opening v, with s0 = 1: crossing bonds
  // (xi > z, mu > z/xi) have extension e = v mu and are broken once v mu / xi >= 1.
  auto energy_density = [&](double z, double v) {
    // per bond length: {int omega xi e, int omega e^2, int_broken omega xi^2, int omega e^2 / xi}
    auto row = [&](double xi) {
      double lo = z / xi, cut = std::min(1.0, xi / v);
      auto in = mu_moments(d, lo, cut);                // intact crossing bonds
      auto br = mu_moments(d, std::max(lo, cut), 1.0);  // broken crossing bonds
      double w = radial(xi) * omega(xi);
      return std::array<double, 4>{w * xi * v * in[1], w * v * v * in[2], w * xi * xi * br[0], w * v * v * in[2] / xi};
    };
    std::vector<double> breaks;
    if (z * v > z * z && z * v < delta * delta) breaks.push_back(std::sqrt(z * v));
    if (v > z && v < delta) breaks.push_back(v);
    auto [s1, a2, mb, pmb] = integrate<std::array<double, 4>>(row, z, delta, breaks, 3);
    if (!lps) return 0.25 * mc.micromodulus * pmb;
    double theta = d * s1 / m;
    return 0.5 * mc.kappa * theta * theta + 0.5 * alpha * (a2 - theta * theta * (m + mb) / (d * d));
  };
  // E(v) = 2 int_0^delta W dz ; work G = int (dE/dv at fixed bonds) dv = int 2 E(v) d(ln v).
  auto energy = [&](double v) {
    std::vector<double> breaks;
    if (v < delta) breaks.push_back(v);
    if (delta * delta / v < delta) breaks.push_back(delta * delta / v);
    return 2.0 * integrate<double>([&](double z) { return energy_density(z, v); }, 0.0, delta, breaks, 3);
  };
  const double lo = std::log(1e-4 * delta), hi = std::log(1e6 * delta);
  return integrate<double>([&](double tau) { return 2.0 * energy(std::exp(tau)); }, lo, hi,
                   {std::log(delta)}, 60);
}

double pmb_separation_work_per_stretch2(const MaterialConstants& mc) {
  if (mc.dimension == 3) return 0.5 * pi * mc.micromodulus * influence_moment(mc.influence, mc.horizon, 4);
  return mc.micromodulus * mc.thickness * influence_moment(mc.influence, mc.horizon, 3);
}

double critical_stretch_from_fracture_energy(const MaterialConstants& mc, double fracture_energy) {
  const double gamma = with_law(mc.model, [&]<class Law>() { return Law::separation_work_per_stretch2(mc); });
  return std::sqrt(fracture_energy / gamma);
}

}  // namespace rift::pd
