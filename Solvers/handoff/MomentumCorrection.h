// The last step of the SPH → DEM hand-off (docs/physics.md §3.3 step 6; Handoff.h): the mapped bed
// particles made to carry exactly the linear and angular momentum (about the origin, spin
// included) of the compact SPH material below the curtain: a uniform velocity shift
// ΔV = (P_SPH − P_DEM)/M_DEM, then a rigid rotation Δω × (r − r_cm) about their centre of mass
// with I Δω = L_SPH − L_DEM (I: their inertia tensor about it), which leaves P unchanged.
#pragma once

#include "common/ParticleSet.h"
#include "handoff/Handoff.h"

#include <cstddef>
#include <string>
#include <vector>

namespace craterkit {

// What the mapped bed carries: the compact material's totals less the curtain's.
HandoffTotals mappedTarget(const HandoffTotals& compact, const HandoffTotals& curtain);

// Corrects the velocities of the particles `mapped` of p to carry `target`; sets `before` (the
// mapped set's totals before) and `after`, and adds a warning where it cannot (no mapped
// particle, or collinear ones).
void correctMomentum(ParticleSet& p, const std::vector<std::size_t>& mapped,
                     const HandoffTotals& target, HandoffTotals& before, HandoffTotals& after,
                     std::vector<std::string>& warnings);

} // namespace craterkit
