// Contact in a distributed run (pd/window.hpp) reaches past a rank's window: another body's
// particles (the bodies are numbered one after the other, so a rank's range of the numbering is no
// layer of the scene) and its own body's particles beyond the bonds' reach (a squeezed block, a
// fragment flung across a cut). At each rebuild of the contact's Verlet list (contact.hpp) every
// rank gives the others the boxes around its owned particles of each body, grown by the list's
// reach (contact distance + skin); each rank then sends every other rank its owned particles inside
// one of that rank's boxes and beyond its window, and refreshes their positions before each
// evaluation of the forces until the next rebuild. A pair missing from such a list was farther than
// the reach when it was made, as in one rank's list (Allen and Tildesley, Computer Simulation of
// Liquids, section 5.3), so an owned particle's contact force sums the same pairs as one rank's.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "rift/parallel/communicator.hpp"
#include "rift/pd/model.hpp"

namespace rift::pd {

template <int D>
class BeyondWindow {
 public:
  // the particles beyond this rank's window that contact may reach, as their owners have them
  std::vector<std::int64_t> number;  // the whole run's numbers
  std::vector<Vec<D>> position;
  std::vector<double> volume;
  std::vector<std::uint32_t> body;

  std::size_t size() const { return number.size(); }

  /// Collective (every rank, at the same rebuild): the particles of other ranks within `reach` of
  /// the boxes around this rank's owned particles of each body, beyond its window.
  void gather(const Model<D>& m, double reach, const parallel::Communicator& comm) {
    const auto ranks = static_cast<std::size_t>(comm.size()), me = static_cast<std::size_t>(comm.rank());
    const std::size_t bodies = m.bodies.size();
    // each rank's window, in the whole run's numbers: its count of ranges, then each range's first
    // and last
    std::vector<std::int64_t> mine{static_cast<std::int64_t>(m.numbering.ranges().size())};
    for (const auto& a : m.numbering.ranges())
      mine.push_back(static_cast<std::int64_t>(a.whole)), mine.push_back(static_cast<std::int64_t>(a.whole + a.count));
    const auto all_windows = comm.all_gather(mine);
    std::vector<std::size_t> window_at(ranks);  // where rank r's ranges start in all_windows
    for (std::size_t r = 0, at = 0; r < ranks; at += 1 + 2 * static_cast<std::size_t>(all_windows[at]), ++r) window_at[r] = at;
    // each rank's boxes, one a body: low (D), high (D); an empty one has low > high. Grown a little
    // past the reach: a pair at the reach to the last bit, which one rank lists, is not lost to the
    // boxes' rounding (more candidates cost nothing but their test)
    reach *= 1.0 + 1e-9;
    std::vector<double> boxes(bodies * 2 * D);
    for (std::size_t q = 0; q < bodies; ++q)
      for (int k = 0; k < D; ++k) boxes[(2 * q) * D + k] = std::numeric_limits<double>::max(), boxes[(2 * q + 1) * D + k] = -std::numeric_limits<double>::max();
    for (const IndexRange& owned : m.owned())
      for (std::size_t i = owned.first; i < owned.last; ++i)
        for (int k = 0; k < D; ++k) {
          double* const low = &boxes[(2 * m.body[i]) * D], *const high = low + D;
          low[k] = std::min(low[k], m.position[i][k] - reach), high[k] = std::max(high[k], m.position[i][k] + reach);
        }
    const auto all_boxes = comm.all_gather(boxes);
    // whether any of rank r's boxes meets one of this rank's (else none of either's particles is
    // inside the other's: both leave the other out of the exchange)
    auto meets_mine = [&](std::size_t r) {
      for (std::size_t q = 0; q < bodies; ++q)
        for (std::size_t p = 0; p < bodies; ++p) {
          bool meet = true;
          for (int k = 0; k < D; ++k)
            meet = meet && all_boxes[(r * bodies + q) * 2 * D + k] <= boxes[(2 * p + 1) * D + k] &&
                   boxes[(2 * p) * D + k] <= all_boxes[(r * bodies + q) * 2 * D + D + k];
          if (meet) return true;
        }
      return false;
    };
    send_.assign(ranks, {});
    std::vector<parallel::Communicator::Parcel> parcels;
    for (std::size_t r = 0; r < ranks; ++r) {
      if (r == me) continue;
      const std::int64_t* const window = &all_windows[window_at[r]];
      auto in_window = [&](std::int64_t g) {  // whether rank r's window holds g: the last range from at or below g
        std::int64_t low = 0, high = window[0];  // the ranges before `low` start at or below g, those from `high` above it
        while (low < high) {
          const std::int64_t mid = (low + high) / 2;
          if (window[1 + 2 * mid] <= g) low = mid + 1;
          else high = mid;
        }
        return low > 0 && g < window[2 * low];
      };
      const double* const theirs = &all_boxes[r * bodies * 2 * D];
      if (!meets_mine(r)) continue;
      auto& parcel = parcels.emplace_back();
      parcel.peer = static_cast<int>(r);
      for (const IndexRange& owned : m.owned())
        for (std::size_t i = owned.first; i < owned.last; ++i) {
          const auto global = static_cast<std::int64_t>(m.numbering.whole(i));
          if (in_window(global)) continue;  // a particle of r's window: r has it
          bool inside = false;
          for (std::size_t q = 0; q < bodies && !inside; ++q) {
            inside = true;
            for (int k = 0; k < D; ++k)
              inside = inside && m.position[i][k] >= theirs[(2 * q) * D + k] && m.position[i][k] <= theirs[(2 * q + 1) * D + k];
          }
          if (!inside) continue;
          send_[r].push_back(i);
          // whole-run number, position, volume, body
          const std::array<double, D + 3> entry = packed(static_cast<double>(global), m.position[i], m.volume[i], static_cast<double>(m.body[i]));
          append(parcel.send, entry.data(), entry.size());
        }
    }
    comm.exchange(parcels);
    number.clear(), position.clear(), volume.clear(), body.clear();
    receive_.assign(ranks, 0);
    for (const auto& parcel : parcels) {
      const std::size_t count = parcel.receive.size() / (sizeof(double) * (D + 3));
      receive_[static_cast<std::size_t>(parcel.peer)] = count;
      for (std::size_t e = 0; e < count; ++e) {
        std::array<double, D + 3> entry;
        std::memcpy(entry.data(), parcel.receive.data() + e * sizeof(entry), sizeof(entry));
        number.push_back(static_cast<std::int64_t>(entry[0]));
        Vec<D> x;
        for (int k = 0; k < D; ++k) x[k] = entry[1 + k];
        position.push_back(x);
        volume.push_back(entry[D + 1]);
        body.push_back(static_cast<std::uint32_t>(entry[D + 2]));
      }
    }
  }

  /// Collective: the positions of the particles gathered at the last rebuild, from their owners
  /// (point to point, with the ranks that send or receive any).
  void refresh(const Model<D>& m, const parallel::Communicator& comm) {
    std::vector<parallel::Communicator::Parcel> parcels;
    for (std::size_t r = 0; r < send_.size(); ++r) {
      if (send_[r].empty() && receive_[r] == 0) continue;
      auto& parcel = parcels.emplace_back();
      parcel.peer = static_cast<int>(r);
      for (const std::size_t i : send_[r]) append(parcel.send, m.position[i].data(), D);
    }
    if (parcels.empty()) return;
    comm.exchange(parcels);
    std::size_t at = 0;  // the received particles lie in the order of the parcels' peers (ascending ranks)
    for (const auto& parcel : parcels) {
      const std::size_t count = parcel.receive.size() / sizeof(Vec<D>);
      for (std::size_t e = 0; e < count; ++e) std::memcpy(position[at + e].data(), parcel.receive.data() + e * sizeof(Vec<D>), sizeof(Vec<D>));
      at += count;
    }
  }

 private:
  static std::array<double, D + 3> packed(double global, const Vec<D>& x, double v, double b) {
    std::array<double, D + 3> e{};
    e[0] = global;
    for (int k = 0; k < D; ++k) e[1 + k] = x[k];
    e[D + 1] = v, e[D + 2] = b;
    return e;
  }
  static void append(std::vector<std::byte>& bytes, const double* values, std::size_t count) {
    const auto at = bytes.size();
    bytes.resize(at + count * sizeof(double));
    std::memcpy(bytes.data() + at, values, count * sizeof(double));
  }
  std::vector<std::vector<std::size_t>> send_;  // per rank: the owned particles it receives from this one
  std::vector<std::size_t> receive_;            // per rank: how many of its particles this one receives
};

}  // namespace rift::pd
