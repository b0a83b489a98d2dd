// Halo exchange between the ranks of a distributed run whose particles are cut into contiguous
// ranges of the global numbering (pd/window.hpp): rank r owns [owned[r], owned[r + 1]) and holds the
// window [window_first[r], window_last[r]) around it; the ghosts are the window's particles another
// rank owns. Each refresh sends every owned particle that another rank's window holds to that rank
// and receives every ghost from its owner: point to point, no rank waits on one it does not neighbour.
#pragma once
#include <cstddef>
#include <vector>

#include "rift/pd/model.hpp"

namespace rift::parallel {

class Halo final : public pd::Ghosts {
 public:
  /// owned: size ranks + 1, ascending; windows: each rank's [first, last), holding its owned range.
  Halo(int rank, const std::vector<std::size_t>& owned, const std::vector<std::size_t>& window_first,
       const std::vector<std::size_t>& window_last);
  void refresh(double* field, std::size_t width) const override;
  /// Particles received per refresh (the ghosts), and sent.
  std::size_t ghosts() const;
  std::size_t sent() const;

 private:
  struct Range {
    int rank = 0;                      // the other rank
    std::size_t first = 0, count = 0;  // particles in this rank's window numbering
  };
  std::vector<Range> receive_, send_;
};

}  // namespace rift::parallel
