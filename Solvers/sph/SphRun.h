// An SPH run driven by requested output times, for time-dependent pipelines, with
// checkpoint files.
//
// Steps stop exactly at requested times. Snapshots of earlier requested times are kept in
// memory, so asking for an earlier time restarts from the nearest kept one (or the initial
// state), never from a stale state. A checkpoint file (binary, written atomically every N
// steps and at each requested time) holds the whole particle state; a run of the same set-up
// resumes from it. The run protocol is the shared one of common/TimeDrivenRun.h, with
// simulated times as positions.
#pragma once

#include "common/Progress.h"
#include "common/TimeDrivenRun.h"
#include "sph/SphSolver.h"

#include <memory>
#include <string>

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
  void resumeFrom(const std::string& checkpointPath);
  double time() const { return solver_->time(); }

private:
  SphState initial_;
  SphParams params_;
};

// Checkpoint files: "CKSPH1\n\0", particle count and steps (uint64), time and the next time
// step (double), then the arrays x v m ρ u h S α D (double) and material (int32), native
// byte order. Written to PATH.part and renamed (common/AtomicWrite.h), so a crash never
// leaves a half-written file.
void writeSphCheckpoint(const std::string& path, const SphState& s, double time, std::size_t steps,
                        double nextStep);
// Throws InputError naming the file and what is wrong with it.
SphState readSphCheckpoint(const std::string& path, double& time, std::size_t& steps,
                           double& nextStep);

} // namespace craterkit
