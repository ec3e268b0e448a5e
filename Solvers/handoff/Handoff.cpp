// The hand-off's steps in order (Handoff.h): split, alpha shape and carving, velocity map,
// ejecta, momentum correction. Each step is a file of its own in this folder.
#include "handoff/Handoff.h"

#include "common/Error.h"
#include "handoff/AlphaShapeCarve.h"
#include "handoff/Ejecta.h"
#include "handoff/MomentumCorrection.h"
#include "handoff/Split.h"
#include "handoff/VelocityMap.h"

#include <chrono>
#include <cmath>
#include <string>

namespace craterkit {

namespace {
double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}
} // namespace

bool TargetRegion::contains(const double x[3]) const {
  const double z = x[2] - surfaceHeight;
  switch (shape) {
  case Shape::Everywhere:
    return true;
  case Shape::Hemisphere:
    return z <= 0.0 && x[0] * x[0] + x[1] * x[1] + z * z <= radius * radius;
  case Shape::HalfSpace:
    return z <= 0.0 && z >= -radius && std::abs(x[0]) <= radius && std::abs(x[1]) <= radius;
  }
  return false;
}

void HandoffParams::validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok)
      throw InputError(std::string("ImpactHandoff: ") + what);
  };
  require(ejectaSpeedLimit > 0.0 && std::isfinite(ejectaSpeedLimit),
          "EjectaSpeedLimit must be a positive speed in m/s");
  require(alphaRadius >= 0.0 && std::isfinite(alphaRadius),
          "Alpha must not be negative (0: automatic)");
  require(minNeighbours >= 1, "the neighbour count must be at least 1");
  require(ejectaDensity >= 0.0 && std::isfinite(ejectaDensity),
          "the ejecta grain density must not be negative (0: the bed's)");
  require(gravity >= 0.0 && std::isfinite(gravity),
          "the gravity for ballistic landing must be finite and not negative");
  require(groupReach >= 0.0 && std::isfinite(groupReach),
          "the reach for merging light ejecta groups must not be negative");
}

HandoffResult handoff(const SphSnapshot& sph, const ParticleSet& bed, const TargetRegion& region,
                      const HandoffParams& params) {
  params.validate();
  checkInputs(sph, bed);
  HandoffResult out;

  // 1. Split.
  auto t0 = std::chrono::steady_clock::now();
  const SplitSets sets = splitBySpeed(sph, params.ejectaSpeedLimit);
  const std::vector<std::size_t>& compact = sets.compact;
  out.compactCount = compact.size();
  out.ejectaCount = sets.ejecta.size();
  out.sphCompact = sphTotals(sph, compact);
  out.sphEjecta = sphTotals(sph, sets.ejecta);
  out.seconds.split = seconds(t0);

  // 2. Delaunay triangulation and alpha shape of the compact material; the curtain above it.
  t0 = std::chrono::steady_clock::now();
  AlphaShapeCarve shape(sph, compact, params.alphaRadius);
  const double alphaRadius = out.alphaRadius = shape.alphaRadius();
  const CurtainTest inCurtain{params.curtainAsParticles, region.surfaceHeight, alphaRadius};
  const std::vector<std::size_t> curtain = curtainOf(sph, compact, inCurtain);
  out.curtainCount = curtain.size();
  out.sphCurtain = sphTotals(sph, curtain);
  shape.buildShape(out.shapeVolume, out.surfacePoints, out.triangles);
  out.seconds.alphaShape = seconds(t0);

  // 3. Carve.
  t0 = std::chrono::steady_clock::now();
  const CompactCloud cloud(sph, compact, alphaRadius);
  Carving carving = shape.carve(bed, region, cloud);
  out.bedRemoved = carving.removed;
  out.seconds.carve = seconds(t0);
  const std::string uncovered = coverageWarning(sph, compact, bed, inCurtain, alphaRadius);
  if (!uncovered.empty())
    out.warnings.push_back(uncovered);
  ParticleSet& p = out.particles;
  p.reserve(carving.keep.size() + sets.ejecta.size());
  for (std::size_t i : carving.keep) {
    const std::size_t k = 3 * i;
    p.position.insert(p.position.end(), &bed.position[k], &bed.position[k] + 3);
    p.velocity.insert(p.velocity.end(), &bed.velocity[k], &bed.velocity[k] + 3);
    p.angularVelocity.insert(p.angularVelocity.end(), &bed.angularVelocity[k],
                             &bed.angularVelocity[k] + 3);
    p.radius.push_back(bed.radius[i]);
    p.mass.push_back(bed.mass[i]);
    p.density.push_back(bed.density[i]);
    p.material.push_back(bed.material[i]);
    p.id.push_back(bed.id[i]);
  }
  out.origin.assign(carving.keep.size(), 0);
  std::vector<std::size_t>& mapped = carving.mapped;
  out.bedMapped = mapped.size();

  // 4. Map velocity and spin from the compact SPH particles.
  t0 = std::chrono::steady_clock::now();
  mapVelocities(sph, compact, cloud, params.minNeighbours, mapped, p);
  out.seconds.map = seconds(t0);

  // 5. Ejecta (and the curtain) as particles.
  t0 = std::chrono::steady_clock::now();
  addEjecta(sph, sets.ejecta, curtain, bed, region, params, mapped, out);
  out.seconds.ejecta = seconds(t0);

  // 6. The mapped set carries the compact SPH material's momentum and angular momentum below
  // the curtain exactly.
  t0 = std::chrono::steady_clock::now();
  correctMomentum(p, mapped, mappedTarget(out.sphCompact, out.sphCurtain), out.demBefore,
                  out.demMapped, out.warnings);
  out.seconds.correct = seconds(t0);
  return out;
}

} // namespace craterkit
