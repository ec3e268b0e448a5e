// The HCP preparation: a hexagonal close-packed lattice of equal spheres (ABAB stacking of
// triangular layers, layer spacing 2r sqrt(2/3)). Box beds stand on the floor; bowl beds are
// anchored so that the top layer touches the free surface.
#pragma once

#include "bed/GranularBed.h"

namespace craterkit {

constexpr double kHcpFraction = 0.74048048969306104; // π / (3 √2)

// The lattice sites inside the container (validated parameters, monodisperse sizes).
ParticleSet hcpLatticeBed(const GranularBedParams& p, const ProgressCallback& progress);

} // namespace craterkit
