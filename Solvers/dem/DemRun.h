// A DEM run driven by requested output times, for time-dependent pipelines (the shared
// protocol is common/TimeDrivenRun.h; positions are step counts, snapshots checkpoint bytes).
//
// Advances the solver to any later time, and keeps serialized snapshots (checkpoint bytes) of
// earlier output times so that a request for an earlier time restarts from the nearest kept
// snapshot (or from the initial state, which it holds or is given again), never from a stale
// state.
//
// With a checkpoint file, the file is written every checkpointEvery steps and at the end of
// every request, and it is never overwritten by an earlier state: a request for a time before
// the file's (after a resume, or after going back) is served by a run from the start that
// writes no checkpoint until it has passed the file's step again.
#pragma once

#include "common/NamedValue.h"
#include "common/TimeDrivenRun.h"
#include "dem/DemSolver.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace craterkit {

class DemRun : public TimeDrivenRun<DemSolver, long long, std::string> {
public:
  // startTime: simulation time of the initial state; keptStates: snapshots kept in memory.
  // again() gives the initial state again, for a request before every kept snapshot, so that
  // the run holds no copy of it (the DEMIntegrator rebuilds it from its input, which the
  // pipeline holds anyway).
  DemRun(const ParticleSet& initial, std::function<ParticleSet()> again, const DemParams& params,
         double startTime, std::size_t keptStates);
  // The same holding a copy of the initial state.
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
  std::function<ParticleSet()> initial_;
  DemParams params_;
  double startTime_;
};

// What the DEMIntegrator writes as field data, in its order: time, step, step size and normal
// stiffness, the energies, momenta, largest overlap, contacts, overlap warning steps, and the
// surface gravity (3 components) the run was set up with.
std::vector<NamedValue> demFields(const DemRun& run, const double* gravity);

} // namespace craterkit
