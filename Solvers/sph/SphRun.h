// An SPH run driven by requested output times, for time-dependent pipelines, with
// checkpoint files.
//
// Steps stop exactly at requested times. Snapshots of earlier requested times are kept in
// memory, so asking for an earlier time restarts from the nearest kept one (or the initial
// state), never from a stale state. A checkpoint file (binary, written atomically every N
// steps and at each requested time) holds the whole particle state; a run of the same set-up
// resumes from it.
#pragma once

#include "common/Progress.h"
#include "sph/SphSolver.h"

#include <limits>
#include <map>
#include <memory>
#include <string>

namespace craterkit {

class SphRun {
public:
  SphRun(const SphState& initial, const SphParams& params, std::size_t keptStates = 8);
  const SphSolver& advanceTo(double time, const ProgressCallback& progress = {},
                             const std::string& checkpointPath = {}, long long checkpointEvery = 0);
  // Continues from a checkpoint of the same set-up (same particle count and materials).
  void resumeFrom(const std::string& checkpointPath);
  double time() const { return solver_->time(); }
  const SphSolver& solver() const { return *solver_; }

private:
  struct Snapshot {
    SphState state;
    double time;
    std::size_t steps;
    double nextStep;
  };
  void keep();
  SphState initial_;
  SphParams params_;
  std::size_t keptStates_;
  std::unique_ptr<SphSolver> solver_;
  std::map<double, Snapshot> kept_;
  double checkpointTime_ =
      -std::numeric_limits<double>::infinity(); // of the state in the checkpoint file
};

// Checkpoint files: "CKSPH1\n\0", particle count and steps (uint64), time and the next time
// step (double), then the arrays x v m ρ u h S α D (double) and material (int32), native
// byte order. Written to PATH.part and renamed, so a crash never leaves a half-written file.
void writeSphCheckpoint(const std::string& path, const SphState& s, double time, std::size_t steps,
                        double nextStep);
// Throws InputError naming the file and what is wrong with it.
SphState readSphCheckpoint(const std::string& path, double& time, std::size_t& steps,
                           double& nextStep);

} // namespace craterkit
