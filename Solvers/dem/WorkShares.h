// How a DEM step's loops are split among the threads (pkdgrav SSDEM; Schwartz, Richardson &
// Michel 2012: one step is a contact search, a contact law and a force sum over the particles).
//
// A step's particles (and their pairs) are split into one contiguous range per thread, each
// thread waiting only for the threads before it (common/ThreadChain.h): a thread that finishes
// early still waits at the step's end. Equal ranges are not
// equal times (the threads' processors are not equally fast on a shared machine, and the pairs
// and particles differ in cost), and the waits took 9 % of a two-thread run's samples
// (benchmarks/JOURNAL.md, DEM bed impact). So the ranges follow the measured times: after each
// step every thread's share moves part of the way towards the share that would have made the
// times equal (its speed, items per second, over the sum of the speeds). Which thread does an
// item never changes its arithmetic, so the results stay bit-identical for any split and any
// thread count; only the waits change.
#pragma once

#include <cstddef>
#include <vector>

namespace craterkit {

class WorkShares {
public:
  // Equal shares for `threads` threads, unless it has that many already.
  void resize(std::size_t threads);
  // The first item of thread t of a team of T threads, of `total` items (t = T gives total).
  // A team of another size than the shares' splits evenly.
  std::size_t begin(std::size_t total, std::size_t t, std::size_t T) const;
  // Thread t of a team of T spent `seconds` on its range (called once a step by every thread).
  void record(std::size_t t, std::size_t T, double seconds);
  // Serially, after the region: moves the shares towards equal times, then clears the times.
  void update();

private:
  std::vector<double> edge_;    // threads + 1 cumulative shares: edge_[0] = 0, edge_.back() = 1
  std::vector<double> seconds_; // per thread, kPad apart (no two threads on one cache line)
  static constexpr std::size_t kPad = 8;
};

} // namespace craterkit
