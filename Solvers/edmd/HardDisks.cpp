// The input of the hard-disk system (HardDiskSystem.h): the disks and the box's parameters,
// checked before a run.
#include "edmd/HardDiskSystem.h"

#include "common/Error.h"

#include <cmath>
#include <string>

namespace craterkit {

void HardDisks::add(double px, double py, double pvx, double pvy, double r, double m, int mat,
                    std::int64_t ident) {
  x.push_back(px);
  y.push_back(py);
  vx.push_back(pvx);
  vy.push_back(pvy);
  radius.push_back(r);
  mass.push_back(m);
  material.push_back(mat);
  id.push_back(ident);
}

void HardDiskParams::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(std::string(name) + " must be positive and finite (got " +
                       std::to_string(v) + ")");
  };
  positive(width, "the box width");
  positive(height, "the box height");
  if (!(restitution > 0.0 && restitution <= 1.0))
    throw InputError("Restitution must be in (0, 1] (got " + std::to_string(restitution) + ")");
  if (!(wallRestitution > 0.0 && wallRestitution <= 1.0))
    throw InputError("the wall restitution must be in (0, 1] (got " +
                     std::to_string(wallRestitution) + ")");
  if (!(gravity >= 0.0) || !std::isfinite(gravity))
    throw InputError("Gravity must be zero or positive (got " + std::to_string(gravity) + ")");
  if (!(tcTime >= 0.0) || !std::isfinite(tcTime))
    throw InputError("the TC-model time must be zero or positive");
  if (!(growthRate >= 0.0) || !std::isfinite(growthRate))
    throw InputError("the growth rate must be zero or positive");
  if (growthRate > 0.0 && gravity > 0.0)
    throw InputError("radius growth (compression) runs without gravity");
  if (periodicY && gravity > 0.0)
    throw InputError("gravity along a periodic axis is not supported");
}

} // namespace craterkit
