// What the bed preparation methods share: the particle cap, the expected particle count, the
// timing of their stages and the split of their progress into sub-ranges.
#pragma once

#include "bed/GranularBed.h"

#include <chrono>
#include <cstdint>

namespace craterkit {

// Particles the parameters' packing puts into the container's fill volume.
double expectedParticles(const GranularBedParams& p);

// Throws InputError naming MaxParticles if about `n` particles exceed `cap`.
void checkCap(double n, std::int64_t cap);

// Appends the seconds since `start` to the report's stage times under `name`, restarts it.
void endStage(GranularBedReport& report, const char* name,
              std::chrono::steady_clock::time_point& start);

// The progress of a stage that covers [lo, hi] of the whole; empty if `progress` is.
ProgressCallback subRange(const ProgressCallback& progress, double lo, double hi);

} // namespace craterkit
