// The SCI-like SPH impact without VTK: builds the default problem of the SPHImpact source,
// runs it to a given time and prints throughput (particle-steps per second) and the
// conservation figures.
//   ck_sph_bench [END_TIME [PARTICLES_ACROSS_IMPACTOR [TARGET_RADIUS]]]
// Environment: CK_POROSITY (target porosity), CK_IMPACTOR (material name), CK_SKIN
// (neighbour-list skin in units of h).
#include "sph/ImpactSetup.h"
#include "sph/SphSolver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <omp.h>

using namespace craterkit;

int main(int argc, char** argv) {
  SphImpactSetup setup;
  setup.materialDirectory = std::string(CRATERKIT_SOURCE_DIR) + "/data/materials";
  const double end = argc > 1 ? std::atof(argv[1]) : 2e-4;
  if (argc > 2)
    setup.particlesAcrossImpactor = std::atoi(argv[2]);
  if (argc > 3)
    setup.targetRadius = std::atof(argv[3]);
  if (const char* e = std::getenv("CK_POROSITY"))
    setup.targetPorosity = std::atof(e);
  if (const char* e = std::getenv("CK_IMPACTOR"))
    setup.impactorMaterial = e;
  setup.frictionAngle = 30.0;
  setup.cohesion = 0.0;
  SphImpactProblem prob = buildImpact(setup);
  if (const char* e = std::getenv("CK_SKIN"))
    prob.params.skin = std::atof(e);

  SphSolver solver(prob.state, prob.params);
  const std::size_t n = prob.state.size();
  std::printf("SCI-like SPH: %zu particles (%zu impactor), dx = %.4g m, %d threads, to t = %.3g s\n", n,
              prob.impactorParticles, prob.spacing, omp_get_max_threads(), end);
  double P0[3];
  solver.totalMomentum(P0);
  const double E0 = solver.totalEnergy();
  const auto t0 = std::chrono::steady_clock::now();
  double nextReport = 0.0;
  while (solver.time() < end) {
    solver.step(std::min(solver.stableStep(), end - solver.time()));
    if (solver.time() >= nextReport || solver.time() >= end) {
      double P[3], vmax = 0.0, pmax = 0.0, amin = 10.0;
      solver.totalMomentum(P);
      const SphState& s = solver.state();
      for (std::size_t i = 0; i < n; ++i) {
        vmax = std::max(vmax, std::sqrt(s.v[3 * i] * s.v[3 * i] + s.v[3 * i + 1] * s.v[3 * i + 1] + s.v[3 * i + 2] * s.v[3 * i + 2]));
        pmax = std::max(pmax, solver.pressure()[i]);
        if (s.material[i] == 1)
          amin = std::min(amin, s.alpha[i]);
      }
      std::printf("t = %.3e s, %zu steps, dt %.2e, vmax %.0f m/s, pmax %.3g Pa, min distention %.3f, dP/P0 = %.1e, dE/E0 = %.2e\n",
                  solver.time(), solver.steps(), solver.stableStep(), vmax, pmax, amin,
                  std::abs(P[2] - P0[2]) / std::abs(P0[2]), (solver.totalEnergy() - E0) / E0);
      std::fflush(stdout);
      nextReport += end / 10.0;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%zu steps in %.2f s: %.3g particle-steps/s\n", solver.steps(), wall,
              static_cast<double>(n) * solver.steps() / wall);
}
