// The impactor stopped in the target at the late-stage switch (SphParams::lateStageStopMaterial;
// SPHImpact's StopImpactorAtLateStage; docs/physics.md §2.8).
//
// The switch gives every solid the late stage's soft law (K' = ρ0 c², at Ryugu's gravity c =
// 0.47 m/s: K' ≈ 260 Pa in the regolith). An impactor that still moves through the target then
// meets almost no resistance: a copper particle 7.5 times heavier than its regolith neighbours,
// still at 18 m/s at the 1 ms switch of the SCI stage, sank on through the target for tens of
// seconds (to 4.7 m at 40 s, docs/validation.md), where the early law's pressures would have
// stopped it within centimetres. With this option each particle of the material shares its
// momentum with the other material's particles within its support, as in a perfectly inelastic
// collision: they all take their common centre-of-mass velocity, and the kinetic energy this
// removes becomes their internal energy, shared by mass. Total momentum and total energy are
// kept to round-off; angular momentum changes by the moment of the velocity changes about the
// groups' centres (second order in the kernel's size). The particles are taken in index order,
// each with its neighbours as they stand after the earlier ones.
#pragma once

#include "sph/Material.h"
#include "sph/SphState.h"

#include <vector>

namespace craterkit {

// Stops each particle of MATERIAL in the flow of the particles of the other materials within its
// support (rigid ones, such as the container, excepted). Returns the kinetic energy turned into
// internal energy (J); 0 if no particle of the material has such neighbours.
double stopInFlow(SphState& s, int material, const std::vector<Material>& materials);

} // namespace craterkit
