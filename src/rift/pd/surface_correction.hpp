// Surface correction (Madenci and Oterkus 2014, "Peridynamic Theory and Its Applications",
// sec. 4.2 for bonds, sec. 6 for state-based): particles near a free surface miss part of their
// family and are too soft. For each particle and axis k, a uniaxial strain eps along k is applied
// to its family; the ratio of the classical strain energy density (or dilatation) to the
// peridynamic one gives g_k(i). A bond i-j takes the mean g_k of its two ends, combined over its
// direction n by the ellipsoid rule  G = (sum_k (n_k / g_k)^2)^(-1/2). G is symmetric, so momentum
// is conserved. PMB: G scales the bond stiffness. LPS: G_theta scales the bond's share of the
// dilatation and G_d its deviatoric energy (forces follow from that energy, see lps.hpp).
#pragma once
#include "rift/pd/model.hpp"

namespace rift::pd {

template <int D>
void apply_surface_correction(Model<D>& m);

}  // namespace rift::pd
