// Continuum constitutive models shared by the material point method (and, later, peridynamic
// correspondence). Small-strain models integrate the rate of deformation objectively (stress
// rotated with the material's spin); the neo-Hookean model
// uses the deformation gradient. In 2D the tensors are 2 x 2: plane strain uses lambda, G;
// plane stress uses the reduced lambda* = 2 lambda G / (lambda + 2 G) (linear elastic only).
#pragma once
#include <Eigen/Dense>
#include <cmath>

namespace rift::material {

template <int D>
using Tensor = Eigen::Matrix<double, D, D>;

enum class Kind { linear_elastic, neo_hookean, j2_plasticity };

struct Constants {
  Kind kind = Kind::linear_elastic;
  double density = 0.0, lambda = 0.0, shear_modulus = 0.0, bulk_modulus = 0.0;
  double yield_stress = 0.0, hardening_modulus = 0.0;  // J2, linear isotropic hardening
  /// Dilatational wave speed sqrt((lambda + 2G) / rho) (for the stable time step).
  double wave_speed() const { return std::sqrt((lambda + 2.0 * shear_modulus) / density); }
};

/// Per-particle state of a constitutive model.
template <int D>
struct State {
  Tensor<D> stress = Tensor<D>::Zero();
  Tensor<D> strain = Tensor<D>::Zero();          // small-strain models: accumulated strain
  Tensor<D> plastic_strain = Tensor<D>::Zero();  // J2
  double equivalent_plastic_strain = 0.0;        // J2
};

/// Cauchy stress update over a step with velocity gradient L, new deformation gradient F.
template <int D>
void update_stress(const Constants& c, State<D>& s, const Tensor<D>& L, const Tensor<D>& F, double dt) {
  const Tensor<D> I = Tensor<D>::Identity();
  if (c.kind == Kind::neo_hookean) {
    // sigma = mu/J (F F^T - I) + lambda ln J / J I (compressible neo-Hookean)
    const double J = F.determinant();
    s.stress = c.shear_modulus / J * (F * F.transpose() - I) + c.lambda * std::log(J) / J * I;
    return;
  }
  // objective update (Hughes and Winget 1980): the stress and strain of the previous step turn
  // with the material by the incremental rotation of the spin W = (L - L^T)/2,
  //   R = (I - W dt/2)^-1 (I + W dt/2),
  // then the rate of deformation D = (L + L^T)/2 adds its elastic increment. Without the rotation a
  // stressed body that turns (a bending beam's arms) gains spurious stress of order angle x stress.
  const Tensor<D> half_spin = 0.25 * dt * (L - L.transpose());
  const Tensor<D> R = (I - half_spin).inverse() * (I + half_spin);
  s.stress = R * s.stress * R.transpose();
  s.strain = R * s.strain * R.transpose();
  // only J2 has plastic strain; the other models' stays zero, and R 0 R^T is zero
  if (c.kind == Kind::j2_plasticity) s.plastic_strain = R * s.plastic_strain * R.transpose();
  const Tensor<D> de = 0.5 * dt * (L + L.transpose());
  s.strain += de;
  Tensor<D> trial = s.stress + c.lambda * de.trace() * I + 2.0 * c.shear_modulus * de;
  if (c.kind == Kind::j2_plasticity) {
    // radial return with linear isotropic hardening (Simo and Hughes 1998, box 3.1); the
    // out-of-plane stress of plane strain is not tracked (2D: in-plane deviator)
    const Tensor<D> dev = trial - trial.trace() / D * I;
    const double q = std::sqrt(1.5 * dev.squaredNorm());
    const double yield = c.yield_stress + c.hardening_modulus * s.equivalent_plastic_strain;
    if (q > yield) {
      const double dp = (q - yield) / (3.0 * c.shear_modulus + c.hardening_modulus);
      const Tensor<D> n = dev / q;
      trial -= 3.0 * c.shear_modulus * dp * n;
      s.plastic_strain += 1.5 * dp * n;
      s.equivalent_plastic_strain += dp;
    }
  }
  s.stress = trial;
}

/// Elastic strain energy density (linear: 1/2 sigma : eps_elastic; neo-Hookean: W(F)).
template <int D>
double strain_energy_density(const Constants& c, const State<D>& s, const Tensor<D>& F) {
  if (c.kind == Kind::neo_hookean) {
    const double J = F.determinant(), lnJ = std::log(J);
    return 0.5 * c.shear_modulus * ((F.transpose() * F).trace() - D) - c.shear_modulus * lnJ + 0.5 * c.lambda * lnJ * lnJ;
  }
  return 0.5 * (s.stress.array() * (s.strain - s.plastic_strain).array()).sum();
}

}  // namespace rift::material
