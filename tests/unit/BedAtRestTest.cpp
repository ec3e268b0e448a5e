// A settled GranularBed is at rest in the DEM stage's own contact law: handed to the DEM solver
// with the stiffness and step the DEMIntegrator's defaults choose, under the gravity it was
// settled at, its surface does not sag and its grains stay still once their contacts have
// re-seated; its grains touch (a frictional packing's coordination number). The loose
// preparation is looser than the RCP bed, as loose as regolith, and carries its weight too.
#include "bed/GranularBed.h"
#include "common/Error.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

using namespace craterkit;

namespace {

// The box bed of the test: monodisperse grains of 2.5 cm in a box 12 x 12 x 8 diameters,
// settled at 9.81 m/s^2 (as a new user would make it).
GranularBedParams boxBed(GranularBedParams::Packing packing) {
  GranularBedParams p;
  p.packing = packing;
  p.container.type = Container::Type::Box;
  p.container.boxSize = {0.6, 0.6, 0.4};
  p.sizes.radius = 0.025;
  p.particleDensity = 2000.0;
  p.settlingGravity = 9.81;
  return p;
}

// O(N^2) oracle: the mean number of grains each grain touches (centre distance at most the sum
// of the radii, to 1e-9 of it), over the grains whose centre lies at least `margin` inside the
// container (away from its walls, floor and surface).
double bruteForceCoordination(const ParticleSet& s, const Container& c, double margin) {
  long long contacts = 0, grains = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!c.inside(&s.position[3 * i], margin))
      continue;
    ++grains;
    for (std::size_t j = 0; j < s.size(); ++j) {
      if (j == i)
        continue;
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k)
        d2 += std::pow(s.position[3 * i + k] - s.position[3 * j + k], 2);
      const double reach = (s.radius[i] + s.radius[j]) * (1.0 + 1e-9);
      contacts += d2 <= reach * reach;
    }
  }
  return grains ? static_cast<double>(contacts) / static_cast<double>(grains) : 0.0;
}

struct StageStart {
  double firstSpeed;   // the fastest grain over the first `settle` seconds, / sqrt(g r)
  double maxSpeed;     // over the rest of the window, / sqrt(g r)
  double surfaceShift; // mean vertical displacement of the surface grains, / r
  double kN, dt;       // the stage's
  long long steps;
};

// The bed handed to the DEM solver as DEMIntegrator hands it (its default contact law,
// MaxExpectedSpeed 1 m/s, MaxOverlap 0.01, 30 steps per collision, the container's walls) under
// the settling gravity, run for `window` seconds: the fastest grain at any step of the first two
// collision times and of the rest of the window, and the mean vertical displacement of the
// grains whose top lies within a diameter of the bed's top.
StageStart runStage(const ParticleSet& bed, const GranularBedParams& p, double window) {
  const double g = p.settlingGravity, r = p.sizes.radius;
  DemSetup setup;
  setup.gravity = Gravity::downward(g);
  setup.walls = DemSetup::Walls::Container;
  setup.container = p.container;
  const DemProblem problem = setUpDem(bed, setup);
  DemSolver solver(problem.particles, problem.params);
  const double settle = 2.0 * solver.collisionTime();
  double top = -INFINITY;
  for (std::size_t i = 0; i < bed.size(); ++i)
    top = std::max(top, bed.position[3 * i + 2] + bed.radius[i]);
  std::unordered_map<std::int64_t, double> surfaceZ; // Id -> height at the start
  for (std::size_t i = 0; i < bed.size(); ++i)
    if (bed.position[3 * i + 2] + bed.radius[i] > top - 2.0 * r)
      surfaceZ[bed.id[i]] = bed.position[3 * i + 2];
  StageStart out{0.0, 0.0, 0.0, problem.params.contact.kN, problem.params.dt, 0};
  while (solver.time() < window) {
    solver.step();
    double& fastest = solver.time() <= settle ? out.firstSpeed : out.maxSpeed;
    fastest = std::max(fastest, solver.diagnostics().maxSpeed);
  }
  out.steps = solver.stepCount();
  const ParticleSet& s = solver.particles();
  double shift = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto it = surfaceZ.find(s.id[i]);
    if (it == surfaceZ.end())
      continue;
    shift += s.position[3 * i + 2] - it->second;
    ++counted;
  }
  out.surfaceShift = counted ? shift / static_cast<double>(counted) / r : NAN;
  out.firstSpeed /= std::sqrt(g * r);
  out.maxSpeed /= std::sqrt(g * r);
  return out;
}

} // namespace

// The bed at rest: over the first 0.05 s of the DEM stage (90 collision times; the bed the
// preparation made before it ended at rest in the stage's law, with no contact, sagged by
// 0.118 r in that time and its grains fell at up to 0.589 sqrt(g r)) the surface moves by less
// than 0.01 r. In the first two collision times the contacts re-seat: the bed hands the stage no
// contact history, so the tangential springs that held it start from zero, and grains near the
// floor move at up to 0.05 sqrt(g r) until they are built again (0.02 measured). After them no
// grain exceeds 0.02 sqrt(g r) (0.00949 measured; a grain the rest left rolling would). Its
// grains touch: coordination number 4-6 away from the walls and the surface.
TEST(BedAtRest, SettledRcpBedCarriesItsWeightInTheStageLaw) {
  const GranularBedParams p = boxBed(GranularBedParams::Packing::RCP);
  GranularBedReport report;
  const ParticleSet bed = generateGranularBed(p, &report);
  ASSERT_GT(bed.size(), 1000u);
  EXPECT_TRUE(report.settled);
  const double z = bruteForceCoordination(bed, p.container, 3.0 * p.sizes.radius);
  EXPECT_NEAR(report.coordinationNumber, z, 1e-12);
  const StageStart stage = runStage(bed, p, 0.05);
  std::printf("RCP box bed: %zu grains, phi %.4f, coordination %.3f; stage k_N %.4g N/m, dt %.4g s,"
              " %lld steps: fastest grain %.3g sqrt(g r) in the first two collision times, %.3g"
              " after, surface shift %.3g r\n",
              bed.size(), report.bulkPackingFraction, z, stage.kN, stage.dt, stage.steps,
              stage.firstSpeed, stage.maxSpeed, stage.surfaceShift);
  EXPECT_NEAR(report.stageStiffness, stage.kN, 1e-9 * stage.kN); // the stage's law
  EXPECT_LT(std::abs(stage.surfaceShift), 0.01);
  EXPECT_LT(stage.firstSpeed, 0.05);
  EXPECT_LT(stage.maxSpeed, 0.02);
  EXPECT_GE(z, 4.0);
  EXPECT_LE(z, 6.0);
}

// The loose bed: poured with the DEM stage's own friction, bulk packing fraction 0.55-0.59 and
// at least 0.02 below the RCP bed of the same grains; its coordination number is reported. In
// the DEM stage its surface moves by less than 0.01 r over the first 0.05 s. (Its grains held
// by rolling resistance re-seat when the stage starts without the contact history: it is not
// asserted to be as still as the RCP bed.)
TEST(BedAtRest, LooseBedIsLooserAndCarriesItsWeight) {
  GranularBedParams p = boxBed(GranularBedParams::Packing::Loose);
  GranularBedReport loose, dense;
  const ParticleSet bed = generateGranularBed(p, &loose);
  p.packing = GranularBedParams::Packing::RCP;
  generateGranularBed(p, &dense);
  p.packing = GranularBedParams::Packing::Loose;
  EXPECT_TRUE(loose.settled);
  const double z = bruteForceCoordination(bed, p.container, 3.0 * p.sizes.radius);
  EXPECT_NEAR(loose.coordinationNumber, z, 1e-12);
  const StageStart stage = runStage(bed, p, 0.05);
  std::printf("Loose box bed: %zu grains, phi %.4f (RCP %.4f), coordination %.3f; fastest grain "
              "%.3g sqrt(g r) in the first two collision times, %.3g after, surface shift %.3g r\n",
              bed.size(), loose.bulkPackingFraction, dense.bulkPackingFraction, z, stage.firstSpeed,
              stage.maxSpeed, stage.surfaceShift);
  EXPECT_GE(loose.bulkPackingFraction, 0.55);
  EXPECT_LE(loose.bulkPackingFraction, 0.59);
  EXPECT_LT(loose.bulkPackingFraction, dense.bulkPackingFraction - 0.02);
  EXPECT_GE(z, 3.5);
  EXPECT_LE(z, 6.0);
  EXPECT_LT(std::abs(stage.surfaceShift), 0.01);
}
