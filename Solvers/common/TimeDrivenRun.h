// The part of a time-driven run that every solver shares (DemRun, SphRun): a pipeline asks
// for output times in any order, and a request for an earlier time restarts from the nearest
// kept snapshot at or before it (or from a fresh start), never from a stale state; a
// checkpoint file is never overwritten by an earlier state (after a resume or going back,
// the run writes none until it has passed the file's position); a resume replaces the solver
// and forgets the snapshots.
//
// A requested state is kept when the solver leaves it, not when it reaches it: until then the
// solver holds that state itself, so the latest requested state is never held twice (a run
// asked for one time keeps no snapshot at all).
//
// Position is the run's own measure of progress: the step count for a fixed-step solver
// (DemRun), the simulated time for an adaptive one (SphRun). Snapshot is whatever restores
// a solver (checkpoint bytes, a copy of the state).
#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <utility>

namespace craterkit {

template <class Solver, class Position, class Snapshot> class TimeDrivenRun {
public:
  const Solver& solver() const { return *solver_; }
  // Position of the furthest state written to or resumed from the checkpoint file
  // (the constructor's `none` if there is none).
  Position checkpointPosition() const { return checkpoint_; }
  // The snapshots kept in memory (the requested state the solver stands at is not among them).
  std::size_t keptCount() const { return kept_.size(); }

protected:
  TimeDrivenRun(std::unique_ptr<Solver> first, std::size_t keptStates, Position none)
      : solver_(std::move(first)), keptStates_(keptStates), checkpoint_(none) {}

  // If the solver is past `target` (it stands at `now`), replaces it by fresh() or by
  // restore(snapshot) of the latest kept snapshot at or before target.
  template <class Fresh, class Restore>
  void goBackTo(Position target, Position now, Fresh&& fresh, Restore&& restore) {
    if (!(target < now))
      return;
    auto it = kept_.upper_bound(target);
    if (it == kept_.begin()) {
      solver_ = fresh();
    } else {
      --it;
      solver_ = restore(it->second);
    }
  }

  // The solver stands at `now`, a requested state (the end of advanceTo).
  void standAt(Position now) { standing_ = now; }

  // Called before the solver moves (on, or back): keeps the requested state it stands at as
  // make() (once per position), dropping the oldest beyond keptStates: the initial state is
  // always recoverable from the input.
  template <class Make> void leaving(Make&& make) {
    if (!standing_)
      return;
    const Position now = *standing_;
    standing_.reset();
    if (keptStates_ == 0 || kept_.count(now))
      return;
    kept_[now] = make();
    while (kept_.size() > keptStates_)
      kept_.erase(kept_.begin());
  }

  // A checkpoint may be written at `now` only past the file's state.
  bool aheadOfCheckpoint(Position now) const { return now > checkpoint_; }
  void checkpointReached(Position now) { checkpoint_ = std::max(checkpoint_, now); }

  // Continues with a solver restored from the checkpoint file at `at`.
  void resumed(std::unique_ptr<Solver> solver, Position at) {
    solver_ = std::move(solver);
    kept_.clear();
    standing_.reset();
    checkpoint_ = at;
  }

  std::unique_ptr<Solver> solver_;

private:
  std::size_t keptStates_;
  std::map<Position, Snapshot> kept_;
  std::optional<Position> standing_; // the requested state the solver stands at, not yet kept
  Position checkpoint_;
};

} // namespace craterkit
