// A loop over independent items, split as a static schedule splits it (thread t takes the t-th of
// equal blocks, in order, so that each pass of a step over the same items finds them in the cache
// of the core that used them last), in which a thread that is done with its block goes on with the
// rest of the others' blocks, a chunk at a time. A static schedule waits at its closing barrier for
// the last thread: on a shared machine a descheduled vCPU holds the whole team for as long as it is
// away, so two threads pay about twice the machine's noise that one does (bench/README.md). Each
// block hands out its chunks from the front through one atomic counter, which its owner alone
// touches until someone else is done. Each item is computed by one thread, by the same code on any
// thread, so the results do not depend on who took it.
#pragma once
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>

#include "rift/parallel/team.hpp"

namespace rift::parallel {

/// body(i) for i in [first, last). One compiled loop for a team's chunks and for the calling thread
/// alone, so that one thread and a team run the same machine code: inlined into each caller, GCC 12
/// compiled the 2D stress update's point body differently in the team's copy (its velocity gradient
/// stored to the stack as scalars and read back as pairs: a failed store forwarding, twice a point),
/// and that pass gained well under 2x from a second thread (bench/README.md).
template <class Body>
[[gnu::noinline]] void for_each_in_range(std::size_t first, std::size_t last, Body& body) {
  for (std::size_t i = first; i < last; ++i) body(i);
}

/// The blocks of one loop: split() by the calling thread before the team starts, take() by each
/// thread of the team.
class SharedBlocks {
 public:
  SharedBlocks() = default;
  // scratch of one loop: a copy starts without blocks
  SharedBlocks(const SharedBlocks&) {}
  SharedBlocks& operator=(const SharedBlocks&) { return *this; }

  /// n items in `threads` blocks of equal size, handed out in chunks of about 1/64 of a block (the
  /// last thread to finish is at most that late).
  void split(std::size_t n, std::size_t threads) {
    if (capacity_ < threads) blocks_ = std::make_unique<Block[]>(threads), capacity_ = threads;
    count_ = threads;
    for (std::size_t t = 0; t < threads; ++t) {
      blocks_[t].next.store(n * t / threads, std::memory_order_relaxed);
      blocks_[t].end = n * (t + 1) / threads;
    }
    chunk_ = std::max<std::size_t>(16, n / (threads * 64));
  }

  /// Thread t's share: body(i) for the items of block t, then for what is left of the others'. A
  /// team smaller than the blocks leaves some without an owner; the others take them.
  template <class Body>
  void take(std::size_t t, Body&& body) {
    for (std::size_t k = 0; k < count_; ++k) {
      Block& b = blocks_[(t + k) % count_];
      for (;;) {
        const std::size_t first = b.next.fetch_add(chunk_, std::memory_order_relaxed);
        if (first >= b.end) break;
        for_each_in_range(first, std::min(first + chunk_, b.end), body);
      }
    }
  }

 private:
  /// One thread's block, [next, end): next is the first item not yet handed out.
  struct alignas(64) Block {
    std::atomic<std::size_t> next{0};
    std::size_t end = 0;
  };
  std::unique_ptr<Block[]> blocks_;
  std::size_t capacity_ = 0, count_ = 0, chunk_ = 1;
};

/// Runs body(i) for every i in [0, n): on the calling thread alone where the loop is not worth a team
/// (team.hpp), else on a team, each thread its own block first and then what is left of the others'.
/// body must compute each item alone (no item reads what another writes in the same loop).
template <class Body>
void for_each_in_shared_blocks(std::size_t n, Body&& body) {
  const int threads = omp_get_max_threads();
  if (!worth_a_team(n) || threads < 2) {
    for_each_in_range(0, n, body);
    return;
  }
  // the calling thread's, kept from loop to loop (a loop does not call another); the team reaches it
  // through the pointer (a thread_local named in the region would be each thread's own)
  static thread_local SharedBlocks own;
  SharedBlocks* const blocks = &own;
  blocks->split(n, static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  blocks->take(static_cast<std::size_t>(omp_get_thread_num()), body);
}

}  // namespace rift::parallel
