// The random fill of the RCP preparation: radii are drawn until their volume fills the
// container to the target packing fraction, centres are placed uniformly at random, and
// overlaps are removed by collective rearrangement (Jacobi relaxation of pair overlaps with
// projection onto the container) while the radii grow to full size. Without settling this is
// the whole RCP bed; a settling bed starts from a looser, taller fill (bed/SettleAndUnload.h).
#pragma once

#include "bed/GranularBed.h"

#include <cstdint>

namespace craterkit {

// What a random fill fills and how far it relaxes: spheres whose volume is the bed's
// PackingFraction of `container` (less a wall layer of half a mean radius), at most
// `maxParticles` of them, relaxed until their radii are full and no pair overlaps by more than
// `overlapTolerance` (relative to the smaller radius), the radii growing over about
// `growthSweeps` sweeps.
struct RandomFillSpec {
  Container container;
  std::int64_t maxParticles = 0;
  double overlapTolerance = 0.0;
  double growthSweeps = 0.0;
};

// The random fill the spec describes; records the stages "placement" and "relaxation" and the
// relaxation sweeps in `report`.
ParticleSet randomFill(const GranularBedParams& p, const RandomFillSpec& spec,
                       GranularBedReport& report, const ProgressCallback& progress);

// The RCP bed without settling: a random fill of the container with no overlap left.
ParticleSet randomBed(const GranularBedParams& p, GranularBedReport& report,
                      const ProgressCallback& progress);

} // namespace craterkit
