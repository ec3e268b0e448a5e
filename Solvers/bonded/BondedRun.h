// A run of the bonded-particle model of Watson & Steinhauser 2017 (Materials 10:379, seed 003;
// see WatsonSteinhauser2017.h and BondedSolver.h) driven by requested output times, for
// time-dependent pipelines. The protocol is the shared one of common/TimeDrivenRun.h, with
// step counts as positions (the solver's Δt is fixed) and copies of the solver as snapshots
// (the solver holds its whole state by value, so a copy continues bit for bit; shared_ptr
// because the protocol's snapshot map needs a default-constructible value).
//
// A request for a later time advances to the first step at or after it; an earlier one
// restarts from the nearest kept snapshot or from the initial state. With a checkpoint file,
// the file is written every checkpointEvery steps and at the end of every request, and it is
// never overwritten by an earlier state (after a resume or going back, no checkpoint is written
// until the run has passed the file's step again).
#pragma once

#include "bonded/BondedSolver.h"
#include "common/Progress.h"
#include "common/TimeDrivenRun.h"

#include <memory>
#include <string>

namespace craterkit {

using BondedSnapshot = std::shared_ptr<const BondedSolver>;

class BondedRun : public TimeDrivenRun<BondedSolver, long long, BondedSnapshot> {
public:
  BondedRun(const BondedSystem& initial, const BondedSolverParams& params = {},
            std::size_t keptStates = 8);

  // The state at the first step at or after `time` (times before 0 give the initial state).
  const BondedSolver& advanceTo(double time, const ProgressCallback& progress = {},
                                const std::string& checkpointPath = {},
                                long long checkpointEvery = 0);
  // Continues from a checkpoint file written by a run of the same set-up (same particle and
  // bond counts); throws InputError naming the file otherwise.
  void resumeFrom(const std::string& checkpointPath);

  double time() const { return solver_->time(); }
  // Simulation time of the furthest state written to or resumed from the checkpoint file
  // (negative if none).
  double checkpointTime() const {
    const long long step = checkpointPosition();
    return step < 0 ? -1.0 : static_cast<double>(step) * solver_->timeStep();
  }

private:
  long long stepOf(double time) const;
  void advanceSteps(long long target, const ProgressCallback& progress,
                    const std::string& checkpointPath, long long checkpointEvery);

  BondedSystem initial_;
  BondedSolverParams params_;
};

} // namespace craterkit
