// Bond failure on the normal stress along the bond (material key bond_failure = "normal_stress"): a Rankine
// criterion. The strain of particle i is the small strain of the intact rock around it, the correspondence
// deformation gradient of its intact bonds (bulk_strain.hpp; Silling et al. 2007, sec. 18), exact for every
// homogeneous deformation, beside free surfaces and cracks too. Bond i-j of stretch s along n = y_ij / |y_ij|
// breaks when
//   sigma_n = lambda (tr eps - n . eps . n) + (lambda + 2 G) s > T,
// eps the mean of its ends' strains, lambda Lame's first parameter, T the tensile strength: Hooke's
// n . sigma . n with the bond's own stretch for the strain along n (the same for a homogeneous deformation).
// A strength criterion: the toughness goes with sqrt(delta). In stretch units, sigma_n / (d kappa) > s0 with
// s0 = T / (d kappa): the pore shift p / (d kappa) (hf/wet_rock.hpp) adds the pore pressure (Terzaghi),
// and the stretch limits are shared. The strain is that of the current positions, over the bonds intact
// before the pass. Why, and what was measured: docs/decisions/hydraulic-fracture-notes.md.
#pragma once
#include "rift/core/vec.hpp"
#include "rift/pd/bulk_strain.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Components of a symmetric stress record: xx, yy, xy (2D); xx, yy, zz, xy, yz, xz (3D).
template <int D>
constexpr int stress_components = D == 2 ? 3 : 6;

/// n . s . n for a symmetric record s (strain or stress) and a unit vector n: the normal component along n.
template <int D>
inline double normal_component(const double* s, const Vec<D>& n) {
  if constexpr (D == 2) return s[0] * n[0] * n[0] + s[1] * n[1] * n[1] + 2.0 * s[2] * n[0] * n[1];
  else
    return s[0] * n[0] * n[0] + s[1] * n[1] * n[1] + s[2] * n[2] * n[2] + 2.0 * (s[3] * n[0] * n[1] + s[4] * n[1] * n[2] + s[5] * n[0] * n[2]);
}

/// tr s of a symmetric record.
template <int D>
inline double trace_of(const double* s) {
  double t = 0.0;
  for (int p = 0; p < D; ++p) t += s[p];
  return t;
}

/// The normal stress along a bond of stretch s and direction n whose ends have the strain records
/// eps_i and eps_j: lambda (tr eps - n . eps . n) + (lambda + 2 G) s, eps their mean (lambda and
/// lambda + 2 G: MaterialConstants::lame_lambda and p_wave_modulus).
template <int D>
inline double bond_normal_stress(const double* eps_i, const double* eps_j, const Vec<D>& n, double stretch, double lambda,
                                 double p_wave_modulus) {
  const double lateral = 0.5 * (trace_of<D>(eps_i) - normal_component<D>(eps_i, n) + trace_of<D>(eps_j) - normal_component<D>(eps_j, n));
  return lambda * lateral + p_wave_modulus * stretch;
}

/// The strain of every particle of the bodies whose bonds fail on the normal stress and may break
/// now (into m.failure_strain), from the current positions. Call before the pass that breaks bonds.
/// While breaking is held (HeldBreaking: the in-situ stage, the iterations of breaking at
/// equilibrium) nothing reads it, and the pass, a quarter of an iteration's time, is skipped.
template <int D>
void update_failure_strain(Model<D>& m) {
  constexpr int C = stress_components<D>;
  for (const auto& body : m.bodies) {
    if (!body.constants.normal_stress_failure || !body.constants.breakable) continue;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) {
      const auto eps = bulk_strain<D>(m, i);
      double* e = &m.failure_strain[C * i];
      for (int p = 0; p < D; ++p) e[p] = eps[4 * p];
      if constexpr (D == 2) {
        e[2] = eps[1];
      } else {
        e[3] = eps[1];
        e[4] = eps[5];
        e[5] = eps[2];
      }
    }
  }
}

}  // namespace rift::pd
