#include "rift/core/stop_signal.hpp"

#include <csignal>

namespace rift {

namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void on_stop_signal(int signal) { received = signal; }

}  // namespace

void catch_stop_signals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGTERM, &action, nullptr);
  action.sa_flags = SA_RESETHAND;  // a second Ctrl-C: the default action, the process ends
  sigaction(SIGINT, &action, nullptr);
}

int stop_signal() { return received; }

void set_stop_signal(int signal) { received = signal; }

}  // namespace rift
