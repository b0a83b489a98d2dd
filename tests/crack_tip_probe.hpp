// The crack-tip probe the initiation and growth tests share: a disk of plane strain rock (E = 10 GPa,
// nu = 0.25, G0 = 50 J/m^2) on a 2 mm lattice, horizon 3.015 spacings, whose boundary layer the
// mode I field of LEFM moves.
#pragma once
#include <array>
#include <cmath>

namespace rift::test {

constexpr double pi = 3.14159265358979323846;
constexpr double spacing = 0.002, horizon_spacings = 3.015, fracture_energy = 50.0;
constexpr double youngs_modulus = 10e9, poisson_ratio = 0.25;  // plane strain
constexpr double tip_x_of_probe = 0.5 * spacing;

// Mode I displacement around a tip with the crack on the negative x axis (Anderson, Table 2.2),
// plane strain: u = K / (2 mu) sqrt(r / 2 pi) (cos(t/2) (k - 1 + 2 sin^2(t/2)), sin(t/2) (k + 1 - 2 cos^2(t/2))), k = 3 - 4 nu.
inline std::array<double, 2> mode_one_displacement(double x, double y, double K) {
  const double mu = youngs_modulus / (2.0 * (1.0 + poisson_ratio)), kolosov = 3.0 - 4.0 * poisson_ratio;
  const double r = std::hypot(x, y), theta = std::atan2(y, x);
  const double a = K / (2.0 * mu) * std::sqrt(r / (2.0 * pi));
  const double c = std::cos(0.5 * theta), s = std::sin(0.5 * theta);
  return {a * c * (kolosov - 1.0 + 2.0 * s * s), a * s * (kolosov + 1.0 - 2.0 * c * c)};
}

}  // namespace rift::test
