// Step 1 of the SPH → DEM hand-off (docs/physics.md §3; Handoff.h): the SPH state split into
// compact material (|v| ≤ EjectaSpeedLimit), which the alpha shape and the bed take over, and
// ejecta faster than the limit, which become particles or leave (docs/physics.md §3.3, step 2).
// The compact material higher than one alpha radius above the target's surface is the curtain
// of a late hand-off: it lands, so it becomes particles as the ejecta do. Also the compact
// material as the later steps search it (positions, support radii, a cell list).
#pragma once

#include "common/CellList.h"
#include "handoff/Handoff.h"

#include <cstddef>
#include <vector>

namespace craterkit {

// Throws InputError naming what is missing or not finite in the SPH state, or an empty bed.
void checkInputs(const SphSnapshot& sph, const ParticleSet& bed);

struct SplitSets {
  std::vector<std::size_t> compact, ejecta; // SPH indices
};

// Throws InputError when fewer than 4 particles are compact (no shape to build).
SplitSets splitBySpeed(const SphSnapshot& sph, double ejectaSpeedLimit);

// The curtain: compact material higher than one alpha radius above the surface (never, when
// curtainAsParticles is off).
struct CurtainTest {
  bool enabled = true;
  double surfaceHeight = 0.0, alphaRadius = 0.0;
  bool operator()(const SphSnapshot& sph, std::size_t i) const {
    return enabled && sph.x[3 * i + 2] > surfaceHeight + alphaRadius;
  }
};

std::vector<std::size_t> curtainOf(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                                   const CurtainTest& inCurtain);

// Mass, momentum and angular momentum about the origin of a subset of the SPH particles.
HandoffTotals sphTotals(const SphSnapshot& s, const std::vector<std::size_t>& subset);

// The compact particles in the order of `compact`: positions, support radii (2 alpha radii
// where the SPH state gives none) and a cell list of cells as wide as the largest.
struct CompactCloud {
  std::vector<double> x, h;
  double hmax = 0.0;
  CellList cells;
  CompactCloud(const SphSnapshot& sph, const std::vector<std::size_t>& compact, double alphaRadius);
};

} // namespace craterkit
