// Granular column collapse of the SSDEM contact model (Solvers/analysis/ColumnCollapse.h)
// against Lube et al. (2004)'s runout fits.
//   ck_column_collapse ASPECT_RATIO RADIUS_IN_GRAINS [MU_S MU_R MU_T]
// Prints one JSON object. A validation run, not a test: tests/slow runs it.
#include "analysis/ColumnCollapse.h"

#include <cstdio>
#include <cstdlib>
#include <exception>

using namespace craterkit;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: ck_column_collapse ASPECT_RATIO RADIUS_IN_GRAINS [MU_S MU_R MU_T]\n");
    return 2;
  }
  ContactParams c; // the defaults DEMIntegrator uses
  if (argc > 5) {
    c.muS = std::atof(argv[3]);
    c.muR = std::atof(argv[4]);
    c.muT = std::atof(argv[5]);
  }
  try {
    const ColumnCollapseResult r = runColumnCollapse(c, std::atof(argv[1]), std::atof(argv[2]));
    std::printf("{\"mu_s\": %g, \"mu_r\": %g, \"mu_t\": %g, \"particles\": %zu, \"r0_m\": %.4f, "
                "\"h0_m\": %.4f, \"aspect_ratio\": %.3f, \"r_final_m\": %.4f, \"h_final_m\": %.4f, "
                "\"runout\": %.3f, \"lube_runout\": %.3f, \"r_99_percent_m\": %.4f, "
                "\"runout_99_percent\": %.3f, \"time_s\": %.2f}\n",
                c.muS, c.muR, c.muT, r.particles, r.columnRadius, r.columnHeight, r.aspectRatio,
                r.finalRadius, r.finalHeight, r.runout, lubeRunout(r.aspectRatio), r.radius99,
                (r.radius99 - r.columnRadius) / r.columnRadius, r.time);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ck_column_collapse: %s\n", e.what());
    return 1;
  }
  return 0;
}
