#include "bed/SettleAndUnload.h"

#include "bed/BedPreparation.h"
#include "bed/RandomFill.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace craterkit {

namespace {

// Settling (docs/physics.md §7). The loose fill may keep overlaps up to kLooseOverlap (relative
// to the smaller radius) and grows over kLooseGrowthSweeps: the soft DEM law pushes them apart.
constexpr double kLooseOverlap = 0.1;
constexpr double kLooseGrowthSweeps = 30.0;
// The soft settling law: k_N from the lithostatic load of the fill at this overlap fraction
// (proposeStiffness), kSettleStepsPerContact steps per contact (the solver's floor is 10),
// restitution kSettleRestitution (strong damping; a trial at 0.1 with this step did not come to
// rest within the time limit). Overlaps of a few per cent are expected while settling.
constexpr double kSettleOverlap = 0.006;
constexpr double kSettleStepsPerContact = 12.0;
constexpr double kSettleRestitution = 0.3;
constexpr double kSettleOverlapWarning = 0.3;
// Settling runs at least this fraction of the fill's free-fall time.
constexpr double kMinFall = 0.5;
// Unloading: gravity lowered to this fraction over this many steps per grain layer.
constexpr double kUnloadGravity = 1.0 / 64.0;
constexpr double kUnloadStepsPerLayer = 25.0;

// The container the loose fill fills. A settled bed compacts from the loose fraction to ~0.62:
// fill higher so that it still reaches the surface afterwards (the bowl's wall continues as a
// cylinder above its rim).
Container raisedFill(const GranularBedParams& p) {
  Container c = p.container;
  const double depth = c.surfaceHeight - c.floorHeight();
  c.surfaceHeight +=
      (0.64 / std::min(p.packingFraction, 0.6) - 1.0) * depth + 2.0 * p.sizes.largest();
  return c;
}

// Kinetic energy (translation and spin) of the particles whose centre lies below `keepBelow`,
// and their number.
double keptKineticEnergy(const ParticleSet& s, double keepBelow, std::size_t& kept) {
  double energy = 0.0;
  kept = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.position[3 * i + 2] > keepBelow)
      continue;
    ++kept;
    double v2 = 0.0, w2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      v2 += s.velocity[3 * i + k] * s.velocity[3 * i + k];
      w2 += s.angularVelocity[3 * i + k] * s.angularVelocity[3 * i + k];
    }
    energy += 0.5 * s.mass[i] * (v2 + 0.4 * s.radius[i] * s.radius[i] * w2);
  }
  return energy;
}

// The settling run's DEM: strong damping, the bed's friction, no rolling resistance, and a
// soft contact law (docs/physics.md §7). The stiffness carries the weight of the filled
// height at the overlap kSettleOverlap of the lithostatic estimate, not an impact: the step
// grows as 1/sqrt(k_N), and the overlaps it leaves are taken out by unloading (unloadBed).
DemParams settlingParams(const GranularBedParams& p, const Container& filled) {
  const double g = p.settlingGravity;
  const double rmin = p.sizes.smallest();
  DemParams dp;
  dp.walls = containerWalls(filled);
  dp.gravity = Gravity::downward(g);
  dp.contact.restitutionN = dp.contact.restitutionT = kSettleRestitution;
  dp.contact.muS = p.settlingFriction;
  dp.contact.muR = dp.contact.muT = 0.0;
  // The loose fill may overlap by kLooseOverlap; the soft law pushes that apart gently.
  dp.initialOverlapLimit = 2.0 * kLooseOverlap;
  dp.overlapWarning = kSettleOverlapWarning;
  dp.warnStepsPerCollision = kSettleStepsPerContact;
  const StiffnessChoice k =
      chooseStiffnessAndStep({rmin, p.particleDensity, 0.0, kSettleOverlap, g,
                              filled.surfaceHeight - filled.floorHeight(), kSettleStepsPerContact});
  dp.contact.kN = k.kN;
  dp.contact.kT = k.kT;
  dp.dt = k.dt;
  return dp;
}

// Unloads a settled bed: gravity falls exponentially to kUnloadGravity of its value over
// kUnloadStepsPerLayer steps per grain layer of the fill (a few crossings of the bed by a
// contact wave), so the contacts relax quasi-statically to a 64th of their overlap under the
// full weight, as a law 64 times stiffer would leave them, at the soft law's step.
void unloadBed(DemSolver& solver, double g, double height, double meanRadius,
               const ProgressCallback& progress) {
  const long steps =
      std::max(200L, std::lround(kUnloadStepsPerLayer * height / (2.0 * meanRadius)));
  for (long i = 0; i < steps; ++i) {
    if (i % 10 == 0) {
      reportProgress(progress, static_cast<double>(i) / steps);
      solver.setGravity(Gravity::downward(g * std::pow(kUnloadGravity, double(i) / steps)));
    }
    solver.step();
  }
}

// Settles a loose bed under gravity with the SSDEM solver until its kinetic energy has
// decayed, then unloads it (docs/physics.md §7).
ParticleSet settleBed(const ParticleSet& loose, const GranularBedParams& p, const Container& filled,
                      GranularBedReport& report, const ProgressCallback& progress) {
  const double g = p.settlingGravity;
  const double height = filled.surfaceHeight - filled.floorHeight();
  const DemParams dp = settlingParams(p, filled);
  const double fall = std::sqrt(2.0 * height / g);
  DemSolver solver(loose, dp);

  // Only the part of the bed that will be kept must come to rest: spheres in the extra fill
  // above the surface keep rolling on its free slope and are trimmed afterwards.
  const double keepBelow = p.container.surfaceHeight - 2.0 * p.sizes.largest();
  double meanMass = 0.0, meanRadius = 0.0;
  for (std::size_t i = 0; i < loose.size(); ++i) {
    meanMass += loose.mass[i] / loose.size();
    meanRadius += loose.radius[i] / loose.size();
  }
  const double chunk = std::max(0.05 * fall, 100.0 * dp.dt);
  const double limit = 40.0 * fall;
  // The loose fill compacts by falling a fraction of its height: half the free-fall time of
  // the whole fill passes before its energy can have peaked and decayed.
  while (solver.time() < limit) {
    solver.advanceTo(solver.time() + chunk);
    reportProgress(progress, std::min(0.9, solver.time() / (2.0 * fall)));
    std::size_t kept = 0;
    const double energy = keptKineticEnergy(solver.particles(), keepBelow, kept);
    if (solver.time() > kMinFall * fall &&
        energy < p.settledEnergy * kept * meanMass * g * meanRadius) {
      report.settled = true;
      break;
    }
  }
  unloadBed(solver, g, height, meanRadius, subRange(progress, 0.9, 1.0));
  report.settlingTime = solver.time();
  report.settlingSteps = solver.stepCount();
  ParticleSet out = solver.particles();
  std::fill(out.velocity.begin(), out.velocity.end(), 0.0);
  std::fill(out.angularVelocity.begin(), out.angularVelocity.end(), 0.0);
  return out;
}

// Keeps the particles whose top is at or below the surface, renumbering the ids.
ParticleSet trimToSurface(const ParticleSet& s, double surface) {
  ParticleSet out;
  out.reserve(s.size());
  std::int64_t next = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.position[3 * i + 2] + s.radius[i] <= surface + 1e-12 * s.radius[i]) {
      out.add(&s.position[3 * i], s.radius[i], s.density[i], s.material[i], next++);
      out.mass.back() = s.mass[i];
    }
  return out;
}

} // namespace

ParticleSet settledRandomBed(const GranularBedParams& p, GranularBedReport& report,
                             const ProgressCallback& progress) {
  const Container filled = raisedFill(p);
  // A fill that settles keeps small overlaps (the DEM removes them) and grows faster.
  const ParticleSet loose =
      randomFill(p, {filled, 2 * p.maxParticles, kLooseOverlap, kLooseGrowthSweeps}, report,
                 subRange(progress, 0.0, 0.2));
  auto clock = std::chrono::steady_clock::now();
  ParticleSet settled = settleBed(loose, p, filled, report, subRange(progress, 0.2, 0.95));
  endStage(report, "settling", clock);
  ParticleSet trimmed = trimToSurface(settled, p.container.surfaceHeight);
  if (static_cast<std::int64_t>(trimmed.size()) > p.maxParticles)
    checkCap(static_cast<double>(trimmed.size()), p.maxParticles);
  endStage(report, "trim", clock);
  // Unloading leaves contacts overlapping by well under 1 % of a radius; remove those so the
  // bed is stress-free under any gravity and stiffness it is used with later.
  report.finalRelaxationIterations =
      removeOverlaps(trimmed, p, p.container, subRange(progress, 0.95, 1.0));
  endStage(report, "final relaxation", clock);
  return trimmed;
}

} // namespace craterkit
