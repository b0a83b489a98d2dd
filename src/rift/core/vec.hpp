// Small fixed-size vectors for particle kinematics; D = 2 or 3 (kernels are templated on it).
#pragma once
#include <array>
#include <cmath>

namespace rift {

template <int D>
using Vec = std::array<double, D>;

template <std::size_t N>
inline std::array<double, N> operator+(const std::array<double, N>& a, const std::array<double, N>& b) {
  std::array<double, N> r;
  for (std::size_t k = 0; k < N; ++k) r[k] = a[k] + b[k];
  return r;
}
template <std::size_t N>
inline std::array<double, N> operator-(const std::array<double, N>& a, const std::array<double, N>& b) {
  std::array<double, N> r;
  for (std::size_t k = 0; k < N; ++k) r[k] = a[k] - b[k];
  return r;
}
template <std::size_t N>
inline std::array<double, N> operator*(double s, const std::array<double, N>& a) {
  std::array<double, N> r;
  for (std::size_t k = 0; k < N; ++k) r[k] = s * a[k];
  return r;
}
template <int D>
inline double dot(const Vec<D>& a, const Vec<D>& b) {
  double s = 0.0;
  for (int k = 0; k < D; ++k) s += a[k] * b[k];
  return s;
}
template <int D>
inline double norm(const Vec<D>& a) {
  return std::sqrt(dot<D>(a, a));
}

/// A point in 3D used by geometry; 2D scenes set z = 0.
using Point3 = std::array<double, 3>;

}  // namespace rift
