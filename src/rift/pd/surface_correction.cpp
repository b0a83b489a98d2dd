#include "rift/pd/surface_correction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "rift/pd/influence.hpp"
#include "rift/pd/laws/registry.hpp"
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

}  // namespace

template <int D>
std::vector<std::size_t> assign_factor_rows(Model<D>& m) {
  Bonds& b = m.bonds;
  b.factor_row.assign(m.size(), 0);
  b.factors.clear();
  std::vector<std::size_t> owners;
  for (const auto& body : m.bodies) {
    const std::size_t count = body.family_count, first_family = body.first_family;
    // without the correction a particle's factors are all 1, whatever its family, and the LPS and
    // VES dilatation weights d omega |xi| / m_i are taken in the passes (lps.hpp dilatation_scale)
    const bool uniform = !body.constants.surface_correction;
    std::int64_t shared = 0;
    bool have_shared = false;
    for (std::size_t i = body.first; i < body.last; ++i) {
      const bool whole = uniform || static_cast<std::size_t>(b.offset[i + 1] - b.offset[i]) == count;
      if (whole && have_shared) {
        b.factor_row[i] = shared;
        continue;
      }
      b.factor_row[i] = static_cast<std::int64_t>(b.factors.size()) - static_cast<std::int64_t>(first_family);
      if (whole) shared = b.factor_row[i], have_shared = true;
      b.factors.resize(b.factors.size() + count);
      owners.push_back(i);
    }
  }
  return owners;
}

template <int D>
void apply_surface_correction(Model<D>& m, const std::vector<std::size_t>& owners) {
  Bonds& b = m.bonds;
  const auto exps = quartic_exponents<D>();
  const int na = static_cast<int>(exps.size());
  const std::vector<LawTraits> laws = body_laws(m.bodies);
#pragma omp parallel for if(rift::parallel::worth_a_team(owners.size())) schedule(dynamic, 64)
  for (std::size_t o = 0; o < owners.size(); ++o) {
    const std::size_t i = owners[o];
    const auto& c = m.constants_of(i);
    if (!c.surface_correction) continue;
    const int p = laws[m.body[i]].energy_moment_power;  // weight |xi|^p of the energy moment
    // continuum moment int_ball omega |xi|^p dV
    const double full = family_moment(D, c.influence, c.horizon, c.thickness, p);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(na, na);
    Eigen::VectorXd rhs(na);
    for (int a = 0; a < na; ++a) rhs[a] = full * isotropic_mean(D, exps[static_cast<std::size_t>(a)]);
    Eigen::VectorXd psi(na);
    auto monomials = [&](const FamilyOffset& f) {
      for (int a = 0; a < na; ++a) {
        const auto& e = exps[static_cast<std::size_t>(a)];
        psi[a] = ipow(f.xi[0] / f.length, e[0]) * ipow(f.xi[1] / f.length, e[1]) * (D == 3 ? ipow(f.xi[2] / f.length, e[2]) : 1.0);
      }
    };
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const FamilyOffset& f = b.family_of(k);
      const double base = influence(c.influence, f.length, c.horizon) * ipow(f.length, p) * f.volume;
      monomials(f);
      A.noalias() += base * psi * psi.transpose();
      rhs -= base * psi;  // moments of the uncorrected family
    }
    // smallest-norm change of the influence function that matches the moments
    Eigen::VectorXd lambda = A.completeOrthogonalDecomposition().solve(rhs);
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      monomials(b.family_of(k));
      b.factors[static_cast<std::size_t>(b.factor_row[i] + b.family[static_cast<std::size_t>(k)])].correction =
          static_cast<float>(1.0 + lambda.dot(psi));
    }
  }
}

template <int D>
void compute_dilatation_weights(Model<D>& m, const std::vector<std::size_t>& owners) {
  Bonds& b = m.bonds;
  constexpr int nq = D == 3 ? 6 : 3;  // degree-2 monomials n_a n_b, a <= b
  std::array<std::array<int, 2>, nq> pairs{};
  {
    int q = 0;
    for (int a = 0; a < D; ++a)
      for (int c = a; c < D; ++c) pairs[static_cast<std::size_t>(q++)] = {a, c};
  }
  const std::vector<LawTraits> laws = body_laws(m.bodies);
#pragma omp parallel for if(rift::parallel::worth_a_team(owners.size())) schedule(dynamic, 64)
  for (std::size_t o = 0; o < owners.size(); ++o) {
    const std::size_t i = owners[o];
    const auto& c = m.constants_of(i);
    if (!laws[m.body[i]].state_based) continue;
    auto weight = [&](std::int64_t k) -> float& {
      return b.factors[static_cast<std::size_t>(b.factor_row[i] + b.family[static_cast<std::size_t>(k)])].dilatation_weight;
    };
    if (!c.surface_correction) continue;  // d omega |xi| / m_i, taken in the passes (lps.hpp dilatation_scale)
    // b_ij = omega |xi| (mu . phi(n)) with sum_j b_ij V_j |xi| n_a n_b = delta_ab
    Eigen::Matrix<double, nq, nq> A = Eigen::Matrix<double, nq, nq>::Zero();
    Eigen::Matrix<double, nq, 1> rhs, phi;
    for (int q = 0; q < nq; ++q) rhs[q] = pairs[static_cast<std::size_t>(q)][0] == pairs[static_cast<std::size_t>(q)][1] ? 1.0 : 0.0;
    auto monomials = [&](const FamilyOffset& f) {
      for (int q = 0; q < nq; ++q)
        phi[q] = (f.xi[static_cast<std::size_t>(pairs[static_cast<std::size_t>(q)][0])] / f.length) *
                 (f.xi[static_cast<std::size_t>(pairs[static_cast<std::size_t>(q)][1])] / f.length);
    };
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const FamilyOffset& f = b.family_of(k);
      monomials(f);
      A.noalias() += influence(c.influence, f.length, c.horizon) * f.length * f.length * f.volume * phi * phi.transpose();
    }
    Eigen::Matrix<double, nq, 1> mu = A.completeOrthogonalDecomposition().solve(rhs);
    for (auto k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const FamilyOffset& f = b.family_of(k);
      monomials(f);
      weight(k) = static_cast<float>(influence(c.influence, f.length, c.horizon) * f.length * mu.dot(phi));
    }
  }
}

template std::vector<std::size_t> assign_factor_rows<2>(Model<2>&);
template std::vector<std::size_t> assign_factor_rows<3>(Model<3>&);
template void apply_surface_correction<2>(Model<2>&, const std::vector<std::size_t>&);
template void apply_surface_correction<3>(Model<3>&, const std::vector<std::size_t>&);
template void compute_dilatation_weights<2>(Model<2>&, const std::vector<std::size_t>&);
template void compute_dilatation_weights<3>(Model<3>&, const std::vector<std::size_t>&);

}  // namespace rift::pd
