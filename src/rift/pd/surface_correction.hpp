// Surface correction by moment matching. Near a free surface a particle misses part of its family
// and is too soft; on a lattice even bulk families are slightly anisotropic. Following the
// position-aware idea of Mitchell, Silling and Littlewood (2015, "A position-aware linear solid
// constitutive model for peridynamics", J. Mech. Mater. Struct. 10), each particle i gets its own
// influence function  omega_i(xi) = omega(|xi|) (1 + lambda_i . psi(n)),  psi = the even degree-4
// monomials of the bond direction n (n_x^4, n_x^2 n_y^2, ...: 6 in 3D, 3 in 2D; on the unit sphere
// they also span 1 and n_x^2, ...). lambda_i is the smallest change that makes these fourth moments
//   sum_j omega_i w_j |xi|^p n_a n_a n_b n_b   (p = 1 for PMB, 2 for LPS)
// equal to those of a full continuum horizon. The strain energy density is W = (c/4) eps : M4 : eps
// (PMB) or, for LPS, built from the second and fourth moments, so every particle then has the
// classical energy under uniaxial, shear and volumetric strain and the exact dilatation. Odd moments
// (n_x^3 n_y, ...) are left alone: at edges and corners no positive influence function can make them
// vanish (they only couple normal to shear strain there), and matching them drives the factors
// negative.
// LPS also needs the dilatation exact for every affine deformation, which involves the second
// moments including n_x n_y; at edges no positive weight gives that, but the dilatation enters the
// energy only as kappa/2 theta^2, which stays positive for weights of any sign. So, as the
// position-aware LPS does, the dilatation gets its own weights theta_i = sum_j b_ij e_ij with
// b_ij = omega (mu_i . phi(n)) |xi| V_j, phi = all degree-2 monomials, such that
// sum_j b_ij |xi| n (x) n = I (uncorrected: b_ij = d omega |xi| V_j / m_i).
// Bond forces use t_i + t_j, so momentum is conserved with per-particle influence functions.
// Both live in the particle's row of factors (bonds.hpp): bonds.factors_of(i, k) for i's side of
// bond k, bonds.mirror_factors_of(j, k) for the other side. Particles whose families are whole share
// one row per body (their factors are equal: the same offsets, the same moments).
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
