// Wall time of a run by phase of the step, as LAMMPS prints its breakdown (Pair, Neigh, Modify, ...)
// at the end of a run: where a long run's time goes, without a profiler. A phase is timed by a
// PhaseClock on the stack; a phase inside another pauses the outer one, so the phases add up to the
// time they cover. Timed on the thread that steps (outside the parallel regions), so the parallel
// work and the waits at its ends are counted, not each thread's share.
#pragma once
#include <array>
#include <chrono>
#include <string>

namespace rift {

enum class Phase { bond_passes, contact, fluid_network, crack_surface, fragments, network_load, fluid_pressure, output, count };

/// The phases' names as printed.
const char* phase_name(Phase p);

class PhaseTimes {
 public:
  using Clock = std::chrono::steady_clock;
  /// Starts phase p, pausing the one running (if any).
  void enter(Phase p);
  /// Ends the innermost phase, resuming the one it paused.
  void leave();
  double seconds(Phase p) const { return seconds_[static_cast<std::size_t>(p)]; }
  void reset() { *this = PhaseTimes{}; }
  /// The whole run's timer (the stepping thread's).
  static PhaseTimes& run();

 private:
  std::array<double, static_cast<std::size_t>(Phase::count)> seconds_{};
  std::array<Phase, 8> stack_{};
  int depth_ = 0;
  Clock::time_point since_{};
};

/// Times the scope as phase p of PhaseTimes::run().
class PhaseClock {
 public:
  explicit PhaseClock(Phase p) { PhaseTimes::run().enter(p); }
  ~PhaseClock() { PhaseTimes::run().leave(); }
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;
};

/// "bond passes 61.2 s (48%), contact 1.2 s (1%), ..., other 10.3 s (8%)" of a loop of `total` s.
std::string phase_summary(const PhaseTimes& t, double total);

}  // namespace rift
