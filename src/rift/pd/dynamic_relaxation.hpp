// Adaptive dynamic relaxation (Kilic and Madenci 2010, Theor. Appl. Fract. Mech. 53, eq. 8-15):
// fictitious density from the stiffness row sum, damping from Rayleigh's quotient of the local
// diagonal stiffness. Solves the static equilibrium for the loads at a given time.
#pragma once
#include "rift/load/boundary.hpp"
#include "rift/pd/contact.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

struct RelaxationResult {
  int iterations = 0;
  double residual = 0.0;  // ||internal + external force|| / ||load||
  bool converged = false;
  int breaking_passes = 1;  // equilibria of the load step (relax_breaking_at_equilibrium)
  double density_factor = 0.0;  // the fictitious density over the row-sum bound, where measured
};

/// The factor over the PMB row-sum bound of the fictitious density (eq. 10) that covers the LPS
/// coupling through the dilatation and the surface correction, where it is not measured.
inline constexpr double row_sum_factor = 5.0;

template <int D>
class DynamicRelaxation {
 public:
  explicit DynamicRelaxation(const Model<D>& m);
  /// Relax to equilibrium for the loads at time t (positions of displacement BCs set first).
  RelaxationResult relax(Model<D>& m, const load::Boundaries<D>& loads, Contact<D>* contact, double t,
                         int max_iterations, double tolerance);
  /// Measures the largest eigenvalue mu of the stiffness over the row-sum bound (eq. 10 without its
  /// factor) by power iteration at the current state, and sets the fictitious density to
  /// `safety` mu / 4 times that bound (stable for dt = 1 where mu / 4 is the largest). Returns the
  /// factor. Call with the bonds held (HeldBreaking): the probes move the particles by a millionth
  /// of a bond.
  double measure_fictitious_density(Model<D>& m, const load::Boundaries<D>& loads, Contact<D>* contact, double t, int iterations = 50,
                                    double safety = 1.25);
  /// lambda_i per particle (eq. 10, time step 1), per unit volume.
  const std::vector<double>& fictitious_density() const { return fictitious_density_; }
  /// Damping from Rayleigh's quotient of the displacement since the start of each relax call
  /// instead of since the reference state (in_situ_strain.hpp: a start already near equilibrium).
  void measure_damping_from_start(bool on) { damping_from_start_ = on; }
  /// Every member, for a checkpoint (pd/checkpoint_state.hpp).
  template <class A>
  void visit_state(A& a) {
    a("relaxation.fictitious_density", fictitious_density_), a("relaxation.damping_from_start", damping_from_start_);
  }
  /// Quasi-static growth: relax with every bond held, break the bonds past their limits at that
  /// equilibrium, and relax again, until an equilibrium breaks nothing (or max_passes equilibria;
  /// then converged is false).
  /// No bond breaks in the transients of a load step, where the loads (an injected fluid's
  /// pressure, say) have not yet found the deformation they belong to. The passes stop once an
  /// injected fluid breaks through to the outer surface: a laboratory test ends there, its pressure
  /// lost, and the bonds keep the crack it had then (what a cut block shows).
  RelaxationResult relax_breaking_at_equilibrium(Model<D>& m, const load::Boundaries<D>& loads, Contact<D>* contact, double t,
                                                 int max_iterations, double tolerance, int max_passes);

 private:
  std::vector<double> fictitious_density_;  // lambda_ii (eq. 10), time step 1
  bool damping_from_start_ = false;
};

}  // namespace rift::pd
