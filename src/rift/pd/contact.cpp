#include "rift/pd/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "rift/parallel/team.hpp"

namespace rift::pd {

template <int D>
Contact<D>::Contact(const scene::Contact& settings, const Model<D>& m) {
  enabled_ = settings.enabled;
  if (!enabled_) return;
  double min_spacing = 1e300;
  for (const auto& b : m.bodies) {
    const auto& c = b.constants;
    distance_.push_back(settings.distance * c.spacing);
    // micromodulus of the constant-influence PMB body with the same P-wave modulus
    const double kappa_equivalent = D == 3 ? 5.0 * c.p_wave_modulus() / 9.0 : 2.0 * c.p_wave_modulus() / 3.0;
    const double cc = pmb_micromodulus(D, kappa_equivalent, c.horizon, c.thickness, scene::Influence::constant);
    stiffness_.push_back(settings.stiffness * cc / c.horizon);
    max_distance_ = std::max(max_distance_, distance_.back());
    min_spacing = std::min(min_spacing, c.spacing);
  }
  skin_ = 0.5 * min_spacing;
  rebuild(m);
}

template <int D>
void Contact<D>::rebuild(const Model<D>& m) {
  const std::size_t n = m.size();
  built_at_ = m.position;
  const double cell = max_distance_ + skin_;
  std::vector<std::array<long, 3>> key(n);
  std::vector<std::int32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    key[i] = {0, 0, 0};
    for (int k = 0; k < D; ++k) key[i][k] = static_cast<long>(std::floor(m.position[i][k] / cell));
    order[i] = static_cast<std::int32_t>(i);
  }
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) { return key[a] < key[b] || (key[a] == key[b] && a < b); });
  std::vector<std::array<long, 3>> sorted_keys(n);
  for (std::size_t q = 0; q < n; ++q) sorted_keys[q] = key[order[q]];
  std::vector<std::vector<std::int32_t>> rows(n);
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(dynamic, 512)
  for (std::size_t i = 0; i < n; ++i) {
    const int rz = D == 3 ? 1 : 0;
    for (long dz = -rz; dz <= rz; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          std::array<long, 3> c{key[i][0] + dx, key[i][1] + dy, key[i][2] + dz};
          auto lo = std::lower_bound(sorted_keys.begin(), sorted_keys.end(), c);
          for (auto it = lo; it != sorted_keys.end() && *it == c; ++it) {
            auto j = order[static_cast<std::size_t>(it - sorted_keys.begin())];
            if (static_cast<std::size_t>(j) == i) continue;
            const double d = 0.5 * (distance_[m.body[i]] + distance_[m.body[j]]) + skin_;
            const Vec<D> eta = m.position[j] - m.position[i];
            if (dot<D>(eta, eta) < d * d) rows[i].push_back(j);
          }
        }
    std::sort(rows[i].begin(), rows[i].end());
  }
  offset_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] = offset_[i] + static_cast<std::int64_t>(rows[i].size());
  pairs_.resize(static_cast<std::size_t>(offset_[n]));
  for (std::size_t i = 0; i < n; ++i) std::copy(rows[i].begin(), rows[i].end(), pairs_.begin() + offset_[i]);
}

template <int D>
void Contact<D>::add_forces(Model<D>& m) {
  if (!enabled_) return;
  double moved2 = 0.0;
  const std::size_t n = m.size();
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) reduction(max : moved2) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> d = m.position[i] - built_at_[i];
    moved2 = std::max(moved2, dot<D>(d, d));
  }
  if (4.0 * moved2 > skin_ * skin_) rebuild(m);
  const Bonds& b = m.bonds;
#pragma omp parallel for if(rift::parallel::worth_a_team(n)) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Vec<D> f{};
    bool any = false;
    for (auto p = offset_[i]; p < offset_[i + 1]; ++p) {
      const auto j = pairs_[static_cast<std::size_t>(p)];
      const double d = 0.5 * (distance_[m.body[i]] + distance_[m.body[j]]);
      const Vec<D> eta = m.position[j] - m.position[i];
      const double r2 = dot<D>(eta, eta);
      if (r2 >= d * d || r2 == 0.0) continue;
      // skip pairs still joined by an intact bond (rows are sorted by neighbour)
      const auto first = b.neighbor.begin() + b.offset[i], last = b.neighbor.begin() + b.offset[i + 1];
      auto it = std::lower_bound(first, last, j);
      if (it != last && *it == j && b.intact[static_cast<std::size_t>(it - b.neighbor.begin())]) continue;
      const double r = std::sqrt(r2);
      const double k = 0.5 * (stiffness_[m.body[i]] + stiffness_[m.body[j]]);
      const double scalar = -k * m.volume[static_cast<std::size_t>(j)] * (d - r) / r;
      for (int q = 0; q < D; ++q) f[q] += scalar * eta[q];
      any = true;
    }
    if (any)
      for (int q = 0; q < D; ++q) m.force[i][q] += f[q];
  }
}

template class Contact<2>;
template class Contact<3>;

}  // namespace rift::pd
