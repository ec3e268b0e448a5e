#include "sph/LateStageSchedule.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

double lateStageSoundSpeedAt(const SphParams& par, double t) {
  const double c1 = par.lateStageSoundSpeed, c0 = par.lateStageInitialSoundSpeed;
  if (!(c0 > c1) || !(t > par.lateStageTime) || !(par.lateStageTime > 0.0))
    return std::max(c0, c1);
  // Stage k starts where the power law c0 (t/t_s)^(−q) reaches c0 2^(−k/4).
  const double k =
      std::floor(4.0 * par.lateStageSoundSpeedExponent * std::log2(t / par.lateStageTime));
  return std::max(c1, c0 * std::exp2(-0.25 * k));
}

} // namespace craterkit
