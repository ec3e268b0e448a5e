// Angle of repose of the SSDEM contact model: a loose column collapses onto a thin disk
// (the fixed-base method: material beyond the base falls off and is removed), and the
// heap left on the base is measured (Solvers/analysis/HeapAngle.h).
//   ck_repose MU_S MU_R MU_T [BASE_RADIUS_IN_PARTICLE_RADII]
// Prints one JSON object. A validation run, not a test: see benchmarks/README.md.
#include "analysis/HeapAngle.h"
#include "bed/GranularBed.h"
#include "dem/DemSolver.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace craterkit;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: ck_repose MU_S MU_R MU_T [BASE_RADIUS/r]\n");
    return 2;
  }
  const double r = 0.01, rho = 2000.0, g = 9.81;
  const double base = (argc > 4 ? std::atof(argv[4]) : 12.0) * r;
  const double side = 1.6 * base, height = 2.0 * base;
  GranularBedParams bp;
  bp.container.type = Container::Type::Box;
  bp.container.boxSize = {side, side, height};
  bp.sizes.radius = r;
  bp.particleDensity = rho;
  bp.settle = false;
  const ParticleSet column = generateGranularBed(bp);

  DemParams p;
  p.contact.muS = std::atof(argv[1]);
  p.contact.muR = std::atof(argv[2]);
  p.contact.muT = std::atof(argv[3]);
  const StiffnessProposal k = proposeStiffness(r, rho, 1.0, 0.02, g, height, 30.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.gravity.vector = {0, 0, -g};
  p.walls.push_back(Wall::disk({0, 0, -height}, {0, 0, 1}, base));
  DemSolver solver(column, p);
  const double chunk = 0.05;
  double quiet = 0.0;
  while (solver.time() < 10.0) {
    solver.advanceTo(solver.time() + chunk);
    const ParticleSet& s = solver.particles();
    std::vector<char> fallen(s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
      fallen[i] = s.position[3 * i + 2] < -height - 2 * r;
    solver.removeParticles(fallen);
    const DemDiagnostics d = solver.diagnostics();
    const double perParticle = (d.kineticEnergy + d.rotationalEnergy) / solver.particles().size();
    quiet = perParticle < 1e-3 * solver.particles().mass[0] * g * r ? quiet + chunk : 0.0;
    if (quiet >= 0.2)
      break;
  }
  const HeapAngle a = measureHeapAngle(solver.particles(), -height, 0.3, 0.9);
  const double cone = std::atan(a.height / base) * 180.0 / M_PI;
  std::printf("{\"mu_s\": %g, \"mu_r\": %g, \"mu_t\": %g, \"particles_start\": %zu, \"particles_heap\": %zu, "
              "\"time\": %.2f, \"flank_angle_deg\": %.1f, \"cone_angle_deg\": %.1f, \"height_m\": %.4f, "
              "\"base_m\": %.3f}\n",
              p.contact.muS, p.contact.muR, p.contact.muT, column.size(), solver.particles().size(),
              solver.time(), a.degrees, cone, a.height, base);
  return 0;
}
