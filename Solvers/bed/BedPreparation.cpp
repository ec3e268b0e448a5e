#include "bed/BedPreparation.h"

#include "bed/LatticeBed.h"
#include "common/Error.h"

#include <cmath>
#include <sstream>

namespace craterkit {

double expectedParticles(const GranularBedParams& p) {
  const double fraction =
      p.packing == GranularBedParams::Packing::HCP ? kHcpFraction : p.packingFraction;
  return fraction * p.container.fillVolume() / (4.0 / 3.0 * M_PI * p.sizes.moment(3));
}

void checkCap(double n, std::int64_t cap) {
  if (n > static_cast<double>(cap)) {
    std::ostringstream msg;
    msg << "the bed needs about " << static_cast<long long>(n)
        << " particles, more than MaxParticles (" << cap
        << "): use larger particles, a smaller container, or raise MaxParticles";
    throw InputError(msg.str());
  }
}

void endStage(GranularBedReport& report, const char* name,
              std::chrono::steady_clock::time_point& start) {
  const auto now = std::chrono::steady_clock::now();
  report.stageSeconds.emplace_back(name, std::chrono::duration<double>(now - start).count());
  start = now;
}

ProgressCallback subRange(const ProgressCallback& progress, double lo, double hi) {
  if (!progress)
    return {};
  return [progress, lo, hi](double f) { return progress(lo + (hi - lo) * f); };
}

} // namespace craterkit
