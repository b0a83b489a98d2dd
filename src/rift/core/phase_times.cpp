#include "rift/core/phase_times.hpp"

#include <algorithm>
#include <cstdio>

namespace rift {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::bond_passes: return "bond passes";
    case Phase::contact: return "contact";
    case Phase::fluid_network: return "fluid network";
    case Phase::crack_surface: return "crack surface";
    case Phase::fragments: return "fragments";
    case Phase::network_load: return "network load";
    case Phase::fluid_pressure: return "fluid pressure";
    case Phase::output: return "output";
    case Phase::count: break;
  }
  return "?";
}

void PhaseTimes::enter(Phase p) {
  const auto now = Clock::now();
  if (depth_ > 0) seconds_[static_cast<std::size_t>(stack_[static_cast<std::size_t>(depth_ - 1)])] += std::chrono::duration<double>(now - since_).count();
  // deeper than the stack: counted to the innermost phase that fits
  if (depth_ < static_cast<int>(stack_.size())) stack_[static_cast<std::size_t>(depth_)] = p;
  else stack_.back() = p;
  ++depth_;
  since_ = now;
}

void PhaseTimes::leave() {
  if (depth_ == 0) return;
  const auto now = Clock::now();
  const int top = std::min(depth_, static_cast<int>(stack_.size())) - 1;
  seconds_[static_cast<std::size_t>(stack_[static_cast<std::size_t>(top)])] += std::chrono::duration<double>(now - since_).count();
  --depth_;
  since_ = now;
}

PhaseTimes& PhaseTimes::run() {
  static PhaseTimes times;
  return times;
}

std::string phase_summary(const PhaseTimes& t, double total) {
  std::string out;
  double timed = 0.0;
  char item[96];
  auto add = [&](const char* name, double s) {
    std::snprintf(item, sizeof item, "%s%s %.3g s (%.0f%%)", out.empty() ? "" : ", ", name, s, total > 0.0 ? 100.0 * s / total : 0.0);
    out += item;
  };
  for (std::size_t p = 0; p < static_cast<std::size_t>(Phase::count); ++p) {
    const double s = t.seconds(static_cast<Phase>(p));
    timed += s;
    if (s > 0.0) add(phase_name(static_cast<Phase>(p)), s);
  }
  add("other", total > timed ? total - timed : 0.0);
  return out;
}

}  // namespace rift
