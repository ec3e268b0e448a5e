// Rates of CraterKit's DEM and of LAMMPS on the same deck (docs/scaling.md).
//   ck_lammps_rate DIR PARTICLES STEPS
// Builds an HCP box bed of about PARTICLES grains (a lattice: no settling) with an impactor,
// writes the LAMMPS deck of STEPS steps into DIR (run it with scripts/run-lammps DIR RANKS and
// read LAMMPS' "Loop time"), runs the same STEPS in CraterKit and prints its particle-steps/s
// (set-up excluded, OMP_NUM_THREADS threads).
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"
#include "dem/Impactor.h"
#include "dem/LammpsDeck.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace craterkit;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: ck_lammps_rate DIR PARTICLES STEPS\n");
    return 2;
  }
  const double n = std::atof(argv[2]);
  const long steps = std::atol(argv[3]);
  const double r = 0.05, side = std::cbrt(n * 4.0 / 3.0 * M_PI * r * r * r / (0.74 * 0.5));
  GranularBedParams bed;
  bed.packing = GranularBedParams::Packing::HCP;
  bed.container.type = Container::Type::Box;
  bed.container.boxSize = {side, side, 0.5 * side};
  bed.sizes.radius = r;
  ParticleSet s = generateGranularBed(bed);
  ImpactorParams imp;
  imp.radius = 2.0 * r;
  imp.speed = 1.0;
  addImpactor(s, imp);
  LammpsDeckParams deck;
  deck.dem.walls = containerWalls(bed.container);
  deck.dem.contact.kN = 1e6;
  deck.dem.dt = M_PI * std::sqrt(0.5 * s.mass[0] / 1e6) / 30.0;
  deck.outputTimes = {static_cast<double>(steps) * deck.dem.dt};
  writeLammpsDeck(argv[1], s, deck);
  DemSolver solver(s, deck.dem);
  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i)
    solver.step();
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"particles\": %zu, \"steps\": %ld, \"seconds\": %.3f, "
              "\"particle_steps_per_s\": %.4g}\n",
              s.size(), steps, sec,
              static_cast<double>(s.size()) * static_cast<double>(steps) / sec);
  return 0;
}
