#include "sph/SphRun.h"

#include "common/Error.h"

#include <algorithm>
#include <limits>

namespace craterkit {

SphRun::SphRun(const SphState& initial, const SphParams& params, std::size_t keptStates)
    : TimeDrivenRun(std::make_unique<SphSolver>(initial, params), keptStates,
                    -std::numeric_limits<double>::infinity()),
      initial_(initial), params_(params) {}

const SphSolver& SphRun::advanceTo(double time, const ProgressCallback& progress,
                                   const std::string& checkpointPath, long long checkpointEvery) {
  if (time < solver_->time() || !solver_->reached(time))
    leaving([&] {
      return SphKeptState{solver_->state(), solver_->time(), solver_->steps(),
                          solver_->stableStep()};
    });
  goBackTo(
      time, solver_->time(), [&] { return std::make_unique<SphSolver>(initial_, params_); },
      [&](const SphKeptState& kept) {
        return std::make_unique<SphSolver>(kept.state, params_,
                                           SphClock{kept.time, kept.steps, kept.nextStep});
      });
  const double from = solver_->time();
  std::size_t lastCheckpoint = solver_->steps();
  const auto checkpoint = [&] {
    writeSphCheckpoint(checkpointPath, solver_->state(), solver_->time(), solver_->steps(),
                       solver_->stableStep());
    checkpointReached(solver_->time());
  };
  while (!solver_->reached(time)) {
    const double dt = std::min(solver_->stableStep(), time - solver_->time());
    solver_->step(dt);
    // A state behind the file's (a request for an earlier time) never overwrites it.
    if (!checkpointPath.empty() && checkpointEvery > 0 && aheadOfCheckpoint(solver_->time()) &&
        solver_->steps() - lastCheckpoint >= static_cast<std::size_t>(checkpointEvery)) {
      checkpoint();
      lastCheckpoint = solver_->steps();
    }
    reportProgress(progress, (solver_->time() - from) / (time - from));
  }
  if (!checkpointPath.empty() && checkpointEvery > 0 && solver_->steps() != lastCheckpoint &&
      aheadOfCheckpoint(solver_->time()))
    checkpoint();
  standAt(solver_->time());
  return *solver_;
}

void SphRun::resumeFrom(const std::string& checkpointPath) {
  double t = 0.0, next = 0.0;
  std::size_t steps = 0;
  std::string warning;
  warnings_.clear();
  try {
    const SphState s = readSphCheckpoint(checkpointPath, t, steps, next, &warning);
    if (s.size() != initial_.size())
      throw InputError(checkpointPath + ": the checkpoint has " + std::to_string(s.size()) +
                       " particles, this set-up " + std::to_string(initial_.size()));
    for (int m : s.material)
      if (m < 0 || static_cast<std::size_t>(m) >= params_.materials.size())
        throw InputError(checkpointPath +
                         ": the checkpoint names a material this set-up does not have");
    resumed(std::make_unique<SphSolver>(s, params_, SphClock{t, steps, next}), t);
  } catch (...) {
    // The file could not be resumed from: never overwrite it (no checkpoint is ever ahead).
    checkpointReached(std::numeric_limits<double>::infinity());
    throw;
  }
  if (!warning.empty())
    warnings_.push_back(warning);
}

} // namespace craterkit
