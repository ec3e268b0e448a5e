#include "dem/DemRun.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace craterkit {

DemRun::DemRun(const ParticleSet& initial, std::function<ParticleSet()> again,
               const DemParams& params, double startTime, std::size_t keptStates)
    : TimeDrivenRun(std::make_unique<DemSolver>(initial, params), keptStates, -1),
      initial_(std::move(again)), params_(params), startTime_(startTime) {}

DemRun::DemRun(const ParticleSet& initial, const DemParams& params, double startTime,
               std::size_t keptStates)
    : DemRun(
          initial, [initial] { return initial; }, params, startTime, keptStates) {}

const DemSolver& DemRun::advanceTo(double time, const ProgressCallback& progress,
                                   const std::string& checkpointPath, long long checkpointEvery) {
  const double dt = params_.dt;
  const long long target =
      std::max(0LL, static_cast<long long>(std::ceil((time - startTime_) / dt - 1e-9)));
  if (target != solver_->stepCount())
    leaving([&] { return solver_->checkpointBytes(); });
  goBackTo(
      target, solver_->stepCount(),
      [&] { return std::make_unique<DemSolver>(initial_(), params_); },
      [](const std::string& bytes) {
        return std::make_unique<DemSolver>(DemSolver::fromCheckpointBytes(bytes));
      });
  if (target > solver_->stepCount()) {
    const long long start = solver_->stepCount();
    // Behind the checkpoint file's state: no checkpoint until it is passed.
    const long long quiet =
        checkpointPath.empty() ? start : std::min(target, std::max(start, checkpointPosition()));
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
        aheadOfCheckpoint(solver_->stepCount()))
      solver_->writeCheckpoint(checkpointPath); // every requested state is recoverable
    if (!checkpointPath.empty())
      checkpointReached(solver_->stepCount());
  }
  standAt(solver_->stepCount());
  return *solver_;
}

void DemRun::resumeFrom(const std::string& checkpointPath) {
  std::unique_ptr<DemSolver> solver;
  try {
    solver = std::make_unique<DemSolver>(DemSolver::readCheckpoint(checkpointPath));
  } catch (...) {
    // The file could not be resumed from: never overwrite it (no checkpoint is ever ahead).
    checkpointReached(std::numeric_limits<long long>::max());
    throw;
  }
  const long long step = solver->stepCount();
  resumed(std::move(solver), step);
  params_ = solver_->params();
}

std::vector<NamedValue> demFields(const DemRun& run, const double* gravity) {
  const DemSolver& solver = run.solver();
  const DemDiagnostics d = solver.diagnostics();
  using V = NamedValue;
  return {V::number("Time", run.time()),
          V::number("Step", static_cast<double>(d.step)),
          V::number("TimeStep", solver.params().dt),
          V::number("NormalStiffness", solver.params().contact.kN),
          V::number("KineticEnergy", d.kineticEnergy),
          V::number("RotationalEnergy", d.rotationalEnergy),
          V::number("ElasticEnergy", d.elasticEnergy),
          V::number("GravitationalEnergy", d.gravitationalEnergy),
          V::vector("TotalMomentum", {d.momentum[0], d.momentum[1], d.momentum[2]}),
          V::vector("TotalAngularMomentum",
                    {d.angularMomentum[0], d.angularMomentum[1], d.angularMomentum[2]}),
          V::number("MaxOverlap", d.maxOverlap),
          V::number("Contacts", static_cast<double>(d.contacts)),
          V::number("OverlapWarningSteps", static_cast<double>(solver.overlapWarnings())),
          V::vector("Gravity", {gravity[0], gravity[1], gravity[2]})};
}

} // namespace craterkit
