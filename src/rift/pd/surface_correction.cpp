#include "rift/pd/surface_correction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

namespace {

/// Exponents (p, q, r) of the even degree-4 monomials in D variables: n_x^4, n_x^2 n_y^2, ...
template <int D>
std::vector<std::array<int, 3>> quartic_exponents() {
  std::vector<std::array<int, 3>> e;
  for (int p = 4; p >= 0; p -= 2)
    for (int q = 4 - p; q >= 0; q -= 2) {
      int r = 4 - p - q;
      if (D == 2 && r != 0) continue;
      e.push_back({p, q, r});
    }
  return e;
}

double ipow(double x, int p) {
  double r = 1.0;
  for (int i = 0; i < p; ++i) r *= x;
  return r;
}

/// Mean of n_x^p n_y^q n_z^r over directions of a full D-ball: (p-1)!!(q-1)!!(r-1)!! / (D (D+2)) for even exponents.
double isotropic_mean(int D, const std::array<int, 3>& e) {
  auto dfact = [](int k) { return k <= 0 ? 1.0 : (k == 1 ? 1.0 : (k == 3 ? 3.0 : 15.0)); };
  for (int x : e)
    if (x % 2) return 0.0;
  return dfact(e[0] - 1) * dfact(e[1] - 1) * dfact(e[2] - 1) / double(D * (D + 2));
}

/// mirror[k] = side value of the bond j-i for bond k = i-j (rows are sorted by neighbour).
void mirror_values(const Bonds& b, const std::vector<float>& side, std::vector<float>& mirror) {
  const auto n = static_cast<std::int64_t>(b.offset.size()) - 1;
#pragma omp parallel for if(rift::parallel::worth_a_team(static_cast<std::size_t>(n))) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const auto j = b.neighbor[k];
      const auto first = b.neighbor.begin() + b.offset[j], last = b.neighbor.begin() + b.offset[j + 1];
      auto it = std::lower_bound(first, last, static_cast<std::int32_t>(i));
      mirror[k] = side[static_cast<std::size_t>(it - b.neighbor.begin())];
    }
}

}  // namespace

template <int D>
void apply_surface_correction(Model<D>& m) {
  Bonds& b = m.bonds;
  const auto exps = quartic_exponents<D>();
  const int na = static_cast<int>(exps.size());
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    if (!c.surface_correction) continue;
    const int p = c.model == scene::ModelKind::pmb ? 1 : 2;  // weight |xi|^p of the energy moment
    // continuum moment int_ball omega |xi|^p dV
    const double full = family_moment(D, c.influence, c.horizon, c.thickness, p);
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(dynamic, 64)
    for (std::size_t i = body.first; i < body.last; ++i) {
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(na, na);
      Eigen::VectorXd rhs(na);
      for (int a = 0; a < na; ++a) rhs[a] = full * isotropic_mean(D, exps[static_cast<std::size_t>(a)]);
      Eigen::VectorXd psi(na);
      auto monomials = [&](std::size_t j, double xi) {
        const Vec<D> n = (1.0 / xi) * (m.reference_position[j] - m.reference_position[i]);
        for (int a = 0; a < na; ++a) {
          const auto& e = exps[static_cast<std::size_t>(a)];
          psi[a] = ipow(n[0], e[0]) * ipow(n[1], e[1]) * (D == 3 ? ipow(n[D - 1], e[2]) : 1.0);
        }
      };
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const double xi = b.length[k];
        const double base = influence(c.influence, xi, c.horizon) * ipow(xi, p) * b.volume[k];
        monomials(static_cast<std::size_t>(b.neighbor[k]), xi);
        A.noalias() += base * psi * psi.transpose();
        rhs -= base * psi;  // moments of the uncorrected family
      }
      // smallest-norm change of the influence function that matches the moments
      Eigen::VectorXd lambda = A.completeOrthogonalDecomposition().solve(rhs);
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        monomials(static_cast<std::size_t>(b.neighbor[k]), b.length[k]);
        b.correction[k] = static_cast<float>(1.0 + lambda.dot(psi));
      }
    }
  }
  mirror_values(b, b.correction, b.mirror_correction);
}

template <int D>
void compute_dilatation_weights(Model<D>& m) {
  Bonds& b = m.bonds;
  bool any_lps = false;
  for (const auto& body : m.bodies) any_lps = any_lps || body.constants.state_based();
  if (!any_lps) return;
  b.dilatation_weight.assign(b.neighbor.size(), 0.0f);
  b.mirror_dilatation_weight.assign(b.neighbor.size(), 0.0f);
  constexpr int nq = D == 3 ? 6 : 3;  // degree-2 monomials n_a n_b, a <= b
  std::array<std::array<int, 2>, nq> pairs{};
  {
    int q = 0;
    for (int a = 0; a < D; ++a)
      for (int c = a; c < D; ++c) pairs[static_cast<std::size_t>(q++)] = {a, c};
  }
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    if (!c.state_based()) continue;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(dynamic, 64)
    for (std::size_t i = body.first; i < body.last; ++i) {
      if (!c.surface_correction) {
        for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k)
          b.dilatation_weight[k] = static_cast<float>(D * influence(c.influence, b.length[k], c.horizon) * b.length[k] /
                                                      m.weighted_volume[i]);
        continue;
      }
      // b_ij = omega |xi| (mu . phi(n)) with sum_j b_ij V_j |xi| n_a n_b = delta_ab
      Eigen::Matrix<double, nq, nq> A = Eigen::Matrix<double, nq, nq>::Zero();
      Eigen::Matrix<double, nq, 1> rhs, phi;
      for (int q = 0; q < nq; ++q) rhs[q] = pairs[static_cast<std::size_t>(q)][0] == pairs[static_cast<std::size_t>(q)][1] ? 1.0 : 0.0;
      auto monomials = [&](auto k) {
        const auto j = static_cast<std::size_t>(b.neighbor[k]);
        const Vec<D> n = (1.0 / b.length[k]) * (m.reference_position[j] - m.reference_position[i]);
        for (int q = 0; q < nq; ++q) phi[q] = n[pairs[static_cast<std::size_t>(q)][0]] * n[pairs[static_cast<std::size_t>(q)][1]];
      };
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        monomials(k);
        const double xi = b.length[k];
        A.noalias() += influence(c.influence, xi, c.horizon) * xi * xi * b.volume[k] * phi * phi.transpose();
      }
      Eigen::Matrix<double, nq, 1> mu = A.completeOrthogonalDecomposition().solve(rhs);
      for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        monomials(k);
        b.dilatation_weight[k] = static_cast<float>(influence(c.influence, b.length[k], c.horizon) * b.length[k] * mu.dot(phi));
      }
    }
  }
  mirror_values(b, b.dilatation_weight, b.mirror_dilatation_weight);
}

template void apply_surface_correction<2>(Model<2>&);
template void apply_surface_correction<3>(Model<3>&);
template void compute_dilatation_weights<2>(Model<2>&);
template void compute_dilatation_weights<3>(Model<3>&);

}  // namespace rift::pd
