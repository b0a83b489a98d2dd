#include "rift/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace rift {

Progress::Progress(long total_steps, double end_time, bool quiet)
    : total_(std::max(1L, total_steps)), end_time_(end_time), quiet_(quiet), tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

static std::string clock_text(double s) {
  char buf[32];
  if (s < 0 || s > 1e7) return "--:--";
  long t = static_cast<long>(s + 0.5);
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%02ld:%02ld", t / 60, t % 60);
  return buf;
}

void Progress::update(long step, double time, double broken_fraction, bool force) {
  if (quiet_) return;
  const double now = elapsed();
  const double interval = tty_ ? 0.2 : 10.0;
  if (!force && now - last_print_ < interval) return;
  last_print_ = now;
  const double done = double(step) / double(total_);
  const double eta = done > 0 ? now * (1.0 - done) / done : -1.0;
  if (tty_) {
    const int width = 30;
    int filled = static_cast<int>(done * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %5.1f%%  step %ld/%ld  t = %.4g / %.4g s  ETA %s  broken %.3f%%  ", bar.c_str(),
                 100.0 * done, step, total_, time, end_time_, clock_text(eta).c_str(), 100.0 * broken_fraction);
  } else {
    std::fprintf(stderr, "rift: step %ld/%ld (%.1f%%), t = %.4g s, elapsed %s, ETA %s, broken bonds %.3f%%\n", step,
                 total_, 100.0 * done, time, clock_text(now).c_str(), clock_text(eta).c_str(), 100.0 * broken_fraction);
  }
  std::fflush(stderr);
}

void Progress::iteration(long step, int iteration, int max_iterations, double residual, double tolerance) {
  if (quiet_) return;
  const double now = elapsed();
  const double interval = tty_ ? 0.2 : 10.0;
  if (now - last_print_ < interval) return;
  last_print_ = now;
  // the time to the tolerance where the residual falls: log(r / tol) over its log's fall per second
  const double log_residual = std::log(std::max(residual, 1e-300));
  double eta = -1.0;
  if (step == iteration_step_ && now > iteration_time_) {
    const double rate = (iteration_log_residual_ - log_residual) / (now - iteration_time_);
    if (rate > 0.0) eta = std::max(0.0, (log_residual - std::log(tolerance)) / rate);
  }
  iteration_step_ = step, iteration_log_residual_ = log_residual, iteration_time_ = now;
  if (tty_)
    std::fprintf(stderr, "\rload step %ld/%ld  iteration %d (at most %d)  residual %.3g (tolerance %.3g)  ETA of the step %s  ", step, total_,
                 iteration, max_iterations, residual, tolerance, clock_text(eta).c_str());
  else
    std::fprintf(stderr, "rift: load step %ld/%ld, iteration %d (at most %d), residual %.3g (tolerance %.3g), elapsed %s, ETA of the step %s\n",
                 step, total_, iteration, max_iterations, residual, tolerance, clock_text(now).c_str(), clock_text(eta).c_str());
  std::fflush(stderr);
}

void Progress::finish(long step, double time, double broken_fraction) {
  if (quiet_) return;
  update(step, time, broken_fraction, true);
  if (tty_) std::fprintf(stderr, "\n");
  std::fprintf(stderr, "rift: finished %ld steps in %s\n", step, clock_text(elapsed()).c_str());
}

}  // namespace rift
