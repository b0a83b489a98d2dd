// Bond failure on the normal stress along the bond (material key bond_failure = "normal_stress"): a
// Rankine criterion. The stress of particle i is Hooke's law of the small strain of the intact rock
// around it, the correspondence deformation gradient of its intact bonds (bulk_strain.hpp; Silling
// et al. 2007, sec. 18):
//   sigma_i = kappa tr(eps_i) I + 2 G (eps_i - tr(eps_i) I / d),
// exact for every homogeneous deformation, beside free surfaces and cracks too (the bond-pair stress
// of stress.hpp is not: its families are cut there). The bond i-j breaks when
//   sigma_n = 1/2 (n . sigma_i . n + n . sigma_j . n) > T,   n = y_ij / |y_ij|,
// T the tensile strength. In the stretch units of the other criterion, sigma_n / (d kappa) > s0 with
// s0 = T / (d kappa), the stretch of a uniform expansion under the stress T: the effective stretch's
// pore shift p / (d kappa) (effective_stretch.hpp) is then the pore pressure added to sigma_n
// (Terzaghi), and the stretch limits are shared. The stress is that of the last force evaluation
// (each pass breaks on the stress of the one before, as LAMMPS lags s0); the VES's is its
// instantaneous elastic one.
// Why: a bond's stretch is not its tension. Under a uniaxial compression a bond across it is
// stretched by the Poisson effect (plane strain: nu (1 + nu) sigma / E), and a stretch criterion
// breaks it where no stress is tensile (Zhou et al. 2008's test S-1, 15 / 0 MPa: 5.0e-4, above the
// s00 of hf_zhou_crossing). The LPS force state is no measure of tension either: it weighs the
// deviatoric extension d + 2 times more than the stress does.
// Its cracks are not yet calibrated: the crack-growth probe of tests/test_crack_growth.cpp
// with T = 5 MPa (LPS, E = 10 GPa, horizon 3.015 spacings of 2 mm) runs at 0.8 K_Ic (G0 = 50 J/m^2)
// and breaks 46 bonds off the crack's line per column it grows: ahead of a mode I tip
// sigma_xx = sigma_yy, so bonds of every direction there pass T together, in a band.
#pragma once
#include "rift/core/vec.hpp"
#include "rift/pd/bulk_strain.hpp"
#include "rift/pd/model.hpp"
#include "rift/parallel/team.hpp"

namespace rift::pd {

/// Components of a symmetric stress record: xx, yy, xy (2D); xx, yy, zz, xy, yz, xz (3D).
template <int D>
constexpr int stress_components = D == 2 ? 3 : 6;

/// n . s . n for a stress record s and a unit vector n: the normal stress along n.
template <int D>
inline double normal_component(const double* s, const Vec<D>& n) {
  if constexpr (D == 2) return s[0] * n[0] * n[0] + s[1] * n[1] * n[1] + 2.0 * s[2] * n[0] * n[1];
  else
    return s[0] * n[0] * n[0] + s[1] * n[1] * n[1] + s[2] * n[2] * n[2] + 2.0 * (s[3] * n[0] * n[1] + s[4] * n[1] * n[2] + s[5] * n[0] * n[2]);
}

/// The stress of every particle of the bodies whose bonds fail on it (into m.failure_stress), from
/// the current positions. Call after each force evaluation.
template <int D>
void update_failure_stress(Model<D>& m) {
  constexpr int C = stress_components<D>;
  for (const auto& body : m.bodies) {
    const auto& c = body.constants;
    if (!c.normal_stress_failure) continue;
#pragma omp parallel for if(rift::parallel::worth_a_team(body.last - body.first)) schedule(static)
    for (std::size_t i = body.first; i < body.last; ++i) {
      const auto eps = bulk_strain<D>(m, i);
      double trace = 0.0;
      for (int p = 0; p < D; ++p) trace += eps[4 * p];
      const double mean = c.kappa * trace - 2.0 * c.shear_modulus * trace / D;  // the diagonal's shared part
      double* s = &m.failure_stress[C * i];
      for (int p = 0; p < D; ++p) s[p] = mean + 2.0 * c.shear_modulus * eps[4 * p];
      if constexpr (D == 2) {
        s[2] = 2.0 * c.shear_modulus * eps[1];
      } else {
        s[3] = 2.0 * c.shear_modulus * eps[1];
        s[4] = 2.0 * c.shear_modulus * eps[5];
        s[5] = 2.0 * c.shear_modulus * eps[2];
      }
    }
  }
}

}  // namespace rift::pd
