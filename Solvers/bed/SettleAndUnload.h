// The settled RCP and the Loose preparations (docs/physics.md §7): a loose random fill, taller than
// the bed and with overlaps of a few per cent left to the DEM, settled under gravity with the
// SSDEM solver and a soft, strongly damped contact law until its kinetic energy has decayed (RCP
// with SettlingFriction and no rolling resistance; Loose poured with high sliding and rolling
// friction), unloaded to a quarter of its weight, its contacts stiffened to the DEM stage's law
// (at most fourfold at a time, gravity lowered by the same factor before each step), trimmed to
// the surface and brought to rest under the full gravity in the DEM stage's own contact law
// (GranularBedParams' stage* fields): its overlaps carry its weight.
#pragma once

#include "bed/GranularBed.h"

namespace craterkit {

// The settled bed; records the stages "placement", "relaxation", "settling", "stiffening",
// "trim" and "rest", the settling figures and the rest's in `report`.
ParticleSet settledRandomBed(const GranularBedParams& p, GranularBedReport& report,
                             const ProgressCallback& progress);

} // namespace craterkit
