#include "analysis/HeapTest.h"

#include "analysis/HeapAngle.h"
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <cmath>
#include <vector>

namespace craterkit {

HeapTestResult runFixedBaseHeap(const ContactParams& contact, double baseInRadii) {
  const double r = 0.01, rho = 2000.0, g = 9.81;
  const double base = baseInRadii * r;
  const double side = 1.6 * base, height = 2.0 * base;
  GranularBedParams bp;
  bp.container.type = Container::Type::Box;
  bp.container.boxSize = {side, side, height};
  bp.sizes.radius = r;
  bp.particleDensity = rho;
  bp.settle = false;
  const ParticleSet column = generateGranularBed(bp);

  DemParams p;
  p.contact = contact;
  const StiffnessChoice k = chooseStiffnessAndStep({r, rho, 1.0, 0.02, g, height, 30.0});
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.gravity = Gravity::downward(g);
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
  HeapTestResult out;
  out.particlesStart = column.size();
  out.particlesHeap = solver.particles().size();
  out.time = solver.time();
  out.flankDegrees = a.degrees;
  out.coneDegrees = std::atan(a.height / base) * 180.0 / M_PI;
  out.height = a.height;
  out.base = base;
  return out;
}

} // namespace craterkit
