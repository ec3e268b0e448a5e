#include "bed/SettleAndUnload.h"

#include "bed/BedPreparation.h"
#include "bed/RandomFill.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

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
// The packing fraction a settled bed reaches at most (the raised fill's height is set for it).
constexpr double kDenseSettled = 0.64;
constexpr double kLooseSettled = 0.60;
// Unloading the settled bed, from rest: gravity lowered to kUnloadGravity over
// kUnloadStepsPerLayer steps per grain layer (lower in one go, the bed's elastic energy is
// released against a weight too small to hold it together and throws it apart).
constexpr double kUnloadGravity = 0.25;
constexpr double kUnloadStepsPerLayer = 25.0;
// Stiffening to the DEM stage's k_N: at most kStiffening-fold per run; each run starts from rest
// under full gravity, lowers gravity by the factor the next run stiffens the law over
// kStiffeningCollisions collision times and holds it kHoldCollisions, so that the stiffer law,
// under full gravity, starts with the contact forces this one ends with.
constexpr double kStiffening = 4.0;
constexpr double kStiffeningCollisions = 20.0;
constexpr double kHoldCollisions = 10.0;
// The stiffening runs and the rest: restitution kRestRestitution and kRestStepsPerCollision
// steps per collision (numerical aids: neither changes where the bed comes to rest). The rest in
// the stage's law runs in chunks of kRestChunk collision times, at least kRestMin and at most
// kRestMax of them, until no grain is faster than kRestSpeed sqrt(g r).
constexpr double kRestRestitution = 0.3;
constexpr double kRestStepsPerCollision = 12.0;
constexpr double kRestChunk = 10.0;
constexpr double kRestMin = 30.0;
constexpr double kRestMax = 300.0;
constexpr double kRestSpeed = 5e-3;

// The container the loose fill fills. A settled bed compacts from the loose fraction to ~0.62
// (RCP) or ~0.58 (Loose): fill higher so that it still reaches the surface afterwards (the bowl's
// wall continues as a cylinder above its rim).
Container raisedFill(const GranularBedParams& p) {
  Container c = p.container;
  const double depth = c.surfaceHeight - c.floorHeight();
  const double settled =
      p.packing == GranularBedParams::Packing::Loose ? kLooseSettled : kDenseSettled;
  c.surfaceHeight += std::max(0.0, settled / std::min(p.packingFraction, 0.6) - 1.0) * depth +
                     2.0 * p.sizes.largest();
  return c;
}

// The DEM stage's run of `bed` as DEMIntegrator sets it up with its default contact law and the
// stage* fields: the container's walls, gravity settlingGravity, k_N and step by setUpDem.
DemParams stageParams(const ParticleSet& bed, const GranularBedParams& p) {
  DemSetup setup;
  setup.normalStiffness = p.stageNormalStiffness;
  setup.maxExpectedSpeed = p.stageMaxExpectedSpeed;
  setup.maxOverlap = p.stageMaxOverlap;
  setup.gravity = Gravity::downward(p.settlingGravity);
  setup.walls = DemSetup::Walls::Container;
  setup.container = p.container;
  return setUpDem(bed, setup).params;
}

// The stage's k_N for the bed `bed` will be once trimmed to the surface: as stageParams, for a
// bed as high as the container's fill.
double trimmedStageStiffness(const ParticleSet& bed, const GranularBedParams& p) {
  const BedExtent e = scanBed(bed);
  StiffnessInput in{e.smallestRadius,        e.smallestDensity,
                    p.stageMaxExpectedSpeed, p.stageMaxOverlap,
                    p.settlingGravity,       p.container.surfaceHeight - p.container.floorHeight()};
  in.normalStiffness = p.stageNormalStiffness;
  return chooseStiffnessAndStep(in).kN;
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

// The particles at rest: velocities and spins zeroed.
ParticleSet atRest(ParticleSet s) {
  std::fill(s.velocity.begin(), s.velocity.end(), 0.0);
  std::fill(s.angularVelocity.begin(), s.angularVelocity.end(), 0.0);
  return s;
}

// The settling run's DEM: strong damping, the bed's friction (RCP: SettlingFriction and no
// rolling resistance; Loose: poured with the DEM stage's default sliding, rolling and twisting
// friction, high enough to hold a 30 degree slope), and a soft contact law (docs/physics.md §7).
// The stiffness carries the weight of the filled height at the overlap kSettleOverlap of the
// lithostatic estimate, not an impact: the step grows as 1/sqrt(k_N). The overlaps it leaves shrink
// to the DEM stage's by unloading and stiffening.
DemParams settlingParams(const GranularBedParams& p, const Container& filled) {
  const double g = p.settlingGravity;
  const double rmin = p.sizes.smallest();
  DemParams dp;
  dp.walls = containerWalls(filled);
  dp.gravity = Gravity::downward(g);
  dp.contact.restitutionN = dp.contact.restitutionT = kSettleRestitution;
  if (p.packing != GranularBedParams::Packing::Loose) { // Loose keeps the stage's defaults
    dp.contact.muS = p.settlingFriction;
    dp.contact.muR = dp.contact.muT = 0.0;
  }
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

// Settles a loose bed under gravity with the SSDEM solver until its kinetic energy has
// decayed, then unloads it from rest to kUnloadGravity (docs/physics.md §7). Returns it at rest.
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
  // Unload from rest: the settled bed still moves, slowly against its weight but not against
  // the unloaded bed's. Gravity falls exponentially over kUnloadStepsPerLayer steps per grain
  // layer of the fill (a few crossings of the bed by a contact wave).
  DemSolver unloading(atRest(solver.particles()), dp);
  const long steps =
      std::max(200L, std::lround(kUnloadStepsPerLayer * height / (2.0 * meanRadius)));
  for (long i = 0; i <= steps; ++i) {
    if (i % 10 == 0 || i == steps) {
      reportProgress(progress, 0.9 + 0.1 * static_cast<double>(i) / steps);
      unloading.setGravity(Gravity::downward(g * std::pow(kUnloadGravity, double(i) / steps)));
    }
    if (i < steps)
      unloading.step();
  }
  report.settlingTime = solver.time() + unloading.time();
  report.settlingSteps = solver.stepCount() + unloading.stepCount();
  return atRest(unloading.particles());
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

// The contact law of the stiffening runs and the rest: `law`'s coefficients with normal
// stiffness k (tangential 2/7 of it), strong damping, kRestStepsPerCollision steps per
// collision of the lightest particle, and the container's walls.
DemParams restParams(DemParams law, double k, double lightest, const Container& container) {
  law.walls = containerWalls(container);
  law.contact.kN = k;
  law.contact.kT = -1.0;
  law.contact.restitutionN = law.contact.restitutionT = kRestRestitution;
  law.dt = pairCollisionTime(lightest, k) / kRestStepsPerCollision;
  law.warnStepsPerCollision = kRestStepsPerCollision;
  law.overlapWarning = std::max(law.overlapWarning, kSettleOverlapWarning);
  law.initialOverlapLimit = 2.0 * kLooseOverlap;
  return law;
}

// Raises k_N of the settling law from `stiffness` (the law whose overlaps under full gravity the
// bed has) to the stage's `stageStiffness`, keeping the contact forces (kStiffening).
ParticleSet stiffen(ParticleSet s, double stiffness, double stageStiffness,
                    const GranularBedParams& p, const Container& filled, GranularBedReport& report,
                    const ProgressCallback& progress) {
  const double g = p.settlingGravity;
  const double lightest = *std::min_element(s.mass.begin(), s.mass.end());
  const int runs = static_cast<int>(std::max(
      0.0, std::ceil(std::log(stageStiffness / stiffness) / std::log(kStiffening) - 1e-9)));
  for (int run = 0; run < runs; ++run) {
    const double next = std::min(stiffness * kStiffening, stageStiffness);
    DemSolver solver(s, restParams(settlingParams(p, filled), stiffness, lightest, filled));
    const long long ramp = std::llround(kStiffeningCollisions * kRestStepsPerCollision);
    for (long long i = 1; i <= ramp; ++i) {
      solver.setGravity(Gravity::downward(g * std::pow(stiffness / next, double(i) / ramp)));
      solver.step();
    }
    solver.advanceSteps(std::llround(kHoldCollisions * kRestStepsPerCollision));
    reportProgress(progress, static_cast<double>(run + 1) / runs);
    report.settlingTime += solver.time();
    report.settlingSteps += solver.stepCount();
    s = atRest(solver.particles());
    stiffness = next;
  }
  return s;
}

// Brings the bed, whose overlaps are the stage law's under full gravity, to rest under full
// gravity in the DEM stage's own contact law (stageParams; strong damping and a longer step are
// numerical aids), so that its overlaps carry its weight as the stage's contacts will. Returns
// the bed at rest, ordered by Id.
ParticleSet restInStageLaw(const ParticleSet& bed, const DemParams& stage,
                           const GranularBedParams& p, GranularBedReport& report,
                           const ProgressCallback& progress) {
  const double lightest = *std::min_element(bed.mass.begin(), bed.mass.end());
  double meanRadius = 0.0;
  for (double r : bed.radius)
    meanRadius += r / static_cast<double>(bed.size());
  const double speedScale = std::sqrt(p.settlingGravity * meanRadius);
  DemSolver solver(bed, restParams(stage, stage.contact.kN, lightest, p.container));
  const long long chunk = std::llround(kRestChunk * kRestStepsPerCollision);
  const long long minSteps = std::llround(kRestMin * kRestStepsPerCollision);
  const long long maxSteps = std::llround(kRestMax * kRestStepsPerCollision);
  double speed = 0.0;
  while (solver.stepCount() < maxSteps) {
    solver.advanceSteps(std::min(chunk, maxSteps - solver.stepCount()));
    reportProgress(progress, static_cast<double>(solver.stepCount()) / maxSteps);
    speed = solver.diagnostics().maxSpeed;
    if (solver.stepCount() >= minSteps && speed < kRestSpeed * speedScale) {
      report.atRest = true;
      break;
    }
  }
  report.restTime = solver.time();
  report.restSteps = solver.stepCount();
  report.restSpeed = speed / speedScale;
  // The solver orders the particles along a curve; give them back in the order of their ids
  // (0..n-1 after trimming).
  const ParticleSet& s = solver.particles();
  std::vector<std::size_t> byId(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    byId[static_cast<std::size_t>(s.id[i])] = i;
  ParticleSet out;
  out.reserve(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const std::size_t i = byId[j];
    out.add(&s.position[3 * i], s.radius[i], s.density[i], s.material[i], s.id[i]);
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
  const ParticleSet settled = settleBed(loose, p, filled, report, subRange(progress, 0.2, 0.75));
  endStage(report, "settling", clock);
  // The unloaded bed has the overlaps of a law 1 / kUnloadGravity times stiffer than the soft
  // one under full gravity; stiffen it to the stage's law (the whole fill: the overlaps that
  // stiffening takes out lift the bed a little), trim it, and bring it to rest in that law.
  const ParticleSet stiff =
      stiffen(settled, settlingParams(p, filled).contact.kN / kUnloadGravity,
              trimmedStageStiffness(settled, p), p, filled, report, subRange(progress, 0.75, 0.85));
  endStage(report, "stiffening", clock);
  const ParticleSet trimmed = trimToSurface(stiff, p.container.surfaceHeight);
  if (static_cast<std::int64_t>(trimmed.size()) > p.maxParticles)
    checkCap(static_cast<double>(trimmed.size()), p.maxParticles);
  endStage(report, "trim", clock);
  if (trimmed.size() == 0)
    return trimmed;
  const DemParams stage = stageParams(trimmed, p);
  report.stageStiffness = stage.contact.kN;
  report.stageTimeStep = stage.dt;
  ParticleSet rested = restInStageLaw(trimmed, stage, p, report, subRange(progress, 0.85, 1.0));
  endStage(report, "rest", clock);
  return rested;
}

} // namespace craterkit
