#include "dem/TouchingPairs.h"

namespace craterkit {

namespace {

// The outcome is an integer (the two comparisons combined with &, not ||) so that no branch
// depends on it.
inline unsigned touches(const double* x, const double* r, std::size_t i, std::size_t j) {
  const double d0 = x[3 * j] - x[3 * i], d1 = x[3 * j + 1] - x[3 * i + 1],
               d2 = x[3 * j + 2] - x[3 * i + 2];
  const double dd = (d0 * d0 + d1 * d1) + d2 * d2, sum = r[i] + r[j];
  return static_cast<unsigned>(!(dd >= sum * sum)) & static_cast<unsigned>(dd != 0.0);
}

} // namespace

std::size_t findTouchingPairs(const double* x, const double* r, const std::uint32_t* first,
                              const std::uint32_t* second, char* active, std::size_t begin,
                              std::size_t end, std::uint32_t* touching) {
  std::size_t count = 0;
  for (std::size_t k = begin; k < end; ++k) {
    // Written whatever the outcome and kept by counting it: no branch on the outcome.
    const unsigned touch = touches(x, r, first[k], second[k]);
    touching[count] = static_cast<std::uint32_t>(k);
    count += touch;
    // A pair that separates (rare, so this branch is well predicted) does not carry its history.
    if ((touch ^ 1u) & static_cast<unsigned>(active[k] != 0))
      active[k] = 0;
  }
  return count;
}

} // namespace craterkit
