// When an output falls due in a run of `steps` steps that writes `count` of them: the k-th at the
// first step s with s count >= k steps, so that the last falls on the last step and a count above
// the steps gives one per step. `next` (the k due next) is the run's state, held by its checkpoint.
#pragma once

namespace rift::run {

struct Cadence {
  long count = 0, steps = 1;
  long next = 1;
  bool due(long step) const { return step * count >= next * steps; }
  /// After the output of `step`: the next k due after it.
  void passed(long step) {
    while (next * steps <= step * count) ++next;
  }
};

}  // namespace rift::run
