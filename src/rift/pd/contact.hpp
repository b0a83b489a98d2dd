// Short-range repulsive contact between particles that are not bonded (broken bonds, fragments,
// separate bodies), so material does not interpenetrate. As LAMMPS PERI / EMU (Silling 2005,
// EMU theory manual p. 18): when two particles come closer than d = distance * spacing, each feels
// f = k V_j (d - r) / delta, k = stiffness * c, with c the PMB micromodulus of the body.
// Candidates come from a Verlet list rebuilt when a particle has moved half the skin.
#pragma once
#include <cstdint>
#include <vector>

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

 private:
  void rebuild(const Model<D>& m);
  bool enabled_ = false;
  double skin_ = 0.0, max_distance_ = 0.0;
  std::vector<double> distance_;  // per body
  std::vector<double> stiffness_; // k / delta per body
  std::vector<Vec<D>> built_at_;
  std::vector<std::int64_t> offset_;
  std::vector<std::int32_t> pairs_;
};

}  // namespace rift::pd
