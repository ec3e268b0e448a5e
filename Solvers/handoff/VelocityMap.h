// Step 4 of the SPH → DEM hand-off (docs/physics.md §3.3 step 5; Handoff.h): the compact SPH
// material's velocity mapped onto the kept bed particles inside the target region. Each takes
// a kernel-weighted linear fit v(x') ≈ v̄ + G (x' − x̄) of the compact SPH velocities within one
// support radius (weights: the SPH cubic spline, sph/Kernels.h, times the mass; exact for rigid
// motions), limited as Barth & Jespersen (1989) limit a reconstruction to the range of the
// neighbours' velocities, so that a grain beyond one-sided neighbours gets no invented speed;
// Shepard's average where the fit is ill-posed, the nearest SPH particle's velocity where fewer
// than minNeighbours are in reach. Spin ω = ½ ∇×v from the same fit.
#pragma once

#include "common/ParticleSet.h"
#include "handoff/Handoff.h"
#include "handoff/Split.h"

#include <cstddef>
#include <vector>

namespace craterkit {

// Sets velocity and angular velocity of the particles `mapped` of p.
void mapVelocities(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                   const CompactCloud& cloud, int minNeighbours,
                   const std::vector<std::size_t>& mapped, ParticleSet& p);

} // namespace craterkit
