// DemSolver's neighbour-list rebuild (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012, §2.1):
// the half Verlet list of particle pairs (dem/PairList.h), the walls each particle can reach
// before the next rebuild (dem/ContactTable.h, WallContacts) and the reference positions the
// displacements are measured from. Every pass over the particles or pairs runs on all threads
// (a thread waiting for a serial pass was 5.8 % of a two-thread run's samples,
// benchmarks/JOURNAL.md); contact flags and histories are carried as before, so the result is
// the same for any thread count.
#include "dem/DemSolver.h"

#include <cmath>

namespace craterkit {

void DemSolver::buildNeighbourList() {
  const double* x = state_.position.data();
  const double* r = state_.radius.data();
  pairs_.build(x, r, n_, rmax_, skin_);
  // Walls a particle can reach before the next rebuild (it moves less than skin/2).
  wallNear_.resize(n_);
  refPos_.resize(3 * n_);
  const std::size_t walls = params_.walls.size();
#pragma omp parallel for schedule(static) if (n_ >= kDemParallelMin)
  for (std::size_t i = 0; i < n_; ++i) {
    std::uint64_t mask = 0;
    for (std::size_t w = 0; w < walls; ++w) {
      const Wall& wall = params_.walls[w];
      double nv[3], lever;
      bool near = wall.overlap(&x[3 * i], r[i] + skin_, nv, lever) > 0.0;
      if (!near && wall.type == Wall::Type::Bowl) { // may cross the rim plane before the next build
        const double d = std::hypot(x[3 * i] - wall.point[0], x[3 * i + 1] - wall.point[1],
                                    x[3 * i + 2] - wall.point[2]);
        near = d > wall.radius - (r[i] + skin_);
      }
      if (!near && wall.type == Wall::Type::CylinderAbove) { // may cross the rim plane upwards
        Wall whole = wall;
        whole.type = Wall::Type::Cylinder;
        near = whole.overlap(&x[3 * i], r[i] + skin_, nv, lever) > 0.0;
      }
      if (near)
        mask |= std::uint64_t(1) << w;
    }
    wallNear_[i] = mask;
    for (int k = 0; k < 3; ++k)
      refPos_[3 * i + k] = x[3 * i + k];
  }
  wallContacts_.build(wallNear_);
  ++builds_;
}

} // namespace craterkit
