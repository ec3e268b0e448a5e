// Step 5 of the SPH → DEM hand-off (docs/physics.md §3.3 steps 2 and 7; Handoff.h): the fast ejecta
// and the curtain become DEM particles of the bed's grain density with their SPH mass and
// momentum: one per SPH particle, or (grouped) one per cube of the bed's mean particle diameter
// at the group's centre of mass with its momentum and, as spin, its angular momentum about that
// centre. A group lighter than half a mean bed grain joins the nearest group within groupReach
// cube edges that stays within two bed grains; one still that light with none to join becomes
// no grain (sphLoneDropped). Material whose ballistic flight (uniform gravity) comes down
// outside the container's footprint leaves the domain (sphEscaped). Each particle is moved
// along its own velocity (which keeps momentum and angular momentum), forward first, to the
// nearest place where it overlaps nothing by more than 1 % of a radius inside the container's
// walls; with none it keeps its place, smaller if that fits, else it takes the place of the bed
// particles it overlaps.
#pragma once

#include "common/ParticleSet.h"
#include "handoff/Handoff.h"

#include <cstddef>
#include <vector>

namespace craterkit {

// Appends the ejecta (none if params.dropEjecta) and the curtain to out.particles (after the
// kept bed, origin 1) and sets out's ejecta figures and totals. Bed particles that ejecta
// displace leave out.particles and `mapped` (indices into it, renumbered).
void addEjecta(const SphSnapshot& sph, std::vector<std::size_t> ejecta,
               const std::vector<std::size_t>& curtain, const ParticleSet& bed,
               const TargetRegion& region, const HandoffParams& params,
               std::vector<std::size_t>& mapped, HandoffResult& out);

} // namespace craterkit
