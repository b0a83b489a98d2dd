// Surface correction by moment matching: position-aware influence functions (Mitchell, Silling and
// Littlewood 2015, J. Mech. Mater. Struct. 10). Each particle i gets its own
//   omega_i(xi) = omega(|xi|) (1 + lambda_i . psi(n)),  psi = even degree-4 monomials of n (3D: 6, 2D: 3),
// lambda_i the smallest change that makes the fourth moments sum_j omega_i w_j |xi|^p n_a n_a n_b n_b
// (p = 1 PMB, 2 LPS) equal a full continuum horizon's. Then W = (c/4) eps : M4 : eps (PMB; LPS: from
// the second and fourth moments) is classical under uniaxial, shear and volumetric strain. Odd moments
// are not matched. The LPS dilatation has its own weights, theta_i = sum_j b_ij e_ij with
// b_ij = omega (mu_i . phi(n)) |xi| V_j, phi the degree-2 monomials, such that sum_j b_ij |xi| n (x) n = I
// (uncorrected: b_ij = d omega |xi| V_j / m_i). Bond forces use t_i + t_j: momentum is conserved.
// The factors are the particle's row (bonds.hpp): factors_of(i, k) for i's side of bond k,
// mirror_factors_of(j, k) for the other; particles whose families are whole share one row per body.
// Why: docs/decisions/method-notes.md.
#pragma once
#include <cstddef>
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::pd {

/// Gives every particle its row of factors (1 and 0 to start with); returns the particles whose rows
/// the two functions below fill (one per shared row, and every particle with a row of its own).
template <int D>
std::vector<std::size_t> assign_factor_rows(Model<D>& m);

template <int D>
void apply_surface_correction(Model<D>& m, const std::vector<std::size_t>& owners);

/// LPS dilatation weights (needs the weighted volumes); nothing to do without LPS bodies.
template <int D>
void compute_dilatation_weights(Model<D>& m, const std::vector<std::size_t>& owners);

}  // namespace rift::pd
