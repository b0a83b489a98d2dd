// Crack propagation for explicit MPM cracks. The direction is that of the maximum hoop stress
// (Erdogan and Sih 1963): in crack-tip axes the crack kinks by
//   theta_c = 2 arctan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)]
// (theta_c = 0 in pure mode I, -+70.5 degrees in pure mode II), and the hoop stress there gives the
// equivalent mode I intensity
//   K_eq = cos(theta_c / 2) [K_I cos^2(theta_c / 2) - 3/2 K_II sin(theta_c)].
// The crack grows by a set increment in that direction when K_eq >= K_Ic (max_hoop_stress) or when
// G >= G_c (energy_release_rate, the direction still from the hoop stress), as NairnMPM offers.
#pragma once
#include <optional>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/mpm/j_integral.hpp"
#include "rift/mpm/solver.hpp"
#include "rift/scene/scene.hpp"

namespace rift::mpm {

/// Kink angle of maximum hoop stress, radians, counter-clockwise from the crack direction.
double hoop_stress_angle(double KI, double KII);
/// Equivalent mode I stress intensity of the hoop stress at angle theta.
double equivalent_mode_one(double KI, double KII, double theta);

/// Where a tip grows to under the scene's criterion, or nothing.
std::optional<Vec<2>> growth_point(const scene::CrackGrowth& criterion, const CrackTipParameters& tip, double cell_size);

/// Crack propagation during a run: every check_every steps each tip that was inside material at
/// the start grows by one increment when the criterion is met; a tip whose next point would leave
/// the material (the crack reached an edge) stops there.
class CrackPropagation {
 public:
  CrackPropagation(const scene::Scene& s, const Model<2>& m, const Solver<2>& solver);
  /// Crack particles added after `step`.
  int check(const Model<2>& m, Solver<2>& solver, long step);
  /// The tips and which of them stopped, for a checkpoint (mpm/checkpoint_state.hpp).
  template <class A>
  void visit_state(A& a) {
    a("propagation.tips", tips_);
  }

 private:
  struct Tip {
    CrackTip tip;
    bool stopped = false;
    template <class A>
    friend void visit(A& a, Tip& t) {
      a("propagation.tip", t.tip), a("propagation.stopped", t.stopped);
    }
  };
  scene::CrackGrowth settings_;
  JContour contour_;
  std::vector<Tip> tips_;
};

}  // namespace rift::mpm
