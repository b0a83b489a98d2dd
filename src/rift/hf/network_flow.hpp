// Viscous flow of the fracturing fluid along its network of broken bonds: lubrication, the cubic law
// q = -(w^3 / (12 mu)) grad p per unit width (plane Poiseuille flow); the rock is impermeable. The pressure
// lives on the particles the fluid reaches; a broken bond i-j carries the volume flux C_ij (p_i - p_j),
//   C_ij = V_ij w_ij^3 / (12 mu S(n)),   S(n) = sum_{xi . n > 0} (xi . n) (|xi|^2 - (xi . n)^2) / (D - 1) V_j / V_i,
// and stands for the crack volume V_ij w_ij / N(n), N(n) = sum_{xi . n > 0} (xi . n) V_j / V_i (S, N: the
// means of its ends' sums over a whole family; V_ij partial near the horizon's edge): a straight crack of
// any direction carries the cubic law's flux and holds w per unit area (tests/test_network_flow.cpp).
// w = |y - (I + eps) xi|, the displacement jump, eps the mean of its ends' bulk strains (pd/bulk_strain.hpp),
// n its direction (mode I); across a failed interface bond n is the interface's normal and w its faces'
// normal opening (geomech/interface_contact.hpp); a bond across an interface that broke as rock is a crack's
// bond. Pressure solve: backward Euler of each node's mass balance, SPD (Eigen's sparse LDLT).
// Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "rift/geomech/interface_contact.hpp"
#include "rift/hf/pd_names.hpp"
#include "rift/pd/bulk_strain.hpp"
#include "rift/pd/model.hpp"

namespace rift::hf {

/// The jump of displacement across a bond i-j of reference vector xi: y_ij - (I + eps) xi, eps the
/// mean of the two ends' bulk strains (3 x 3, row-major).
template <int D>
Vec<D> crack_jump(const Model<D>& m, std::size_t i, std::size_t j, const std::array<double, 3>& xi, const std::array<double, 9>& eps_i,
                  const std::array<double, 9>& eps_j) {
  Vec<D> jump{};
  for (int p = 0; p < D; ++p) {
    double strained = xi[p];
    for (int q = 0; q < D; ++q) strained += 0.5 * (eps_i[3 * p + q] + eps_j[3 * p + q]) * xi[q];
    jump[p] = m.position[j][p] - m.position[i][p] - strained;
  }
  return jump;
}

/// Moments of particle i's family about a crack of normal n, over the bonds with xi . n > 0,
/// weighted by V_j / V_i: N = sum (xi . n) (the bonds that cross a unit area of it) and
/// S = sum (xi . n) (|xi|^2 - (xi . n)^2) / (D - 1) (their transverse reach). The family is every
/// bond it ever had: intact or broken, and those a pre-crack cut.
struct CrackMoments {
  double normal = 0.0, transverse = 0.0;
};
template <int D>
CrackMoments crack_moments(const Model<D>& m, std::size_t i, const Vec<D>& n) {
  CrackMoments c;
  auto add = [&](const std::array<double, 3>& xi, double volume) {
    double along = 0.0, squared = 0.0;
    for (int p = 0; p < D; ++p) along += xi[p] * n[p], squared += xi[p] * xi[p];
    if (along <= 0.0) return;
    c.normal += along * volume;
    c.transverse += along * (squared - along * along) * volume;
  };
  const Bonds& b = m.bonds;
  for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) add(b.family_of(k).xi, b.volume(k));
  const CrackBonds& w = m.crack_bonds;
  if (!w.offset.empty())
    for (auto k = w.offset[i]; k < w.offset[i + 1]; ++k)
      if (w.neighbor[static_cast<std::size_t>(k)] >= 0) add(w.xi[static_cast<std::size_t>(k)], w.volume[static_cast<std::size_t>(k)]);
  c.normal /= m.volume[i];
  c.transverse /= (D - 1) * m.volume[i];
  return c;
}

/// A broken bond that carries fluid: its ends, its conductance C and its share of the crack's volume.
struct FlowBond {
  std::size_t i = 0, j = 0;
  double opening = 0.0;      // |jump| (across a failed interface bond its normal part), m
  double conductance = 0.0;  // flux from i to j per unit of p_i - p_j, m^3 / (Pa s)
  double volume = 0.0;       // the crack's volume this bond stands for, m^3
};

/// The bonds that carry fluid between the particles of a list, each once (i < j), with their
/// openings and conductances for a fluid of viscosity mu (Pa s): the broken bonds for which
/// carries(i, k, j) holds (k the bond's index in m.bonds) and the bonds a pre-crack cut for which
/// cut(i, k, j) holds (k its index in m.crack_bonds).
template <int D, class Carries, class Cut>
std::vector<FlowBond> flow_bonds(const Model<D>& m, double viscosity, const std::vector<std::size_t>& particles, Carries carries, Cut cut) {
  const Bonds& b = m.bonds;
  const CrackBonds& cb = m.crack_bonds;
  std::vector<FlowBond> out;
  // the bulk strain of each bond end, once (the particles near the crack, not the model)
  std::unordered_map<std::size_t, std::array<double, 9>> strain;
  auto strain_of = [&](std::size_t i) -> const std::array<double, 9>& {
    auto [it, added] = strain.try_emplace(i);
    if (added) it->second = bulk_strain<D>(m, i);
    return it->second;
  };
  // a bond of opening w and normal n between i and j, V_j its neighbour's volume share
  auto add = [&](std::size_t i, std::size_t j, double w, const Vec<D>& n, double volume) {
    FlowBond f{i, j, w, 0.0, 0.0};
    if (w > 0.0) {
      const CrackMoments ci = crack_moments<D>(m, i, n), cj = crack_moments<D>(m, j, n);
      f.conductance = volume * w * w * w / (6.0 * viscosity * (ci.transverse + cj.transverse));
      f.volume = 2.0 * volume * w / (ci.normal + cj.normal);
    }
    out.push_back(f);
  };
  auto opening = [&](std::size_t i, std::size_t j, const std::array<double, 3>& xi, Vec<D>& n) {
    const Vec<D> jump = crack_jump<D>(m, i, j, xi, strain_of(i), strain_of(j));
    const double w = norm<D>(jump);
    n = w > 0.0 ? (1.0 / w) * jump : Vec<D>{};
    return w;
  };
  for (const std::size_t i : particles) {
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(b.neighbor[static_cast<std::size_t>(k)]);
      if (j <= i || b.intact[static_cast<std::size_t>(k)] == bond_intact || !carries(i, k, j)) continue;
      Vec<D> n{};
      double w = 0.0;
      const auto q = b.intact[static_cast<std::size_t>(k)] == bond_interface_failed ? geomech::interface_entry<D>(m, i, k) : -1;
      if (q >= 0) {  // a failed interface bond: its faces' normal opening
        const auto& law = m.interface_bonds.laws[m.interface_bonds.interface[static_cast<std::size_t>(q)]];
        for (int p = 0; p < D; ++p) n[p] = law.normal[p];
        w = std::max(0.0, geomech::interface_opening<D>(m, i, j, law));
      } else {
        w = opening(i, j, b.family_of(k).xi, n);
      }
      add(i, j, w, n, b.volume(k));
    }
    if (cb.offset.empty()) continue;
    for (auto k = cb.offset[i]; k < cb.offset[i + 1]; ++k) {
      const auto neighbor = cb.neighbor[static_cast<std::size_t>(k)];
      if (neighbor < 0 || static_cast<std::size_t>(neighbor) <= i || !cut(i, k, static_cast<std::size_t>(neighbor))) continue;
      const auto j = static_cast<std::size_t>(neighbor);
      Vec<D> n{};
      const double w = opening(i, j, cb.xi[static_cast<std::size_t>(k)], n);
      add(i, j, w, n, cb.volume[static_cast<std::size_t>(k)]);
    }
  }
  return out;
}

/// Every broken bond of the model between particles that carries(i, j) accepts (no cut bonds).
template <int D, class Carries>
std::vector<FlowBond> flow_bonds(const Model<D>& m, double viscosity, Carries carries) {
  std::vector<std::size_t> all(m.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return flow_bonds<D>(
      m, viscosity, all, [&](std::size_t i, std::int64_t, std::size_t j) { return carries(i, j); },
      [](std::size_t, std::int64_t, std::size_t) { return false; });
}

/// The pressure on the nodes of a flow network: for each free node a,
///   storage_a (p_a - previous_a) + sum_b C_ab (p_a - p_b) = source_a,
/// (backward Euler of the fluid's mass balance, storage = V / (K_f dt); 0 for steady flow), and
/// p_a = fixed_value_a where fixed_a. Nodes are indices into the vectors; bonds join them.
/// A free node that stores nothing and meets no open bond keeps its previous pressure. Throws
/// std::runtime_error where a part of the network stores nothing and meets no fixed node.
inline std::vector<double> solve_network_pressure(const std::vector<FlowBond>& bonds, const std::vector<double>& storage,
                                                  const std::vector<double>& previous, const std::vector<double>& source,
                                                  const std::vector<std::uint8_t>& fixed, const std::vector<double>& fixed_value) {
  const std::size_t n = storage.size();
  // a free node that stores nothing and meets no open bond keeps its previous pressure
  std::vector<std::uint8_t> held(fixed);
  std::vector<double> diagonal(storage);
  for (const auto& f : bonds) diagonal[f.i] += f.conductance, diagonal[f.j] += f.conductance;
  std::vector<double> value(fixed_value);
  for (std::size_t a = 0; a < n; ++a)
    if (!fixed[a] && diagonal[a] == 0.0) held[a] = 1, value[a] = previous[a];
  std::vector<std::int64_t> row(n, -1);
  std::int64_t free_nodes = 0;
  for (std::size_t a = 0; a < n; ++a)
    if (!held[a]) row[a] = free_nodes++;
  std::vector<double> p(value);
  if (free_nodes == 0) return p;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(free_nodes);
  for (std::size_t a = 0; a < n; ++a)
    if (!held[a]) {
      entries.emplace_back(row[a], row[a], storage[a]);
      rhs[row[a]] += storage[a] * previous[a] + source[a];
    }
  for (const auto& f : bonds) {
    const double C = f.conductance;
    if (C == 0.0) continue;
    const auto ra = row[f.i], rb = row[f.j];
    if (ra >= 0) entries.emplace_back(ra, ra, C);
    if (rb >= 0) entries.emplace_back(rb, rb, C);
    if (ra >= 0 && rb >= 0) entries.emplace_back(ra, rb, -C), entries.emplace_back(rb, ra, -C);
    if (ra >= 0 && rb < 0) rhs[ra] += C * value[f.j];
    if (rb >= 0 && ra < 0) rhs[rb] += C * value[f.i];
  }
  Eigen::SparseMatrix<double> A(free_nodes, free_nodes);
  A.setFromTriplets(entries.begin(), entries.end());
  // The fill-reducing ordering and the symbolic factorization (most of a solve: the minimum degree
  // ordering) kept from the calling thread's last solves for the last few patterns (a relaxation's
  // iterations between bond breaks, each with its few cavitation passes, repeat them):
  // analyzePattern() then factorize() is what compute() does, so a kept analysis gives the same bits.
  struct KeptAnalysis {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    std::vector<int> outer, inner;
    std::uint64_t used = 0;
  };
  static thread_local std::array<KeptAnalysis, 4> kept;
  static thread_local std::uint64_t solves = 0;
  const auto outer = A.outerIndexPtr(), inner = A.innerIndexPtr();
  const auto stored = static_cast<std::size_t>(A.nonZeros());
  auto same_pattern = [&](const KeptAnalysis& k) {
    return k.outer.size() == static_cast<std::size_t>(free_nodes) + 1 && k.inner.size() == stored &&
           std::equal(k.outer.begin(), k.outer.end(), outer) && std::equal(k.inner.begin(), k.inner.end(), inner);
  };
  auto found = std::find_if(kept.begin(), kept.end(), same_pattern);
  if (found == kept.end()) {  // the least recently used makes way
    found = std::min_element(kept.begin(), kept.end(), [](const KeptAnalysis& a, const KeptAnalysis& b) { return a.used < b.used; });
    found->outer.clear(), found->inner.clear();  // a throw below leaves nothing kept
    found->solver.analyzePattern(A);
    found->outer.assign(outer, outer + free_nodes + 1), found->inner.assign(inner, inner + stored);
  }
  found->used = ++solves;
  auto& solver = found->solver;
  solver.factorize(A);
  if (solver.info() != Eigen::Success) throw std::runtime_error("network flow: a part of the network holds no fluid and meets no fixed pressure");
  const Eigen::VectorXd x = solver.solve(rhs);
  for (std::size_t a = 0; a < n; ++a)
    if (!held[a]) p[a] = x[row[a]];
  return p;
}

}  // namespace rift::hf
