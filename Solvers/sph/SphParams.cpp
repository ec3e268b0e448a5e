#include "sph/SphParams.h"

#include "common/Error.h"

#include <cmath>
#include <string>

namespace craterkit {

void SphParams::validate() const {
  if (materials.empty())
    throw InputError("SPH: no material");
  if (!(alpha >= 0.0) || !(beta >= 0.0) || !std::isfinite(alpha) || !std::isfinite(beta))
    throw InputError("SPH: artificial viscosity alpha and beta must be finite and not negative");
  if (!(wallViscosity >= 0.0 && wallViscosity <= 1.0))
    throw InputError("SPH: the wall viscosity factor must be in [0, 1]");
  if (!(xsph >= 0.0 && xsph <= 1.0))
    throw InputError("SPH: the XSPH factor must be in [0, 1]");
  if (!(kappa > 1.0 && kappa < 10.0))
    throw InputError("SPH: kappa (support radius over particle spacing) must be in (1, 10)");
  if (!(courant > 0.0 && courant <= 1.0))
    throw InputError("SPH: the Courant number must be in (0, 1]");
  if (!(densityFloor < 1.0))
    throw InputError(
        "SPH: the density floor must be below 1 (a fraction of the reference bulk density)");
  if (!(forceFactor > 0.0 && forceFactor <= 1.0))
    throw InputError("SPH: the force time-step factor must be in (0, 1]");
  if (!(errorTolerance > 0.0 && errorTolerance <= 1.0))
    throw InputError("SPH: the error tolerance must be in (0, 1]");
  if (!(minTimeStep >= 0.0))
    throw InputError("SPH: the time-step floor must not be negative");
  if (!(maxSmoothingGrowth == 0.0 ||
        (maxSmoothingGrowth >= 1.0 && std::isfinite(maxSmoothingGrowth))))
    throw InputError("SPH: the smoothing-length growth cap must be 0 (none) or at least 1");
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(gravity[k]) || !std::isfinite(pointMassAt[k]))
      throw InputError("SPH: gravity must be finite");
    if (periodic[k] && !(boxHi[k] > boxLo[k]))
      throw InputError("SPH: a periodic axis needs boxHi > boxLo");
  }
  if (!(pointMassGM >= 0.0) || !std::isfinite(pointMassGM))
    throw InputError("SPH: the point mass GM must be finite and not negative");
  if (!(domainRadius >= 0.0) || !std::isfinite(domainRadius))
    throw InputError("SPH: the domain radius must be finite and not negative (0: no limit)");
  if (!std::isfinite(lateStageTime))
    throw InputError("SPH: the late-stage time must be finite (negative: no late stage)");
  if (lateStageTime >= 0.0 && !(lateStageSoundSpeed > 0.0 && std::isfinite(lateStageSoundSpeed)))
    throw InputError("SPH: the late-stage sound speed must be positive");
  if (!(lateStageInitialSoundSpeed >= 0.0) || !std::isfinite(lateStageInitialSoundSpeed))
    throw InputError("SPH: the late-stage initial sound speed must be finite and not negative "
                     "(0: one switch)");
  if (lateStageInitialSoundSpeed > lateStageSoundSpeed &&
      !(lateStageSoundSpeedExponent > 0.0 && lateStageSoundSpeedExponent <= 2.0))
    throw InputError("SPH: the late-stage sound speed's exponent must be in (0, 2]");
  if (lateStageInitialSoundSpeed > lateStageSoundSpeed && lateStageTime == 0.0)
    throw InputError("SPH: a late-stage sound speed that falls with time needs a late-stage "
                     "time after 0");
  if (!(lateStagePoissonRatio < 0.5) || !std::isfinite(lateStagePoissonRatio))
    throw InputError("SPH: the late-stage Poisson ratio must be below 0.5 (negative: each "
                     "material keeps its own)");
  if (lateStageStopMaterial < -1 || lateStageStopMaterial >= static_cast<int>(materials.size()))
    throw InputError("SPH: the material stopped at the late-stage switch must be one of the " +
                     std::to_string(materials.size()) + " materials (-1: none)");
  if (!(overburdenDensity >= 0.0) || !std::isfinite(overburdenDensity) ||
      !std::isfinite(overburdenSurface))
    throw InputError("SPH: the overburden density must be finite and not negative (0: none) and "
                     "its surface height finite");
  if (!(blockStepLevels >= 0 && blockStepLevels <= 12))
    throw InputError("SPH: the block-step levels (BlockStepLevels) must be in [0, 12]");
  if (blockStepLevels > 0 && (xsph > 0.0 || summationDensity))
    throw InputError("SPH: block steps (BlockStepLevels > 0) need XSPH off and the integrated "
                     "density (no summation density)");
}

void bodyForce(const SphParams& par, const double* x, double g[3]) {
  for (int k = 0; k < 3; ++k)
    g[k] = par.gravity[k];
  if (par.pointMassGM > 0.0) {
    const double dx = x[0] - par.pointMassAt[0], dy = x[1] - par.pointMassAt[1],
                 dz = x[2] - par.pointMassAt[2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 > 0.0) {
      const double k = -par.pointMassGM / (r2 * std::sqrt(r2));
      g[0] += k * dx, g[1] += k * dy, g[2] += k * dz;
    }
  }
}

} // namespace craterkit
