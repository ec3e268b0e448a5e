#include "bed/LatticeBed.h"

#include "bed/BedPreparation.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {

// Lattice sites may touch a wall to this relative tolerance.
constexpr double kWallTolerance = 1e-12;

} // namespace

ParticleSet hcpLatticeBed(const GranularBedParams& p, const ProgressCallback& progress) {
  const Container& c = p.container;
  const double r = p.sizes.radius;
  const double a = 2.0 * r;
  const double dy = a * std::sqrt(3.0) / 2.0;
  const double dz = a * std::sqrt(2.0 / 3.0);
  double lo[3], hi[3];
  c.bounds(r, lo, hi);
  // Box beds stand on the floor; bowl beds hang from the surface so it stays flat.
  const bool fromFloor = c.type == Container::Type::Box;
  const double z0 = fromFloor ? c.floorHeight() + r : c.surfaceHeight - r;
  const long layers = static_cast<long>(std::floor((hi[2] - lo[2]) / dz + 1e-9)) + 1;
  const long imax = static_cast<long>(std::ceil(std::max(-lo[0], hi[0]) / a)) + 1;
  const long jmax = static_cast<long>(std::ceil(std::max(-lo[1], hi[1]) / dy)) + 1;
  const double margin = r * (1.0 - kWallTolerance);

  ParticleSet out;
  out.reserve(static_cast<std::size_t>(expectedParticles(p) * 1.05) + 16);
  std::int64_t next = 0;
  for (long k = 0; k < layers; ++k) {
    reportProgress(progress, static_cast<double>(k) / layers);
    const double z = fromFloor ? z0 + k * dz : z0 - k * dz;
    const bool layerB = (k % 2) == 1;
    const double ox = layerB ? r : 0.0, oy = layerB ? r / std::sqrt(3.0) : 0.0;
    for (long j = -jmax; j <= jmax; ++j)
      for (long i = -imax; i <= imax; ++i) {
        const double x[3] = {i * a + ((j % 2) != 0 ? r : 0.0) + ox, j * dy + oy, z};
        if (!c.inside(x, margin))
          continue;
        if (next >= p.maxParticles)
          checkCap(static_cast<double>(next) + 1.0, p.maxParticles);
        out.add(x, r, p.particleDensity, p.material, next++);
      }
  }
  return out;
}

} // namespace craterkit
