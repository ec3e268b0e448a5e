#include "bonded/BondedRun.h"

#include "bonded/ShockViscosity.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace craterkit {

BondedRun::BondedRun(const BondedSystem& initial, const BondedSolverParams& params,
                     std::size_t keptStates)
    : TimeDrivenRun(std::make_unique<BondedSolver>(initial, params), keptStates, -1),
      initial_(initial), params_(params) {}

long long BondedRun::stepOf(double time) const {
  if (!std::isfinite(time))
    throw InputError("BondedRun: the requested time must be finite");
  const double dt = solver_->timeStep();
  // Same rounding as BondedSolver::advanceTo: an output time a whisker past a step is that step.
  return std::max(0LL, static_cast<long long>(std::ceil(time / dt * (1.0 - 1e-12))));
}

// Steps to `target` in pieces that end on multiples of checkpointEvery (where the file is
// written, if the run is past the file's state), with one progress fraction over the whole.
void BondedRun::advanceSteps(long long target, const ProgressCallback& progress,
                             const std::string& checkpointPath, long long checkpointEvery) {
  const long long start = static_cast<long long>(solver_->stepCount());
  const bool periodic = !checkpointPath.empty() && checkpointEvery > 0;
  while (static_cast<long long>(solver_->stepCount()) < target) {
    const long long from = static_cast<long long>(solver_->stepCount());
    const long long to =
        periodic ? std::min(target, (from / checkpointEvery + 1) * checkpointEvery) : target;
    ProgressCallback part;
    if (progress)
      part = [&progress, from, to, start, target](double f) {
        return progress((static_cast<double>(from - start) + f * static_cast<double>(to - from)) /
                        static_cast<double>(target - start));
      };
    solver_->advance(static_cast<std::size_t>(to - from), part);
    if (periodic && to % checkpointEvery == 0 && aheadOfCheckpoint(to)) {
      solver_->writeCheckpoint(checkpointPath);
      checkpointReached(to);
    }
  }
}

const BondedSolver& BondedRun::advanceTo(double time, const ProgressCallback& progress,
                                         const std::string& checkpointPath,
                                         long long checkpointEvery) {
  const long long target = stepOf(time);
  if (target != static_cast<long long>(solver_->stepCount()))
    leaving([&] { return std::make_shared<const BondedSolver>(*solver_); });
  goBackTo(
      target, static_cast<long long>(solver_->stepCount()),
      [&] { return std::make_unique<BondedSolver>(initial_, params_); },
      [](const BondedSnapshot& kept) { return std::make_unique<BondedSolver>(*kept); });
  if (target > static_cast<long long>(solver_->stepCount())) {
    advanceSteps(target, progress, checkpointPath, checkpointEvery);
    // Every requested state is recoverable from the file.
    if (!checkpointPath.empty() && aheadOfCheckpoint(target)) {
      solver_->writeCheckpoint(checkpointPath);
      checkpointReached(target);
    }
  }
  standAt(static_cast<long long>(solver_->stepCount()));
  return *solver_;
}

void BondedRun::resumeFrom(const std::string& checkpointPath) {
  try {
    auto solver = std::make_unique<BondedSolver>(BondedSolver::readCheckpoint(checkpointPath));
    if (solver->system().size() != initial_.size() ||
        solver->system().bonds.size() != initial_.bonds.size())
      throw InputError(checkpointPath + ": the bonded checkpoint has " +
                       std::to_string(solver->system().size()) + " particles and " +
                       std::to_string(solver->system().bonds.size()) + " bonds, this set-up " +
                       std::to_string(initial_.size()) + " and " +
                       std::to_string(initial_.bonds.size()));
    // The same set-up: the law, the impact and the step's settings (the state at a later time
    // differs, the set-up must not: an earlier time is replayed from the initial state).
    const BondedSystem& was = solver->system();
    const ws2017::Law& law = was.law;
    if (law.sigma != initial_.law.sigma || law.epsilon != initial_.law.epsilon ||
        law.kappa != initial_.law.kappa || law.rCut != initial_.law.rCut ||
        was.impactSpeed != initial_.impactSpeed || was.axis != initial_.axis ||
        was.rearFace != initial_.rearFace || was.masses != initial_.masses ||
        solver->params().timeStep != params_.timeStep ||
        solver->params().timeStepFraction != params_.timeStepFraction ||
        solver->params().skin != params_.skin)
      throw InputError(checkpointPath +
                       ": the bonded checkpoint holds another set-up (its law, impact, masses "
                       "or time step differ from this run's): resume with the same, or start "
                       "afresh");
    const BondedSolverParams& saved = solver->params();
    if (saved.dissipation != params_.dissipation ||
        (params_.dissipation != BondedDissipation::None &&
         (saved.shockViscosityLinear != params_.shockViscosityLinear ||
          saved.shockViscosityQuadratic != params_.shockViscosityQuadratic ||
          saved.shockViscosityThreshold != params_.shockViscosityThreshold)))
      throw InputError(checkpointPath + ": the bonded checkpoint was written with Dissipation " +
                       dissipationName(saved.dissipation) +
                       " and its coefficients; this run asks for " +
                       dissipationName(params_.dissipation) +
                       " or other coefficients: resume with the same, or start afresh");
    const long long step = static_cast<long long>(solver->stepCount());
    resumed(std::move(solver), step);
  } catch (...) {
    // The file could not be resumed from: never overwrite it (no checkpoint is ever ahead).
    checkpointReached(std::numeric_limits<long long>::max());
    throw;
  }
}

} // namespace craterkit
