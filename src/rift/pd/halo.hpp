// Halo exchange between the ranks of a distributed run whose particles are cut into ranges of the
// global numbering (pd/window.hpp): each rank owns a few ranges and holds a window of ranges around
// them; the ghosts are the window's particles another rank owns. Each refresh sends every owned
// particle that another rank's window holds to that rank and receives every ghost from its owner:
// point to point, one message per neighbour and direction, no rank waiting on one it does not
// neighbour.
#pragma once
#include <cstddef>
#include <vector>

#include "rift/core/index_range.hpp"
#include "rift/pd/model.hpp"
#include "rift/pd/numbering.hpp"

namespace rift::pd {

class Halo final : public Ghosts {
 public:
  /// owned, windows: every rank's owned particles and window as ranges of the whole numbering
  /// (ascending; each window holds its rank's owned ranges); `here` numbers this rank's window.
  Halo(int rank, const std::vector<std::vector<IndexRange>>& owned, const std::vector<std::vector<IndexRange>>& windows, const Numbering& here);
  void refresh(double* field, std::size_t width) const override;
  /// Particles received per refresh (the ghosts), and sent.
  std::size_t ghosts() const;
  std::size_t sent() const;

 private:
  struct Peer {
    int rank = 0;                     // the other rank
    std::vector<IndexRange> ranges;   // the particles, in this rank's window numbering, ascending
  };
  std::vector<Peer> receive_, send_;
};

}  // namespace rift::pd
