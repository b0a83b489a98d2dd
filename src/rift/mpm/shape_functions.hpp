// Grid shape functions of the material point method, one dimension at a time (the grid functions
// are tensor products). Each returns the nodes a particle touches with their weights and
// derivatives: linear hat (Sulsky et al. 1994), uGIMP (Bardenhagen and Kober 2004, particle
// half-width l), quadratic and cubic B-splines (Steffen et al. 2008).
#pragma once
#include <array>
#include <cmath>

namespace rift::mpm {

enum class ShapeKind { linear, gimp, bspline2, bspline3 };

/// Nodes touched along one axis: first node index and up to 4 weights / derivatives (per unit length).
struct Stencil1 {
  long first = 0;
  int count = 0;
  std::array<double, 4> weight{}, gradient{};
};

/// Weights of the particle at coordinate x (grid origin 0, cell size h) along one axis.
/// `half_width` is the uGIMP particle half-width l (< h/2).
[[gnu::always_inline]] inline Stencil1 stencil_1d(ShapeKind kind, double x, double h, double half_width) {
  Stencil1 s;
  const double u = x / h;  // position in cells
  switch (kind) {
    case ShapeKind::linear: {
      s.first = static_cast<long>(std::floor(u));
      s.count = 2;
      const double f = u - double(s.first);
      s.weight = {1.0 - f, f, 0, 0};
      s.gradient = {-1.0 / h, 1.0 / h, 0, 0};
      break;
    }
    case ShapeKind::gimp: {
      // nodes within h + l: at most three
      s.first = static_cast<long>(std::floor(u - half_width / h));
      s.count = 3;
      const double l = half_width;
      for (int k = 0; k < 3; ++k) {
        const double r = x - double(s.first + k) * h, a = std::abs(r), sg = r < 0 ? -1.0 : 1.0;
        double w = 0.0, g = 0.0;
        if (a < l) {
          w = 1.0 - (r * r + l * l) / (2.0 * h * l);
          g = -r / (h * l);
        } else if (a < h - l) {
          w = 1.0 - a / h;
          g = -sg / h;
        } else if (a < h + l) {
          w = (h + l - a) * (h + l - a) / (4.0 * h * l);
          g = -sg * (h + l - a) / (2.0 * h * l);
        }
        s.weight[static_cast<std::size_t>(k)] = w;
        s.gradient[static_cast<std::size_t>(k)] = g;  // dS/dx_p of S(x_p - x_i)
      }
      break;
    }
    case ShapeKind::bspline2: {
      s.first = static_cast<long>(std::floor(u - 0.5));
      s.count = 3;
      for (int k = 0; k < 3; ++k) {
        const double r = u - double(s.first + k), a = std::abs(r), sg = r < 0 ? -1.0 : 1.0;
        double w = 0.0, g = 0.0;
        if (a < 0.5) {
          w = 0.75 - r * r;
          g = -2.0 * r;
        } else if (a < 1.5) {
          w = 0.5 * (1.5 - a) * (1.5 - a);
          g = -sg * (1.5 - a);
        }
        s.weight[static_cast<std::size_t>(k)] = w;
        s.gradient[static_cast<std::size_t>(k)] = g / h;
      }
      break;
    }
    case ShapeKind::bspline3: {
      s.first = static_cast<long>(std::floor(u)) - 1;
      s.count = 4;
      for (int k = 0; k < 4; ++k) {
        const double r = u - double(s.first + k), a = std::abs(r), sg = r < 0 ? -1.0 : 1.0;
        double w = 0.0, g = 0.0;
        if (a < 1.0) {
          w = 0.5 * a * a * a - r * r + 2.0 / 3.0;
          g = sg * (1.5 * a * a) - 2.0 * r;
        } else if (a < 2.0) {
          w = (2.0 - a) * (2.0 - a) * (2.0 - a) / 6.0;
          g = -sg * 0.5 * (2.0 - a) * (2.0 - a);
        }
        s.weight[static_cast<std::size_t>(k)] = w;
        s.gradient[static_cast<std::size_t>(k)] = g / h;
      }
      break;
    }
  }
  return s;
}

/// Nodes per axis a particle can touch (for buffer sizes).
inline constexpr int support(ShapeKind kind) {
  return kind == ShapeKind::linear ? 2 : kind == ShapeKind::bspline3 ? 4 : 3;
}

}  // namespace rift::mpm
