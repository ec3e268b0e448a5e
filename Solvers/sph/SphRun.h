// An SPH run driven by requested output times, for time-dependent pipelines, with
// checkpoint files.
//
// Steps stop exactly at requested times. Snapshots of earlier requested times are kept in
// memory, so asking for an earlier time restarts from the nearest kept one (or the initial
// state), never from a stale state. A checkpoint file (binary, written atomically every N
// steps and at each requested time) holds the whole particle state; a run of the same set-up
// resumes from it (the file's format and functions: sph/SphCheckpoint.h). A run whose resume
// failed writes no checkpoint at all, so that the file it could not read is never overwritten.
// The run protocol is the shared one of common/TimeDrivenRun.h, with simulated times as
// positions.
#pragma once

#include "common/Progress.h"
#include "common/TimeDrivenRun.h"
#include "sph/SphCheckpoint.h"
#include "sph/SphSolver.h"

#include <memory>
#include <string>
#include <vector>

namespace craterkit {

// A kept state of an SphRun: the particles and where the solver stood.
struct SphKeptState {
  SphState state;
  double time;
  std::size_t steps;
  double nextStep;
};

class SphRun : public TimeDrivenRun<SphSolver, double, SphKeptState> {
public:
  SphRun(const SphState& initial, const SphParams& params, std::size_t keptStates = 8);
  const SphSolver& advanceTo(double time, const ProgressCallback& progress = {},
                             const std::string& checkpointPath = {}, long long checkpointEvery = 0);
  // Continues from a checkpoint of the same set-up (same particle count and materials).
  // Throws InputError naming the file if it cannot; the run then writes no checkpoint.
  void resumeFrom(const std::string& checkpointPath);
  double time() const { return solver_->time(); }
  // Warnings of the last resume, each naming the file (an old checkpoint without a checksum).
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  SphState initial_;
  SphParams params_;
  std::vector<std::string> warnings_;
};

} // namespace craterkit
