// Progress of a long run: a redrawn bar on a terminal (step, simulated time, ETA, broken-bond
// fraction), plain periodic log lines otherwise; within a load step of an iterative solve, its
// iteration and residual, with the time to the tolerance at the residual's rate of fall.
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
  /// An iteration of load step `step` (dynamic relaxation): printed as update prints a step.
  void iteration(long step, int iteration, int max_iterations, double residual, double tolerance);

 private:
  double elapsed() const;
  long total_;
  double end_time_;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_;
  double last_print_ = -1e9;
  // the residual's fall since the last line of the same load step: its log and when
  long iteration_step_ = -1;
  double iteration_log_residual_ = 0.0, iteration_time_ = 0.0;
};

}  // namespace rift
