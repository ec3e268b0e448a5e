// The settled RCP preparation (docs/physics.md §7): a loose random fill, taller than the bed and
// with overlaps of a few per cent left to the DEM, settled under gravity with the SSDEM solver
// and a soft, strongly damped contact law until its kinetic energy has decayed, unloaded by
// lowering gravity 64-fold, trimmed to the surface and relaxed so that no two particles overlap.
#pragma once

#include "bed/GranularBed.h"

namespace craterkit {

// The settled bed; records the stages "placement", "relaxation", "settling", "trim" and
// "final relaxation" and the settling figures in `report`.
ParticleSet settledRandomBed(const GranularBedParams& p, GranularBedReport& report,
                             const ProgressCallback& progress);

} // namespace craterkit
