// Bed settling benchmark (see run.py beside this file): builds a settled RCP GranularBed and
// prints the wall time of each stage, the packing, the coordination number, the largest overlap
// and whether it is at rest.
//   ck_bed_bench box PARTICLES [REST_STEPS]   the DEM bed-impact benchmark's box bed (r = 5 cm)
//   ck_bed_bench bowl PARTICLES [REST_STEPS]  the SCI example's bowl bed (bowl 1.05 m, g = 1000)
// At rest: the bed is released under the impact's gravity, stiffness and contact law (the
// DEMIntegrator's defaults, k_N and Δt for a Froude-scaled 1 m/s at 5 cm and 9.81 m/s², as
// in the DEM bed-impact benchmark) for REST_STEPS steps (default 500); the largest
// displacement and the kinetic energy per grain are printed in units of r and m g r.
// Prints one JSON object on the last line.
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

using namespace craterkit;

namespace {

GranularBedParams boxBed(double particles) {
  // As benchmarks/dem_bed_impact/ck_dem_bench.cpp: N ≈ 0.62 L * L * (L/2) / (4/3 π r^3).
  constexpr double r = 0.05;
  const double side = std::cbrt(particles * 4.0 / 3.0 * M_PI * r * r * r / (0.62 * 0.5));
  GranularBedParams p;
  p.container.type = Container::Type::Box;
  p.container.boxSize = {side, side, 0.5 * side};
  p.sizes.radius = r;
  p.particleDensity = 2000.0;
  return p;
}

GranularBedParams bowlBed(double particles) {
  // As examples/sci_crater.py at its default gravity (D = 1 m): bowl of radius 1.05 D,
  // grain radius R (0.6 / 2N)^(1/3), grain density 1190 / 0.6 kg/m^3.
  GranularBedParams p;
  p.container.type = Container::Type::Bowl;
  p.container.bowlRadius = 1.05;
  p.container.surfaceHeight = 0.0;
  p.sizes.radius = 1.05 * std::cbrt(0.6 / (2.0 * particles));
  p.particleDensity = 1190.0 / 0.6;
  p.settlingGravity = 1000.0;
  // The bed rests in the law restCheck releases it in (1 m/s Froude-scaled).
  p.stageMaxExpectedSpeed = std::sqrt(p.settlingGravity * p.sizes.radius / (9.81 * 0.05));
  p.maxParticles = std::max<std::int64_t>(10 * static_cast<std::int64_t>(particles), 100000);
  return p;
}

struct Rest {
  double maxDisplacement, kineticEnergy; // / r, per grain / (m g r)
};

Rest restCheck(const ParticleSet& bed, const GranularBedParams& p, long steps) {
  const double r = p.sizes.radius, g = p.settlingGravity;
  DemSetup setup;
  setup.gravity = Gravity::downward(g);
  setup.maxExpectedSpeed = std::sqrt(g * r / (9.81 * 0.05)); // 1 m/s at r = 5 cm, 9.81 m/s^2
  setup.walls = DemSetup::Walls::Container;
  setup.container = p.container;
  const DemProblem problem = setUpDem(bed, setup);
  DemSolver solver(problem.particles, problem.params);
  for (long i = 0; i < steps; ++i)
    solver.step();
  const ParticleSet& s = solver.particles();
  // The solver reorders particles; match them by Id (the bed's ids are 0..n-1).
  double worst = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::size_t j = static_cast<std::size_t>(s.id[i]);
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
      d2 += std::pow(s.position[3 * i + k] - bed.position[3 * j + k], 2);
    worst = std::max(worst, std::sqrt(d2));
  }
  const DemDiagnostics d = solver.diagnostics();
  const double m = bed.mass[0];
  return {worst / r, (d.kineticEnergy + d.rotationalEnergy) / s.size() / (m * g * r)};
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 3 || (std::string(argv[1]) != "box" && std::string(argv[1]) != "bowl")) {
    std::cerr << "usage: ck_bed_bench box|bowl PARTICLES [REST_STEPS]\n";
    return 2;
  }
  const std::string kind = argv[1];
  const double n = std::atof(argv[2]);
  const long restSteps = argc > 3 ? std::atol(argv[3]) : 500;
  const GranularBedParams p = kind == "box" ? boxBed(n) : bowlBed(n);
  GranularBedReport report;
  const auto t0 = std::chrono::steady_clock::now();
  const ParticleSet bed = generateGranularBed(p, &report);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double gap = smallestGap(bed) / p.sizes.radius;
  const Rest rest = restSteps > 0 ? restCheck(bed, p, restSteps) : Rest{NAN, NAN};
  std::printf("{\"container\": \"%s\", \"threads\": %d, \"particles\": %zu, \"seconds\": %.2f, ",
              kind.c_str(), omp_get_max_threads(), bed.size(), seconds);
  for (const auto& [name, s] : report.stageSeconds)
    std::printf("\"%s_s\": %.2f, ", name.c_str(), s);
  std::printf(
      "\"relaxation_sweeps\": %d, \"settling_steps\": %lld, \"settled\": %s, "
      "\"bed_rest_steps\": %lld, \"bed_at_rest\": %s, \"packing_fraction\": %.4f, "
      "\"coordination_number\": %.3f, \"top_above_surface_r\": %.3g, \"smallest_gap_r\": %.3g, "
      "\"rest_steps\": %ld, "
      "\"rest_max_displacement_r\": %.3g, \"rest_kinetic_energy_mgr\": %.3g}\n",
      report.relaxationIterations, report.settlingSteps, report.settled ? "true" : "false",
      report.restSteps, report.atRest ? "true" : "false", report.bulkPackingFraction,
      report.coordinationNumber, (report.topHeight - p.container.surfaceHeight) / p.sizes.radius,
      gap, restSteps, rest.maxDisplacement, rest.kineticEnergy);
  return 0;
}
