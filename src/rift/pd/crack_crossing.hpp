// The bonds that cross a fluid-filled crack or its extension past the tip: those whose effective
// stretch the pore pressure shifts (effective_stretch.hpp). The crack's surface is made of patches,
// one at the midpoint of each short broken bond of a network (nearest and diagonal lattice
// neighbours, and the short bonds a pressurized pre-crack cut), each a plane whose normal is the
// principal direction of the short broken bonds around it (the largest eigenvector of the sum of
// n n^T over those within 1.5 spacings: sign-free, so a crack's zigzag of straight and diagonal
// bonds reads as its mean plane). A bond crosses the crack when its ends lie on opposite sides of a
// patch's plane and it pierces the plane within one spacing of the patch's point: across the faces
// (the points of a straight crack lie half a spacing apart), or across the crack's extension just
// past its last broken bond, where the bonds that break next sit. Bonds within a face (parallel to
// it) and beside the crack do not cross it: they carry the total stress.
// The crack grows by the bonds that break across it or its extension, and from a borehole's
// wall; a bond that breaks beside the crack (the rock of a face splitting on the total stress) lets
// the fluid in, but adds no patch. Otherwise the crack's
// surface would run along the faces: in hf_kgd_viscosity (3 mm, confined by 15 MPa) a bond that
// broke just above a tip made a patch a row above the faces, the bonds across it read the
// effective stress of the net pressure beside a short crack as a tension, broke, and made patches
// a row higher: a band of damage nine rows thick in one load step, where the rule alone (no patch
// from such bonds) grows a sharp crack of the right length.
// Whether a bond crosses is pure geometry in the reference configuration. It is asked only of the
// bonds the pore shift would break, and of the bonds that break (to know whether they extend the
// crack): a mark per bond, remade around each new patch, made hf_injection_rate's cube (diffuse
// damage, a network change every time step) several times slower. The patches are remade when a
// network changes, each normal only where a patch within 1.5 spacings came or went.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::pd {

namespace detail {
// x the fastest: the cells of a row along x have consecutive keys
template <int D>
std::int64_t surface_cell_key(const std::array<std::int64_t, D>& c) {
  std::int64_t k = 0;
  for (int q = D - 1; q >= 0; --q) k = k * 2097152 + (c[q] + 1048576);
  return k;
}

template <int D>
std::array<std::int64_t, D> surface_cell_of(const double* x, double cell) {
  std::array<std::int64_t, D> c{};
  for (int q = 0; q < D; ++q) c[q] = static_cast<std::int64_t>(std::floor(x[q] / cell));
  return c;
}

/// Calls f(patch) for every patch in the 3^D cells around x's (x fastest, then y, then z; in a
/// cell in the grid's order) until f returns true. The three cells of a row along x are one range
/// of keys, found by one search.
template <int D, class F>
void for_patches_around(const CrackSurface& s, const double* x, F&& f) {
  const auto c = surface_cell_of<D>(x, s.cell);
  std::array<std::int64_t, D> d{};
  for (int q = 1; q < D; ++q) d[q] = -1;
  while (true) {
    std::array<std::int64_t, D> at{};
    for (int q = 1; q < D; ++q) at[q] = c[q] + d[q];
    at[0] = c[0] - 1;
    const std::int64_t first = surface_cell_key<D>(at), last = first + 2;
    for (auto e = std::lower_bound(s.cell_keys.begin(), s.cell_keys.end(), first); e != s.cell_keys.end() && *e <= last; ++e)
      if (f(s.in_cell[static_cast<std::size_t>(e - s.cell_keys.begin())])) return;
    int q = 1;
    for (; q < D; ++q) {
      if (++d[q] <= 1) break;
      d[q] = -1;
    }
    if (q == D) break;
  }
}
/// Calls f(patch) for every patch in the cells within `margin` of the box around a and b (x
/// fastest: one search per row of cells along x) until f returns true.
template <int D, class F>
void for_patches_near_segment(const CrackSurface& s, const double* a, const double* b, double margin, F&& f) {
  std::array<std::int64_t, D> lo{}, hi{};
  for (int q = 0; q < D; ++q) {
    lo[q] = static_cast<std::int64_t>(std::floor((std::min(a[q], b[q]) - margin) / s.cell));
    hi[q] = static_cast<std::int64_t>(std::floor((std::max(a[q], b[q]) + margin) / s.cell));
  }
  std::array<std::int64_t, D> at = lo;
  while (true) {
    at[0] = lo[0];
    const std::int64_t first = surface_cell_key<D>(at), last = first + (hi[0] - lo[0]);
    for (auto e = std::lower_bound(s.cell_keys.begin(), s.cell_keys.end(), first); e != s.cell_keys.end() && *e <= last; ++e)
      if (f(s.in_cell[static_cast<std::size_t>(e - s.cell_keys.begin())])) return;
    int q = 1;
    for (; q < D; ++q) {
      if (++at[q] <= hi[q]) break;
      at[q] = lo[q];
    }
    if (q == D) break;
  }
}
}  // namespace detail

/// Whether the bond between reference positions a and b crosses the crack surface or its extension:
/// its ends on opposite sides of a patch's plane, which it pierces within `reach` of the patch's
/// point (at most the surface's own reach; by default that), among the patches `accept(p)` takes.
template <int D, class Accept>
bool pierces_crack_if(const CrackSurface& s, const Vec<D>& a, const Vec<D>& b, double reach, Accept accept) {
  if (s.empty()) return false;
  if (reach < 0.0 || reach > s.reach) reach = s.reach;
  // a patch it pierces within reach lies within reach of the bond
  bool crosses = false;
  detail::for_patches_near_segment<D>(s, a.data(), b.data(), reach, [&](std::uint32_t p) {
    if (!accept(p)) return false;
    const auto& plane = s.planes[p];
    double da = 0.0, db = 0.0;
    for (int q = 0; q < D; ++q) da += (a[q] - plane[static_cast<std::size_t>(q)]) * plane[static_cast<std::size_t>(3 + q)],
                                db += (b[q] - plane[static_cast<std::size_t>(q)]) * plane[static_cast<std::size_t>(3 + q)];
    if (!(da * db < 0.0)) return false;  // both ends on one side, or one on the plane
    const double t = da / (da - db);
    double r2 = 0.0;
    for (int q = 0; q < D; ++q) {
      const double e = a[q] + t * (b[q] - a[q]) - plane[static_cast<std::size_t>(q)];
      r2 += e * e;
    }
    crosses = r2 <= reach * reach;
    return crosses;
  });
  return crosses;
}

/// pierces_crack_if over every patch, within the surface's reach.
template <int D>
bool pierces_crack(const CrackSurface& s, const Vec<D>& a, const Vec<D>& b) {
  return pierces_crack_if<D>(s, a, b, -1.0, [](std::uint32_t) { return true; });
}

/// Remakes the crack surface when a network changed (call after update_fluid_network).
template <int D>
void update_crack_surface(Model<D>& m) {
  FluidNetwork& f = m.fluid_network;
  CrackSurface& surface = f.crack_surface;
  if (surface.made && f.network_bonds == f.surface_bonds) return;
  f.surface_bonds = f.network_bonds;
  const Bonds& b = m.bonds;
  const CrackBonds& w = m.crack_bonds;
  const std::size_t n = m.size();
  const bool first = !surface.made;
  const CrackSurface before = std::move(surface);  // its normals serve the patches nothing changed around
  surface = CrackSurface{};
  surface.made = true;
  if (f.source.size() != n) return;
  // the bodies' largest lattice spacing
  double spacing = 0.0;
  for (const auto& body : m.bodies) spacing = std::max(spacing, body.constants.spacing);
  const double short_bond = 1.5 * spacing;  // nearest and diagonal neighbours
  surface.reach = (1.0 + 1e-9) * spacing;   // a lattice neighbour's crossing included
  struct Seed {
    std::int64_t key;
    std::array<double, 3> point, direction;
  };
  std::vector<Seed> seeds;
  auto add_seed = [&](std::int64_t key, std::size_t i, const std::array<double, 3>& xi, double length) {
    if (length > short_bond) return;
    Seed p{key, {}, {}};
    for (int q = 0; q < D; ++q) p.point[static_cast<std::size_t>(q)] = m.reference_position[i][q] + 0.5 * xi[static_cast<std::size_t>(q)],
                                p.direction[static_cast<std::size_t>(q)] = xi[static_cast<std::size_t>(q)] / length;
    seeds.push_back(p);
  };
  // a particle on a borehole's wall: a pressure bond to a fluid site as short as a lattice neighbour
  auto on_wall = [&](std::size_t i) {
    if (w.offset.size() != n + 1) return false;
    for (auto q = w.offset[i]; q < w.offset[i + 1]; ++q)
      if (w.neighbor[static_cast<std::size_t>(q)] < 0 && w.length(static_cast<std::size_t>(q)) <= short_bond) return true;
    return false;
  };
  for (const auto& bonds : f.network_bonds)
    for (const auto k : bonds) {
      const auto i = b.row_of(k);
      const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
      if (j < i) continue;
      // the crack grows by the bonds that break across it or its extension, and from a borehole's
      // wall; a bond that breaks beside it (a face's rock splitting) does not extend it (before the
      // surface is first made, every broken bond is the crack's: a scene's initial state)
      const bool crossed = std::binary_search(f.crossing_broken.begin(), f.crossing_broken.end(), k);
      if (!first && !crossed && !on_wall(i) && !on_wall(j)) continue;
      add_seed(k, i, b.family_of(k).xi, b.length(k));
    }
  // the short bonds a pre-crack cut, where a fluid (its own or one that reached it) fills it
  if (w.offset.size() == n + 1)
    for (std::size_t i = 0; i < n; ++i) {
      if (f.source[i] < 0) continue;
      for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k) {
        const auto j = w.neighbor[static_cast<std::size_t>(k)];
        if (j < 0 || static_cast<std::size_t>(j) < i || f.source[static_cast<std::size_t>(j)] != f.source[i]) continue;
        add_seed(-1 - k, i, w.xi[static_cast<std::size_t>(k)], w.length(static_cast<std::size_t>(k)));
      }
    }
  if (seeds.empty()) return;
  std::sort(seeds.begin(), seeds.end(), [](const Seed& a, const Seed& c) { return a.key < c.key; });
  // the grid of the patches' points, cell size 1.5 spacings first: each normal is the principal
  // direction of the short broken bonds within 1.5 spacings
  auto make_grid = [&](double cell) {
    surface.cell = cell;
    std::vector<std::pair<std::int64_t, std::uint32_t>> entries(seeds.size());
    for (std::size_t p = 0; p < seeds.size(); ++p)
      entries[p] = {detail::surface_cell_key<D>(detail::surface_cell_of<D>(seeds[p].point.data(), cell)), static_cast<std::uint32_t>(p)};
    std::sort(entries.begin(), entries.end());
    surface.cell_keys.resize(entries.size()), surface.in_cell.resize(entries.size());
    for (std::size_t e = 0; e < entries.size(); ++e) surface.cell_keys[e] = entries[e].first, surface.in_cell[e] = entries[e].second;
  };
  make_grid(short_bond);
  surface.patches.resize(seeds.size());
  surface.planes.resize(seeds.size());
  // a patch keeps its normal unless a patch within 1.5 spacings came or went: the new patches and
  // those the old surface had that are gone mark their neighbourhoods
  std::vector<std::uint8_t> turn(seeds.size(), 0);
  std::vector<std::int64_t> kept_from(seeds.size(), -1);  // the old surface's index of each kept patch
  auto mark_around = [&](const double* x) {
    detail::for_patches_around<D>(surface, x, [&](std::uint32_t o) {
      turn[o] = 1;
      return false;
    });
  };
  for (std::size_t p = 0, o = 0; p < seeds.size() || o < before.patches.size();) {
    if (o == before.patches.size() || (p < seeds.size() && seeds[p].key < before.patches[o])) {
      mark_around(seeds[p++].point.data());
    } else if (p == seeds.size() || before.patches[o] < seeds[p].key) {
      mark_around(before.planes[o++].data());
    } else {
      kept_from[p++] = static_cast<std::int64_t>(o++);
    }
  }
  for (std::size_t p = 0; p < seeds.size(); ++p) {
    surface.patches[p] = seeds[p].key;
    if (!turn[p] && kept_from[p] >= 0) {
      surface.planes[p] = before.planes[static_cast<std::size_t>(kept_from[p])];
      continue;
    }
    Eigen::Matrix<double, D, D> t = Eigen::Matrix<double, D, D>::Zero();
    detail::for_patches_around<D>(surface, seeds[p].point.data(), [&](std::uint32_t o) {
      double r2 = 0.0;
      for (int q = 0; q < D; ++q) {
        const double e = seeds[o].point[static_cast<std::size_t>(q)] - seeds[p].point[static_cast<std::size_t>(q)];
        r2 += e * e;
      }
      if (r2 > short_bond * short_bond) return false;
      Eigen::Matrix<double, D, 1> v;
      for (int q = 0; q < D; ++q) v[q] = seeds[o].direction[static_cast<std::size_t>(q)];
      t += v * v.transpose();
      return false;
    });
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eigen(t);
    const auto v = eigen.eigenvectors().col(D - 1);  // the largest eigenvalue's
    surface.planes[p] = {};
    for (int q = 0; q < D; ++q) surface.planes[p][static_cast<std::size_t>(q)] = seeds[p].point[static_cast<std::size_t>(q)],
                                surface.planes[p][static_cast<std::size_t>(3 + q)] = v[q];
  }
  make_grid(surface.reach);  // for pierces_crack_if: a pierced patch lies within reach of the bond
}

/// Keeps the bonds just broken that crossed the crack (pairs (i, k): row i's entry k), both entries.
template <int D>
void record_crossing_breaks(Model<D>& m, const std::vector<std::pair<std::size_t, std::int64_t>>& crossed) {
  if (crossed.empty()) return;
  const Bonds& b = m.bonds;
  auto& kept = m.fluid_network.crossing_broken;
  const std::size_t before = kept.size();
  for (const auto& [i, k] : crossed) {
    const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
    const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
    kept.push_back(k);
    kept.push_back(std::lower_bound(first, last, static_cast<std::int32_t>(i)) - b.neighbor.begin());
  }
  std::sort(kept.begin() + static_cast<std::ptrdiff_t>(before), kept.end());
  std::inplace_merge(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(before), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
}

}  // namespace rift::pd
