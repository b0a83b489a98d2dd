// The run loop of both methods: a method's stepper (run/runner.cpp: PD's explicit steps, or the load
// steps of dynamic relaxation; run/mpm_runner.cpp: MPM's steps) gives each step's stages, and the
// loop runs them in this order: advance (the step itself; false where a stop cut it short, having
// written its own checkpoint), record (the outputs its cadences make due: history row, snapshot,
// progress; run/cadence.hpp), then the checkpoint that falls due or that a stop asks for, which
// ends the run (run/checkpointing.hpp; gather brings a distributed run's state to rank 0 first).
#pragma once
#include "rift/core/phase_times.hpp"
#include "rift/run/checkpointing.hpp"

namespace rift::run {

template <class Advance, class Record, class Gather, class WriteState>
struct Stepper {
  Advance advance;          // bool(long step)
  Record record;            // void(long step)
  Gather gather;            // void(long step)
  WriteState write_state;   // void(io::CheckpointWriter&)
};
template <class A, class R, class G, class W>
Stepper(A, R, G, W) -> Stepper<A, R, G, W>;

/// Steps first_step to last_step of `stepper`; `time` is its model's.
template <class S>
void run_steps(S& stepper, long first_step, long last_step, const double& time, Checkpointing& checkpoints, Result& res) {
  for (long step = first_step; step <= last_step; ++step) {
    if (!stepper.advance(step)) break;
    PhaseClock output_clock(Phase::output);
    stepper.record(step);
    if (checkpoints.after_step(step, time, res, [&] { stepper.gather(step); }, stepper.write_state)) break;
  }
}

}  // namespace rift::run
