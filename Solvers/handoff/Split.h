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
#include <cstdint>
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
// where the SPH state gives none) and their cell lists. The cells fit the ordinary support
// radii (common/CellList.h, sizeClasses); the few wide ones (above twice the mean) are also
// listed on cells of their own, so that one wide particle makes no cell, and no search for the
// others, larger. Without wide ones, `cells` is the grid of cells hmax wide the map has always
// searched.
struct CompactCloud {
  std::vector<double> x, h;
  double hmax = 0.0;      // the largest support radius
  double hOrdinary = 0.0; // the largest one not wide (hmax when none is)
  CellList cells;         // every compact particle, cells hOrdinary wide
  // The wide particles (empty when none is), their flags and their own cells, hmax wide.
  std::vector<std::uint32_t> wide;
  std::vector<char> isWide;
  CellList wideCells;
  // With wide particles: each particle's cell (its linear index) on the grid of cells hmax wide
  // that `cells` is without them (orderGrid): the velocity map sums a grain's neighbours in the
  // order a search on that grid visits them (by cell, then by index), so that its figures do
  // not depend on whether a wide particle changed the cells.
  CellList::DenseGeometry orderGrid;
  std::vector<std::uint64_t> orderKey;
  CompactCloud(const SphSnapshot& sph, const std::vector<std::size_t>& compact, double alphaRadius);
  // Calls visit(k) for every compact particle k with |x_k - x| < h[k], and for others (the
  // candidates of the cells): in the order of a search on cells hmax wide when no particle is
  // wide, in no set order otherwise.
  template <class Visit> void forEachCandidateSupport(const double* at, Visit&& visit) const {
    if (wide.empty()) {
      cells.forEachCandidate(at, hmax, visit);
      return;
    }
    cells.forEachCandidate(at, hOrdinary, [&](std::size_t k) {
      if (!isWide[k])
        visit(k);
    });
    wideCells.forEachCandidate(at, hmax, [&](std::size_t w) { visit(std::size_t(wide[w])); });
  }
};

} // namespace craterkit
