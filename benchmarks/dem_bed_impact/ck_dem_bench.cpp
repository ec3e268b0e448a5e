// CraterKit side of the DEM bed-impact benchmark (see run.py beside this file).
//   ck_dem_bench make-bed FILE PARTICLES   settle a monodisperse RCP bed in a box, write it
//   ck_dem_bench run FILE STEPS            add the impactor, run STEPS steps, print timings
//   ck_dem_bench lammps-deck FILE STEPS DIR
//                                          write the same problem (particles, contact law,
//                                          walls, gravity, time step, STEPS steps) as the LAMMPS
//                                          deck CraterKit's writer makes (dem/LammpsDeck.h:
//                                          DIR/in.craterkit, DIR/data.craterkit), print its
//                                          parameters
// All print one JSON object on the last line; run's ends with a hash of the final state.
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"
#include "dem/Impactor.h"
#include "dem/LammpsDeck.h"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

using namespace craterkit;

namespace {
constexpr double kRadius = 0.05, kDensity = 2000.0, kGravity = 9.81, kSpeed = 1.0;

struct Box {
  double side, depth;
};

// FNV-1a over the bytes of the final positions, velocities and spins: two runs with equal
// hashes ended in bit-identical states (e.g. before and after a change meant to keep them).
std::uint64_t stateHash(const ParticleSet& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const std::vector<double>* a : {&s.position, &s.velocity, &s.angularVelocity})
    for (const double v : *a) {
      unsigned char bytes[sizeof v];
      std::memcpy(bytes, &v, sizeof v);
      for (const unsigned char b : bytes) {
        h ^= b;
        h *= 1099511628211ULL;
      }
    }
  return h;
}

Box boxFor(double particles) {
  // N ≈ 0.62 L * L * (L/2) / (4/3 π r^3)
  const double side = std::cbrt(particles * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3) / (0.62 * 0.5));
  return {side, 0.5 * side};
}

// The benchmark problem: the settled bed of FILE, the impactor, the contact law, walls, gravity
// and time step. `run` integrates it, `lammps-deck` hands exactly this to the LAMMPS deck writer.
struct Problem {
  Box box{};
  ParticleSet particles;
  ImpactorParams impactor;
  StiffnessChoice stiffness{};
  DemParams dem;
};

Problem loadProblem(const std::string& file) {
  Problem pr;
  std::ifstream in(file);
  in >> pr.box.side >> pr.box.depth;
  ParticleSet& s = pr.particles;
  double x[3];
  while (in >> x[0] >> x[1] >> x[2])
    s.add(x, kRadius, kDensity, 0, static_cast<std::int64_t>(s.size()));
  pr.impactor.radius = 2.0 * kRadius;
  pr.impactor.density = kDensity;
  pr.impactor.speed = kSpeed;
  addImpactor(s, pr.impactor);

  DemParams& p = pr.dem;
  Container c;
  c.type = Container::Type::Box;
  c.boxSize = {pr.box.side, pr.box.side, pr.box.depth};
  p.walls = containerWalls(c);
  p.gravity = Gravity::downward(kGravity);
  pr.stiffness =
      chooseStiffnessAndStep({kRadius, kDensity, kSpeed, 0.01, kGravity, pr.box.depth, 30.0});
  p.contact.kN = pr.stiffness.kN;
  p.dt = pr.stiffness.dt;
  // pkdgrav "moderate" regolith coefficients (docs/physics.md §1.7); run.py's LIGGGHTS deck
  // repeats those it uses (MU_S, MU_R, BETA there; LIGGGHTS has no twisting model).
  p.contact.restitutionN = p.contact.restitutionT = 0.55;
  p.contact.muS = 0.6;
  p.contact.muR = 1.05;
  p.contact.muT = 1.3;
  p.contact.beta = 0.5;
  return pr;
}

// The problem's parameters as JSON members (no braces), for run.py's LIGGGHTS deck.
std::string problemJson(const Problem& pr) {
  const double m = kDensity * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  char buf[1024];
  std::snprintf(
      buf, sizeof buf,
      "\"particles\": %zu, \"kn\": %.17g, \"dt\": %.17g, \"mass\": %.17g, "
      "\"radius\": %.17g, \"impactor_radius\": %.17g, \"speed\": %.17g, "
      "\"side\": %.17g, \"depth\": %.17g, \"damping_factor_n\": %.17g, "
      "\"damping_factor_t\": %.17g",
      pr.particles.size(), pr.stiffness.kN, pr.dem.dt, m, kRadius, pr.impactor.radius, kSpeed,
      pr.box.side, pr.box.depth,
      clippedDampingFactor(NormalLawKind::LinearSpringDashpot, pr.dem.contact.restitutionN),
      dashpotFactor(pr.dem.contact.restitutionT));
  return buf;
}
} // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: ck_dem_bench make-bed FILE PARTICLES | run FILE STEPS | "
                 "lammps-deck FILE STEPS DIR\n";
    return 2;
  }
  const std::string mode = argv[1], file = argv[2];
  if (mode == "make-bed") {
    const Box box = boxFor(std::atof(argv[3]));
    GranularBedParams p;
    p.container.type = Container::Type::Box;
    p.container.boxSize = {box.side, box.side, box.depth};
    p.sizes.radius = kRadius;
    p.particleDensity = kDensity;
    GranularBedReport report;
    int last = -1;
    const ParticleSet bed = generateGranularBed(p, &report, [&](double f) {
      if (static_cast<int>(f * 20) != last) {
        last = static_cast<int>(f * 20);
        std::fprintf(stderr, "  settling the bed: %3.0f %%\n", 100 * f);
      }
      return true;
    });
    std::ofstream out(file);
    out.precision(17);
    out << box.side << " " << box.depth << "\n";
    for (std::size_t i = 0; i < bed.size(); ++i)
      out << bed.position[3 * i] << " " << bed.position[3 * i + 1] << " " << bed.position[3 * i + 2]
          << "\n";
    std::printf(
        "{\"particles\": %zu, \"bulk_packing_fraction\": %.4f, \"side\": %.6f, \"depth\": %.6f}\n",
        bed.size(), report.bulkPackingFraction, box.side, box.depth);
    return 0;
  }
  if (mode == "lammps-deck") {
    if (argc < 5) {
      std::cerr << "usage: ck_dem_bench lammps-deck FILE STEPS DIR\n";
      return 2;
    }
    const long steps = std::atol(argv[3]);
    const Problem pr = loadProblem(file);
    LammpsDeckParams deck;
    deck.dem = pr.dem;
    deck.outputTimes = {static_cast<double>(steps) * pr.dem.dt}; // one run of STEPS steps
    writeLammpsDeck(argv[4], pr.particles, deck);
    std::printf("{\"input\": \"%s\", \"data\": \"%s\", \"steps\": %ld, %s}\n",
                deck.inputFile.c_str(), deck.dataFile.c_str(), steps, problemJson(pr).c_str());
    return 0;
  }
  if (mode != "run")
    return 2;
  const long steps = std::atol(argv[3]);
  Problem pr = loadProblem(file);
  ParticleSet& s = pr.particles;
  DemSolver solver(s, pr.dem);
  const auto t0 = std::chrono::steady_clock::now();
  solver.advanceSteps(steps); // the bits of step() called STEPS times
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"code\": \"CraterKit\", \"threads\": %d, \"steps\": %ld, \"seconds\": %.4f, "
              "%s, \"builds\": %zu, \"contacts\": %zu, \"state_hash\": \"%016llx\"}\n",
              omp_get_max_threads(), steps, seconds, problemJson(pr).c_str(),
              solver.neighbourBuilds(), solver.diagnostics().contacts,
              static_cast<unsigned long long>(stateHash(solver.particles())));
  return 0;
}
