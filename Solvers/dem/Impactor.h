// A single spherical impactor placed above a bed, for DEM impact runs without the SPH stage.
#pragma once

#include "common/ParticleSet.h"

namespace craterkit {

struct ImpactorParams {
  double radius = 0.5;     // m
  double density = 8900.0; // kg/m^3
  double speed = 2.0;      // m/s
  double angle = 0.0;      // degrees from the vertical, tilted towards +x
  int material = 1;
  // Impact point on the surface (x, y) and the surface height; the impactor starts a
  // quarter radius above the surface along its incoming path.
  double target[3] = {0.0, 0.0, 0.0};
};

// Appends the impactor (Id one above the largest) and returns its index. Throws InputError.
std::size_t addImpactor(ParticleSet& particles, const ImpactorParams& params);

} // namespace craterkit
