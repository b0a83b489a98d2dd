// Progress of a long run: a redrawn bar on a terminal (step, simulated time, ETA, broken-bond
// fraction), plain periodic log lines otherwise.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace rift {

class Progress {
 public:
  Progress(long total_steps, double end_time, bool quiet);
  void update(long step, double time, double broken_fraction, bool force = false);
  void finish(long step, double time, double broken_fraction);

 private:
  double elapsed() const;
  long total_;
  double end_time_;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_;
  double last_print_ = -1e9;
};

}  // namespace rift
