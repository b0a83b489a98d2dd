// Adaptive dynamic relaxation (Kilic and Madenci 2010, Theor. Appl. Fract. Mech. 53, eq. 8-15):
// fictitious density from the stiffness row sum, damping from Rayleigh's quotient of the local
// diagonal stiffness. Solves the static equilibrium for the loads at a given time.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "rift/pd/contact.hpp"
#include "rift/pd/held_breaking.hpp"
#include "rift/pd/loads.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

struct RelaxationResult {
  int iterations = 0;
  double residual = 0.0;  // ||internal + external force|| / ||load||
  bool converged = false;
  int breaking_passes = 1;  // equilibria of the load step (relax_breaking_at_equilibrium)
  double density_factor = 0.0;  // the fictitious density over the row-sum bound, where measured
  bool stopped = false;  // a stop signal cut it short (core/stop_signal.hpp): not an equilibrium
};

/// The factor over the PMB row-sum bound of the fictitious density (eq. 10) that covers the LPS
/// coupling through the dilatation and the surface correction, where it is not measured.
inline constexpr double row_sum_factor = 5.0;

template <int D>
class DynamicRelaxation {
 public:
  explicit DynamicRelaxation(const Model<D>& m);
  /// Relax to equilibrium for the loads at time t (positions of displacement BCs set first). Each
  /// iteration reads the stop signal (every rank alike); a stop leaves the iterations where they
  /// are (unfinished(), stopped = true) for a checkpoint, and the next call goes on from there.
  RelaxationResult relax(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                         int max_iterations, double tolerance);
  /// Measures the largest eigenvalue mu of the stiffness over the row-sum bound (eq. 10 without its
  /// factor) by power iteration at the current state, and sets the fictitious density to
  /// `safety` mu / 4 times that bound (stable for dt = 1 where mu / 4 is the largest). Returns the
  /// factor. Call with the bonds held (HeldBreaking): the probes move the particles by a millionth
  /// of a bond.
  double measure_fictitious_density(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t, int iterations = 50,
                                    double safety = 1.25);
  /// lambda_i per particle (eq. 10, time step 1), per unit volume.
  const std::vector<double>& fictitious_density() const { return fictitious_density_; }
  /// Damping from Rayleigh's quotient of the displacement since the start of each relax call
  /// instead of since the reference state (geomech/in_situ_strain.hpp: a start already near equilibrium).
  void measure_damping_from_start(bool on) { damping_from_start_ = on; }
  /// Every member, for a checkpoint (pd/checkpoint_state.hpp).
  template <class A>
  void visit_state(A& a) {
    a("relaxation.fictitious_density", fictitious_density_), a("relaxation.damping_from_start", damping_from_start_);
    a("relaxation.unfinished.iteration", unfinished_.iteration), a("relaxation.unfinished.load_norm", unfinished_.load_norm);
    a("relaxation.unfinished.previous", unfinished_.previous), a("relaxation.unfinished.start", unfinished_.start);
    a("relaxation.unfinished.pass", unfinished_.pass), a("relaxation.unfinished.iterations", unfinished_.iterations);
    a("relaxation.unfinished.broken_through", unfinished_.broken_through), a("relaxation.unfinished.spent", unfinished_.spent);
  }
  /// A load step a stop signal cut short: where its iterations stood. The next relax call (the same
  /// load step, after a restart from the checkpoint that holds it) goes on from there, bit for bit.
  struct Unfinished {
    std::int32_t iteration = 0;  // the iteration to go on with; 0: no load step unfinished
    double load_norm = 0.0;      // ||external force||^2 of the load step
    std::vector<Vec<D>> previous, start;  // F^{n-1} / lambda per particle; the start of the damping's displacement
    std::int32_t pass = 0;                 // relax_breaking_at_equilibrium: the pass it is in, the iterations
    std::int32_t iterations = 0;           // of the passes before it and the fluid sources broken
    std::uint64_t broken_through = 0;      // through to the outer surface when the load step began
    std::int32_t spent = 0;                // the static solver: the force evaluations its conjugate
                                           // gradients spent before this relaxation took over
  };
  Unfinished& unfinished() { return unfinished_; }
  /// Called after each iteration's residual (a run's progress lines): f(iteration, residual).
  void observe(std::function<void(int, double)> f) { observer_ = std::move(f); }
  const std::function<void(int, double)>& observer() const { return observer_; }
  bool is_unfinished() const { return unfinished_.iteration > 0; }
  /// Whether a stop cut a load step's breaking passes short: in a relaxation, or in another
  /// equilibrium (breaking_at_equilibrium) of a pass after the first.
  bool passes_unfinished() const { return is_unfinished() || unfinished_.pass > 0; }
  /// Quasi-static growth: relax with every bond held, break the bonds past their limits at that
  /// equilibrium, and relax again, until an equilibrium breaks nothing (or max_passes equilibria;
  /// then converged is false).
  /// No bond breaks in the transients of a load step, where the loads (an injected fluid's
  /// pressure, say) have not yet found the deformation they belong to. The passes stop once an
  /// injected fluid breaks through to the outer surface: a laboratory test ends there, its pressure
  /// lost, and the bonds keep the crack it had then (what a cut block shows).
  RelaxationResult relax_breaking_at_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, double t,
                                                 int max_iterations, double tolerance, int max_passes);
  /// The same passes with another equilibrium: `equilibrium()` brings the model, its bonds held, to
  /// the load step's equilibrium (the static solver's, run/simulation.hpp).
  RelaxationResult breaking_at_equilibrium(Model<D>& m, const Loads<D>& loads, Contact<D>* contact, int max_passes,
                                           const std::function<RelaxationResult()>& equilibrium);

 private:
  std::vector<double> fictitious_density_;  // lambda_ii (eq. 10), time step 1
  bool damping_from_start_ = false;
  Unfinished unfinished_;
  std::function<void(int, double)> observer_;
};

}  // namespace rift::pd
