// CraterKit side of the DEM bed-impact benchmark (see run.py beside this file).
//   ck_dem_bench make-bed FILE PARTICLES   settle a monodisperse RCP bed in a box, write it
//   ck_dem_bench run FILE STEPS            add the impactor, run STEPS steps, print timings
// Both print one JSON object on the last line; run's ends with a hash of the final state.
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"
#include "dem/Impactor.h"

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
} // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: ck_dem_bench make-bed FILE PARTICLES | run FILE STEPS\n";
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
  if (mode != "run")
    return 2;
  const long steps = std::atol(argv[3]);
  std::ifstream in(file);
  Box box{};
  in >> box.side >> box.depth;
  ParticleSet s;
  double x[3];
  while (in >> x[0] >> x[1] >> x[2])
    s.add(x, kRadius, kDensity, 0, static_cast<std::int64_t>(s.size()));
  ImpactorParams imp;
  imp.radius = 2.0 * kRadius;
  imp.density = kDensity;
  imp.speed = kSpeed;
  addImpactor(s, imp);

  DemParams p;
  Container c;
  c.type = Container::Type::Box;
  c.boxSize = {box.side, box.side, box.depth};
  p.walls = containerWalls(c);
  p.gravity = Gravity::downward(kGravity);
  const StiffnessChoice k =
      chooseStiffnessAndStep({kRadius, kDensity, kSpeed, 0.01, kGravity, box.depth, 30.0});
  p.contact.kN = k.kN;
  p.dt = k.dt;
  // The coefficients run.py gives the peers (EPS, MU_S, MU_R, MU_T, BETA there).
  p.contact.restitutionN = p.contact.restitutionT = 0.55;
  p.contact.muS = 0.6;
  p.contact.muR = 1.05;
  p.contact.muT = 1.3;
  p.contact.beta = 0.5;
  DemSolver solver(s, p);
  const auto t0 = std::chrono::steady_clock::now();
  solver.advanceSteps(steps); // the bits of step() called STEPS times
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double m = kDensity * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  std::printf(
      "{\"code\": \"CraterKit\", \"threads\": %d, \"particles\": %zu, \"steps\": %ld, "
      "\"seconds\": %.4f, \"kn\": %.17g, \"dt\": %.17g, \"mass\": %.17g, \"radius\": %.17g, "
      "\"impactor_radius\": %.17g, \"speed\": %.17g, \"side\": %.17g, \"depth\": %.17g, "
      "\"builds\": %zu, \"contacts\": %zu, \"damping_factor_n\": %.17g, "
      "\"damping_factor_t\": %.17g, \"state_hash\": \"%016llx\"}\n",
      omp_get_max_threads(), s.size(), steps, seconds, k.kN, k.dt, m, kRadius, imp.radius, kSpeed,
      box.side, box.depth, solver.neighbourBuilds(), solver.diagnostics().contacts,
      clippedDampingFactor(NormalLawKind::LinearSpringDashpot, p.contact.restitutionN),
      dashpotFactor(p.contact.restitutionT),
      static_cast<unsigned long long>(stateHash(solver.particles())));
  return 0;
}
