// What a hydraulic fracture did at a pre-existing fracture, read off the bonds as Zhou et al. (2008) read
// their cut blocks (crossed, dilated, arrested):
//   crossed: a rock bond the fluid reaches is broken on the far side of the interface from the fluid
//     sources, at least `crossing_depth` horizons from its plane and within its extent;
//   dilated: open failed interface bonds the fluid reaches (normal opening above the rock's critical stretch
//     times the bond length), with p above the in-situ compression sigma_n across the interface (Warpinski
//     and Teufel 1987; the thesis' EQ 4.7, sigma_n from EQ 4.4), span at least `dilation_span` horizons;
//   arrested: the interface failed (or rock broke within crossing_depth of it) but neither holds;
//   not reached: nothing broke at the interface.
// An interface with no fluid source in the scene has no far side: only "dilated" can be read. As a cut
// block shows it, a run keeps what it has seen, load step by load step (record_outcomes): an interface
// once dilated reads dilated though it shut again. Why: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rift/geometry/precrack.hpp"
#include "rift/pd/ghost_fields.hpp"
#include "rift/geomech/interface_law.hpp"
#include "rift/pd/model.hpp"

namespace rift::geomech {

using pd::Bonds, pd::FluidNetwork, pd::InterfaceBonds, pd::Model;
using pd::bond_broken, pd::bond_intact, pd::bond_interface_failed, pd::ranks_of;

struct InterfaceOutcome {
  bool reached = false, crossed = false, dilated = false;
  double crossing_distance = 0.0;  // the farthest broken rock bond past the plane, within the extent, m
  double opened_length = 0.0;      // span of the open, wet failed interface bonds along the interface, m

  std::string name() const {
    if (crossed && dilated) return "crossed+dilated";
    if (crossed) return "crossed";
    if (dilated) return "dilated";
    return reached ? "arrested" : "not reached";
  }
};

inline constexpr double crossing_depth = 2.0;  // horizons past the plane
inline constexpr double dilation_span = 3.0;   // horizons along the interface

template <int D>
std::vector<InterfaceOutcome> classify_interfaces(const Model<D>& m) {
  const InterfaceBonds& ib = m.interface_bonds;
  std::vector<InterfaceOutcome> out(ib.laws.size());
  if (out.empty()) return out;
  double horizon = 0.0;
  for (const auto& body : m.bodies) horizon = std::max(horizon, body.constants.horizon);
  const Bonds& b = m.bonds;
  const FluidNetwork& net = m.fluid_network;
  auto wet = [&](std::size_t i) { return !net.source.empty() && net.source[i] >= 0; };
  auto point_of = [&](const Vec<D>& a, const Vec<D>& c) {
    Point3 p{0, 0, 0};
    for (int k = 0; k < D; ++k) p[k] = 0.5 * (a[k] + c[k]);
    return p;
  };
  std::vector<geometry::PreCrack> planes;
  for (const auto& law : ib.laws) planes.emplace_back(D, law.polygon);
  // within the extent: the foot of the point on the plane lies on the segment / in the polygon
  auto within_extent = [&](std::size_t f, const Point3& x, double d) {
    const auto& law = ib.laws[f];
    if constexpr (D == 2) {
      const double t = dot<3>(x - law.point, law.tangent);
      return t >= 0.0 && t <= law.length;
    } else {
      Point3 through{x[0] - 2.0 * d * law.normal[0], x[1] - 2.0 * d * law.normal[1], x[2] - 2.0 * d * law.normal[2]};
      return planes[f].cuts(x, through);
    }
  };
  // over the owned rows (on N ranks each rank's, then reduced: a rank's window holds its owned
  // particles' whole rows)
  // crossed, and reached by rock broken near the plane
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i < owned.last; ++i)
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        if (j < i || b.intact[k] != bond_broken) continue;
        const bool fed = wet(i) && wet(j);  // part of the fracture the fluid drives, not stray damage (block corners)
        const Point3 x = point_of(m.reference_position[i], m.reference_position[j]);
        for (std::size_t f = 0; f < out.size(); ++f) {
          const auto& law = ib.laws[f];
          const double d = dot<3>(x - law.point, law.normal);
          if (!within_extent(f, x, d)) continue;
          if (std::abs(d) < crossing_depth * horizon) out[f].reached = true;
          if (!fed || law.near_side == 0 || d * law.near_side >= 0.0) continue;
          out[f].crossing_distance = std::max(out[f].crossing_distance, std::abs(d));
        }
      }
  // dilated: span of the open, wet failed interface bonds
  std::vector<double> lo(out.size(), std::numeric_limits<double>::max()), hi(out.size(), -std::numeric_limits<double>::max());
  std::vector<double> lo2 = lo, hi2 = hi;
  for (const IndexRange& owned : m.owned())
    for (std::size_t i = owned.first; i + 1 < ib.offset.size() && i < owned.last; ++i)
      for (auto q = ib.offset[i]; q < ib.offset[i + 1]; ++q) {
        const auto k = static_cast<std::size_t>(ib.slot[static_cast<std::size_t>(q)]);
        if (b.intact[k] == bond_intact) continue;
        const std::size_t f = ib.interface[static_cast<std::size_t>(q)];
        out[f].reached = true;
        if (b.intact[k] != bond_interface_failed) continue;  // broke as rock: the crossing fracture's, not the interface's opening
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        if (!wet(i) || !wet(j)) continue;
        const auto& law = ib.laws[f];
        if (net.pressure[static_cast<std::size_t>(net.source[i])] <= law.in_situ_normal_compression) continue;  // held shut (EQ 4.7)
        if (!interface_faces_apart<D>(m, static_cast<std::int64_t>(k), i, j, law)) continue;  // open as far as a rock bond breaks
        const Point3 x = point_of(m.reference_position[i], m.reference_position[j]);
        const double t = dot<3>(x - law.point, law.tangent), t2 = dot<3>(x - law.point, law.binormal);
        lo[f] = std::min(lo[f], t), hi[f] = std::max(hi[f], t);
        lo2[f] = std::min(lo2[f], t2), hi2[f] = std::max(hi2[f], t2);
      }
  const auto& ranks = ranks_of<D>(m);
  if (ranks.distributed()) {
    // the largest of each over the ranks: reached, the crossing distance, and the open span's ends
    // (a least value as the largest of its negative)
    std::vector<double> largest;
    for (std::size_t f = 0; f < out.size(); ++f)
      largest.insert(largest.end(), {out[f].reached ? 1.0 : 0.0, out[f].crossing_distance, -lo[f], hi[f], -lo2[f], hi2[f]});
    ranks.max(largest.data(), largest.size());
    for (std::size_t f = 0; f < out.size(); ++f) {
      const double* x = &largest[6 * f];
      out[f].reached = x[0] > 0.0, out[f].crossing_distance = x[1];
      lo[f] = -x[2], hi[f] = x[3], lo2[f] = -x[4], hi2[f] = x[5];
    }
  }
  for (std::size_t f = 0; f < out.size(); ++f) {
    if (hi[f] >= lo[f]) out[f].opened_length = std::max(hi[f] - lo[f], D == 3 ? hi2[f] - lo2[f] : 0.0);
    out[f].dilated = out[f].opened_length >= dilation_span * horizon;
    out[f].crossed = out[f].crossing_distance >= crossing_depth * horizon;
    out[f].reached = out[f].reached || out[f].crossed;
  }
  return out;
}

/// The outcome's records in a run's checkpoint (io/checkpoint.hpp).
template <class A>
void visit(A& a, InterfaceOutcome& o) {
  a("outcome.reached", o.reached), a("outcome.crossed", o.crossed), a("outcome.dilated", o.dilated);
  a("outcome.crossing_distance", o.crossing_distance), a("outcome.opened_length", o.opened_length);
}
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(InterfaceOutcome) == 8 + 2 * 8, "a member was added to InterfaceOutcome: list it in visit above");
#endif

// What the run has seen so far at each interface, as a cut block shows it: the fluid's path once
// made stays (dilated), broken rock stays broken (crossed, reached); lengths are the largest seen.
inline void record_outcomes(std::vector<InterfaceOutcome>& record, const std::vector<InterfaceOutcome>& now) {
  if (record.size() < now.size()) record.resize(now.size());
  for (std::size_t f = 0; f < now.size(); ++f) {
    auto& r = record[f];
    r.reached = r.reached || now[f].reached;
    r.crossed = r.crossed || now[f].crossed;
    r.dilated = r.dilated || now[f].dilated;
    r.crossing_distance = std::max(r.crossing_distance, now[f].crossing_distance);
    r.opened_length = std::max(r.opened_length, now[f].opened_length);
  }
}

}  // namespace rift::geomech
