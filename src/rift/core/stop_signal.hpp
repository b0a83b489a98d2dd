// SIGTERM and SIGINT during a run (a batch system's notice before it kills a job, or Ctrl-C): the
// run ends the step, iteration or pass it is in, writes a checkpoint and stops, to go on with
// `rift run --restart`. Every long loop reads stop_signal() (explicit and MPM steps, each iteration
// of dynamic relaxation and of conjugate gradients, each breaking pass). SIGTERM stays caught:
// a batch system may send it more than once, and each is the same request. SIGINT's handler is
// reset by its first signal, so a second Ctrl-C ends the process at once.
#pragma once

namespace rift {

/// Installs the handlers (`rift run`).
void catch_stop_signals();
/// The signal received since, or 0.
int stop_signal();
/// Sets the signal as its handler would (tests: a stop at a chosen moment); 0 clears it.
void set_stop_signal(int signal);

}  // namespace rift
