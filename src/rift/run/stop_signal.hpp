// SIGTERM and SIGINT during a run (a batch system's notice before it kills a job, or Ctrl-C): the
// run ends the step it is in, writes a checkpoint and stops, to go on with `rift run --restart`.
// The handler is reset by its first signal, so a second one ends the process at once.
#pragma once

namespace rift::run {

/// Installs the handlers (`rift run` on a scene that can write checkpoints).
void catch_stop_signals();
/// The signal received since, or 0.
int stop_signal();

}  // namespace rift::run
