// A DEM run driven by requested output times, for time-dependent pipelines (the shared
// protocol is common/TimeDrivenRun.h; positions are step counts, snapshots checkpoint bytes).
//
// Holds the initial state, advances the solver to any later time, and keeps serialized
// snapshots of earlier output times so that a request for an earlier time restarts from
// the nearest kept snapshot (or from the initial state), never from a stale state.
//
// With a checkpoint file, the file is written every checkpointEvery steps and at the end of
// every request, and it is never overwritten by an earlier state: a request for a time before
// the file's (after a resume, or after going back) is served by a run from the start that
// writes no checkpoint until it has passed the file's step again.
#pragma once

#include "common/NamedValue.h"
#include "common/TimeDrivenRun.h"
#include "dem/DemSolver.h"

#include <memory>
#include <string>
#include <vector>

namespace craterkit {

class DemRun : public TimeDrivenRun<DemSolver, long long, std::string> {
public:
  // startTime: simulation time of the initial state; keptStates: snapshots kept in memory.
  DemRun(const ParticleSet& initial, const DemParams& params, double startTime = 0.0,
         std::size_t keptStates = 16);

  // The state at the first step at or after `time` (times before the start give the start).
  const DemSolver& advanceTo(double time, const ProgressCallback& progress = {},
                             const std::string& checkpointPath = {}, long long checkpointEvery = 0);
  // Continues from a checkpoint file written by an earlier run of the same set-up.
  void resumeFrom(const std::string& checkpointPath);
  // Simulation time of the furthest state written to or resumed from the checkpoint file
  // (negative if none).
  double checkpointTime() const {
    const long long step = checkpointPosition();
    return step < 0 ? -1.0 : startTime_ + step * params_.dt;
  }

  double time() const { return startTime_ + solver_->time(); }

private:
  ParticleSet initial_;
  DemParams params_;
  double startTime_;
};

// What the DEMIntegrator writes as field data, in its order: time, step, step size and normal
// stiffness, the energies, momenta, largest overlap, contacts, overlap warning steps, and the
// surface gravity (3 components) the run was set up with.
std::vector<NamedValue> demFields(const DemRun& run, const double* gravity);

} // namespace craterkit
