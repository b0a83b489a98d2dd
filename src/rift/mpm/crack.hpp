// Explicit cracks in the material point method (CRAMP; Nairn 2003, "Material point method
// calculations with explicit cracks", CMES 4). A crack is a polyline of massless crack particles.
// Each particle-node pair gets a velocity field by the line-crossing test: 0 when the segment from
// the particle to the node does not cross a crack, 1 when it crosses and the particle is above the
// crack (left of its direction), 2 when below. Nodes near a crack so carry up to two fields and solve
// momentum per field. Crack particles move with the centre-of-mass velocity; the positions of the
// top and bottom surfaces, moving with their own fields, give the crack opening and sliding
// displacements. 2D only.
#pragma once
#include <array>
#include <vector>

#include "rift/core/vec.hpp"
#include "rift/scene/scene.hpp"

namespace rift::mpm {

/// Which end of a crack polyline a tip is.
enum class TipEnd { start, end };

struct CrackTip {
  std::size_t crack = 0;
  TipEnd end = TipEnd::end;
};

class CrackSet {
 public:
  struct Crack {
    std::vector<Vec<2>> points;        // crack particles, in order along the crack
    std::vector<Vec<2>> above, below;  // surface positions at each crack particle
    Vec<2> lo{}, hi{};                 // bounding box of the points
  };

  CrackSet() = default;
  /// Crack particles every half cell along each scene polyline.
  CrackSet(const scene::Scene& s, double cell_size);
  bool empty() const { return cracks_.empty(); }
  const std::vector<Crack>& cracks() const { return cracks_; }
  std::vector<Crack>& cracks() { return cracks_; }

  /// Velocity field of a material point at xp seen from the node at xn: 0, 1 (above) or 2 (below).
  int field(const Vec<2>& xp, const Vec<2>& xn) const;
  /// True when x is within `reach` of some crack's bounding box (only such points need field()).
  bool near(const Vec<2>& x, double reach) const;
  /// Unit normal (pointing to the "above" side) of crack c at crack particle k.
  Vec<2> normal(std::size_t c, std::size_t k) const;
  /// Opening (normal) and sliding (tangential) displacement at crack particle k of crack c.
  std::array<double, 2> opening(std::size_t c, std::size_t k) const;
  /// Nearest crack particle to x: {crack, particle, distance}.
  struct Nearest {
    std::size_t crack = 0, particle = 0;
    double distance = 1e300;
  };
  Nearest nearest(const Vec<2>& x) const;
  /// A point just on one side (1: above, 2: below) of crack c, next to x: the nearest point of the
  /// crack's segments within `window` particles of particle k, moved `offset` along that side's
  /// normal. Seen from it, a node's field is the one the material on that side uses there (crack
  /// surfaces slide away from their crack particle, so the particle itself is not a safe probe).
  Vec<2> side_point(std::size_t c, std::size_t k, const Vec<2>& x, int side, double offset, std::size_t window = 16) const;
  void update_bounds();
  /// Grows crack c at one end by a new crack particle at x (its surfaces start closed there).
  void extend(const CrackTip& tip, const Vec<2>& x);

 private:
  std::vector<Crack> cracks_;
};

}  // namespace rift::mpm
