#include "dem/WorkShares.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

void WorkShares::resize(std::size_t threads) {
  threads = std::max<std::size_t>(1, threads);
  if (edge_.size() == threads + 1)
    return;
  edge_.resize(threads + 1);
  for (std::size_t t = 0; t <= threads; ++t)
    edge_[t] = static_cast<double>(t) / static_cast<double>(threads);
  seconds_.assign(kPad * threads, 0.0);
}

std::size_t WorkShares::begin(std::size_t total, std::size_t t, std::size_t T) const {
  if (t >= T)
    return total;
  if (edge_.size() != T + 1)
    return total * t / T;
  const double b = std::floor(edge_[t] * static_cast<double>(total));
  return std::min(total, static_cast<std::size_t>(b));
}

void WorkShares::record(std::size_t t, std::size_t T, double seconds) {
  if (edge_.size() == T + 1)
    seconds_[kPad * t] = seconds;
}

void WorkShares::update() {
  const std::size_t T = edge_.size() - 1;
  if (T < 2)
    return;
  // Speeds: share over time. A thread with no time (or a nonsense one) leaves the shares as
  // they are.
  std::vector<double> speed(T);
  double sum = 0.0;
  for (std::size_t t = 0; t < T; ++t) {
    const double s = seconds_[kPad * t], share = edge_[t + 1] - edge_[t];
    seconds_[kPad * t] = 0.0;
    if (!(s > 0.0) || !std::isfinite(s))
      return;
    speed[t] = share / s;
    sum += speed[t];
  }
  // Part of the way only (a thread preempted for one step must not lose its work for long),
  // and never below a quarter of an even share.
  constexpr double kGain = 0.3;
  const double least = 0.25 / static_cast<double>(T);
  std::vector<double> share(T);
  double total = 0.0;
  for (std::size_t t = 0; t < T; ++t) {
    const double now = edge_[t + 1] - edge_[t];
    share[t] = std::max(least, now + kGain * (speed[t] / sum - now));
    total += share[t];
  }
  for (std::size_t t = 0; t < T; ++t)
    edge_[t + 1] = edge_[t] + share[t] / total;
  edge_[T] = 1.0;
}

} // namespace craterkit
