#include "DemRun.h"

#include <cmath>
#include <sstream>

namespace craterkit {

DemRun::DemRun(const ParticleSet& initial, const DemParams& params, double startTime,
               std::size_t keptStates)
    : initial_(initial), params_(params), startTime_(startTime), keptStates_(keptStates),
      solver_(std::make_unique<DemSolver>(initial, params)) {}

void DemRun::keep() {
  if (keptStates_ == 0 || kept_.count(solver_->stepCount()))
    return;
  std::ostringstream out;
  solver_->writeCheckpoint(out);
  kept_[solver_->stepCount()] = out.str();
  while (kept_.size() > keptStates_)
    kept_.erase(kept_.begin()); // the initial state is always recoverable from the input
}

const DemSolver& DemRun::advanceTo(double time, const ProgressCallback& progress,
                                   const std::string& checkpointPath, long long checkpointEvery) {
  const double dt = params_.dt;
  const long long target =
      std::max(0LL, static_cast<long long>(std::ceil((time - startTime_) / dt - 1e-9)));
  if (target < solver_->stepCount()) {
    auto it = kept_.upper_bound(target);
    if (it == kept_.begin()) {
      solver_ = std::make_unique<DemSolver>(initial_, params_);
    } else {
      --it;
      std::istringstream in(it->second);
      solver_ = std::make_unique<DemSolver>(DemSolver::readCheckpoint(in, it->second.size()));
    }
  }
  if (target > solver_->stepCount()) {
    const long long start = solver_->stepCount();
    // Behind the checkpoint file's state: no checkpoint until it is passed.
    const long long quiet =
        checkpointPath.empty() ? start : std::min(target, std::max(start, checkpointStep_));
    const auto part = [&](long long from, long long to) -> ProgressCallback {
      if (!progress)
        return {};
      return [&progress, from, to, start, target](double f) {
        return progress((static_cast<double>(from - start) + f * static_cast<double>(to - from)) /
                        static_cast<double>(target - start));
      };
    };
    if (quiet > start)
      solver_->advanceTo(static_cast<double>(quiet) * dt, part(start, quiet));
    if (target > solver_->stepCount())
      solver_->advanceTo(static_cast<double>(target) * dt, part(solver_->stepCount(), target),
                         checkpointPath, checkpointEvery);
    while (solver_->stepCount() < target) // advanceTo rounds to whole steps
      solver_->step();
    if (!checkpointPath.empty() &&
        (checkpointEvery <= 0 || solver_->stepCount() % checkpointEvery != 0) &&
        solver_->stepCount() > checkpointStep_)
      solver_->writeCheckpoint(checkpointPath); // every requested state is recoverable
    if (!checkpointPath.empty())
      checkpointStep_ = std::max(checkpointStep_, solver_->stepCount());
  }
  keep();
  return *solver_;
}

void DemRun::resumeFrom(const std::string& checkpointPath) {
  solver_ = std::make_unique<DemSolver>(DemSolver::readCheckpoint(checkpointPath));
  params_ = solver_->params();
  kept_.clear();
  checkpointStep_ = solver_->stepCount();
}

} // namespace craterkit
