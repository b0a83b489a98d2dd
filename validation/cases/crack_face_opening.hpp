// The opening of a straight crack along x between two lattice rows of a 2D body, read at its faces:
// each face's displacement u_y extrapolated linearly from the two rows next to it (at dx/2 and
// 3 dx/2 from the crack line) to the line. Used by the pressurized-crack cases (hf_sneddon,
// hf_kgd_toughness).
#pragma once
#include <cmath>
#include <map>
#include <utility>

#include "rift/pd/model.hpp"

namespace rift::validation {

class CrackFaceOpening {
 public:
  /// Lattice sites at ((i + offset) spacing, (j + offset) spacing).
  CrackFaceOpening(const pd::Model<2>& m, double spacing, double offset) {
    for (std::size_t k = 0; k < m.size(); ++k) {
      const auto& X = m.reference_position[k];
      uy_[{std::lround(X[0] / spacing - offset), std::lround(X[1] / spacing - offset)}] = m.position[k][1] - X[1];
    }
  }

  /// The opening at column i of a crack lying just below row `above` (0 where a site is missing).
  double at(long i, long above) const {
    const double upper = 1.5 * u(i, above) - 0.5 * u(i, above + 1), lower = 1.5 * u(i, above - 1) - 0.5 * u(i, above - 2);
    return upper - lower;
  }

 private:
  double u(long i, long j) const {
    const auto it = uy_.find({i, j});
    return it == uy_.end() ? 0.0 : it->second;
  }
  std::map<std::pair<long, long>, double> uy_;
};

}  // namespace rift::validation
