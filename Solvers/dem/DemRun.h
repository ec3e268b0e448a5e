// A DEM run driven by requested output times, for time-dependent pipelines.
//
// Holds the initial state, advances the solver to any later time, and keeps serialized
// snapshots of earlier output times so that a request for an earlier time restarts from
// the nearest kept snapshot (or from the initial state), never from a stale state.
#pragma once

#include "DemSolver.h"

#include <map>
#include <memory>
#include <string>

namespace craterkit {

class DemRun {
public:
  // startTime: simulation time of the initial state; keptStates: snapshots kept in memory.
  DemRun(const ParticleSet& initial, const DemParams& params, double startTime = 0.0,
         std::size_t keptStates = 16);

  // The state at the first step at or after `time` (times before the start give the start).
  const DemSolver& advanceTo(double time, const ProgressCallback& progress = {},
                             const std::string& checkpointPath = {}, long long checkpointEvery = 0);
  // Continues from a checkpoint file written by an earlier run of the same set-up.
  void resumeFrom(const std::string& checkpointPath);

  double time() const { return startTime_ + solver_->time(); }
  const DemSolver& solver() const { return *solver_; }

private:
  void keep();

  ParticleSet initial_;
  DemParams params_;
  double startTime_;
  std::size_t keptStates_;
  std::unique_ptr<DemSolver> solver_;
  std::map<long long, std::string> kept_; // step -> checkpoint bytes
};

} // namespace craterkit
