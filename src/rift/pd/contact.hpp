// Short-range repulsive contact between particles that are not bonded (broken bonds, fragments, separate
// bodies), as LAMMPS PERI / EMU (Silling 2005, EMU theory manual p. 18): closer than d = distance *
// spacing, each feels f = k V_j (d - r) / delta, k = stiffness * c, c the body's PMB micromodulus.
// A pair of one family is read from its bond once the bond broke; only the other pairs (separate bodies,
// the faces of a pre-crack or a borehole, fragments out of their families' reach) come from a Verlet
// list rebuilt when a particle has moved half the skin. Broken bonds are read only where they may touch:
// the bonds of any state shorter than d + s_f when last looked at (up to seven a row, by their places; a
// row with more is read whole), s_f a skin under the gap between d and the shortest bond, looked at again
// once a particle has moved s_f / 2 (Allen and Tildesley, Computer Simulation of Liquids, section 5.3).
// One rank looks by the bodies' runs of forward bonds (bond_runs.hpp), each noting a near bond in both
// rows; other ranks' particles beyond the window: contact_beyond_window.hpp.
// Why, and what was measured: docs/decisions/method-notes.md.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "rift/pd/contact_beyond_window.hpp"
#include "rift/pd/model.hpp"
#include "rift/scene/scene.hpp"

namespace rift::pd {

template <int D>
class Contact {
 public:
  Contact() = default;
  Contact(const scene::Contact& settings, const Model<D>& m);
  bool enabled() const { return enabled_; }
  /// Add contact force densities to m.force.
  void add_forces(Model<D>& m);
  std::size_t candidate_pairs() const { return pairs_.size(); }
  /// Every member, for a checkpoint (pd/checkpoint_state.hpp): the Verlet lists and where they
  /// were built, so a restart looks again exactly when the run it continues would have (a distributed
  /// run's checkpoint holds the list rank 0 makes for the whole model; the forces do not depend on
  /// when a list was made).
  template <class A>
  void visit_state(A& a) {
    a("contact.enabled", enabled_), a("contact.skin", skin_), a("contact.max_distance", max_distance_);
    a("contact.distance", distance_), a("contact.stiffness", stiffness_), a("contact.built_at", built_at_);
    a("contact.offset", offset_), a("contact.pairs", pairs_), a("contact.family_skin", family_skin_);
    a("contact.family_looked_at", family_looked_at_), a("contact.family_near", family_near_);
  }

 private:
  void rebuild(const Model<D>& m);
  void look_at_family_rows(const Model<D>& m);
  void look_at_family_runs(const Model<D>& m);
  bool enabled_ = false;
  double skin_ = 0.0, max_distance_ = 0.0;
  std::vector<double> distance_;  // per body
  std::vector<double> stiffness_; // k / delta per body
  std::vector<Vec<D>> built_at_;
  std::vector<std::int64_t> offset_;
  // per particle, ascending in the whole run's numbers: the pairs within reach that no family holds
  // (a distributed run's particle n + k: beyond_'s k-th)
  std::vector<std::int32_t> pairs_;
  double family_skin_ = 0.0;  // s_f; 0: every row's broken bonds are read
  std::vector<std::array<float, D>> family_looked_at_;  // the displacements when the rows were looked at
  // per particle, the bonds shorter than d + s_f then: `count` of them at `place` in the row, or
  // count = whole_row: more than the places hold (or a row too long for them), every broken bond read
  struct NearBonds {
    static constexpr std::uint8_t whole_row = 255;
    std::uint8_t count = 0;
    std::array<std::uint8_t, 7> place{};
    /// Notes the bond at `at` in the row, its places kept ascending (add_forces merges the bonds
    /// with the listed pairs in the order of their neighbours); past seven, the whole row is read.
    void add(std::uint8_t at) {
      if (count == whole_row) return;
      if (count == place.size()) {
        count = whole_row;
        return;
      }
      std::size_t q = count++;
      for (; q > 0 && place[q - 1] > at; --q) place[q] = place[q - 1];
      place[q] = at;
    }
  };
  std::vector<NearBonds> family_near_;
  BeyondWindow<D> beyond_;  // a distributed run's particles beyond the window within reach; not state
};

}  // namespace rift::pd
