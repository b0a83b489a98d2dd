// The states of the directed bonds (bond_intact, bond_broken, bond_interface_failed) and a count of
// their changes. What the passes make of the states each step (bond_runs.hpp RowStates: which rows
// are whole, and the bits of their intact offsets) is kept from one step to the next and made again
// only after a change, so a step without breaking reads no byte per bond. Every write goes through
// set() or replace(), or through writable() followed by changed(): a write that bypassed them would
// leave the kept rows stale, so there is no other way to write. A change takes its version from one
// count of the whole process, so that two states that are not copies of each other never share a
// version (a cache made from one is never taken for the other's: hf/fluid_network.hpp).
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "rift/parallel/uninitialized_vector.hpp"

namespace rift::pd {

class BondStates {
 public:
  using Storage = uninitialized_vector<std::uint8_t>;

  std::uint8_t operator[](std::size_t k) const { return states_[k]; }
  const std::uint8_t* data() const { return states_.data(); }
  std::size_t size() const { return states_.size(); }
  bool empty() const { return states_.empty(); }
  Storage::const_iterator begin() const { return states_.begin(); }
  Storage::const_iterator end() const { return states_.end(); }
  const Storage& all() const { return states_; }

  /// One bond's state (not from inside a parallel region: see writable()).
  void set(std::size_t k, std::uint8_t state) {
    states_[k] = state;
    version_ = next_version();
  }
  /// The states to write in place, from a team; changed() after the writes.
  std::uint8_t* writable() { return states_.data(); }
  void changed() { version_ = next_version(); }
  /// The storage itself, to fill, resize or read into (a checkpoint's restore): counted as a change.
  Storage& replace() {
    version_ = next_version();
    return states_;
  }
  /// Counts the changes: rows made at one version are those of the states while it lasts.
  std::uint64_t version() const { return version_; }

  friend bool operator==(const BondStates& a, const BondStates& b) { return a.states_ == b.states_; }

 private:
  static std::uint64_t next_version() {
    static std::atomic<std::uint64_t> count{0};
    return count.fetch_add(1, std::memory_order_relaxed) + 1;
  }
  Storage states_;
  std::uint64_t version_ = 0;
};

}  // namespace rift::pd
