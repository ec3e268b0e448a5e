// Angle of repose of the SSDEM contact model by the fixed-base heap test
// (Solvers/analysis/HeapTest.h).
//   ck_repose MU_S MU_R MU_T [BASE_RADIUS_IN_PARTICLE_RADII]
// Prints one JSON object. A validation run, not a test: see benchmarks/README.md.
#include "analysis/HeapTest.h"

#include <cstdio>
#include <cstdlib>

using namespace craterkit;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: ck_repose MU_S MU_R MU_T [BASE_RADIUS/r]\n");
    return 2;
  }
  ContactParams c;
  c.muS = std::atof(argv[1]);
  c.muR = std::atof(argv[2]);
  c.muT = std::atof(argv[3]);
  const HeapTestResult h = runFixedBaseHeap(c, argc > 4 ? std::atof(argv[4]) : 12.0);
  std::printf(
      "{\"mu_s\": %g, \"mu_r\": %g, \"mu_t\": %g, \"particles_start\": %zu, \"particles_heap\": "
      "%zu, "
      "\"time\": %.2f, \"flank_angle_deg\": %.1f, \"cone_angle_deg\": %.1f, \"height_m\": %.4f, "
      "\"base_m\": %.3f}\n",
      c.muS, c.muR, c.muT, h.particlesStart, h.particlesHeap, h.time, h.flankDegrees, h.coneDegrees,
      h.height, h.base);
  return 0;
}
