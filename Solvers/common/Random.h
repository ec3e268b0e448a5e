// Reproducible random numbers.
//
// std::uniform_real_distribution is implementation-defined, so the same seed could give
// different beds with another standard library. We draw 53-bit doubles straight from
// std::mt19937_64, whose output sequence the standard fixes.
#pragma once

#include <cstdint>
#include <random>

namespace craterkit {

class Random {
public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in (0, 1), safe for logarithms and negative powers.
  double uniformOpen() {
    double u;
    do {
      u = uniform();
    } while (u == 0.0);
    return u;
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
  std::mt19937_64 engine_;
};

} // namespace craterkit
