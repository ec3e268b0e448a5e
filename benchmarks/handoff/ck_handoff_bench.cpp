// Hand-off benchmark: N SPH particles on a cubic lattice filling a hemisphere (a Maxwell
// Z-model excavation flow, so some are ejecta) onto a bed of about N spheres; prints the time
// of each step.   ck_handoff_bench [N_SPH [N_BED]]
#include "handoff/Handoff.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <omp.h>

using namespace craterkit;

int main(int argc, char** argv) {
  const double nSph = argc > 1 ? std::atof(argv[1]) : 1e6,
               nBed = argc > 2 ? std::atof(argv[2]) : nSph;
  const double R = 1.0, volume = 2.0 / 3.0 * M_PI * R * R * R;
  const double dx = std::cbrt(volume / nSph);
  SphSnapshot s;
  const int n = static_cast<int>(R / dx) + 1;
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, -(k + 0.5) * dx};
        const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (r > R)
          continue;
        const double uR = std::pow(0.25 / r, 3.0), cosT = -x[2] / r,
                     sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        const double uT = uR * sinT / (1.0 + cosT), rho = std::hypot(x[0], x[1]);
        const double eT[3] = {rho > 0 ? cosT * x[0] / rho : 0.0, rho > 0 ? cosT * x[1] / rho : 0.0,
                              sinT};
        for (int a = 0; a < 3; ++a)
          s.v.push_back(uR * x[a] / r + uT * eT[a]);
        s.x.insert(s.x.end(), x, x + 3);
        s.mass.push_back(1190.0 * dx * dx * dx);
        s.h.push_back(2.5 * dx);
      }
  // Bed: simple cubic spheres (packing π/6) in a box 2.4 R wide and 1.2 R deep.
  const double boxVolume = 2.4 * 2.4 * 1.2 * R * R * R, spacing = std::cbrt(boxVolume / nBed),
               rb = 0.5 * spacing;
  ParticleSet bed;
  const int m = static_cast<int>(1.2 * R / spacing);
  std::int64_t id = 0;
  for (int i = -m; i < m; ++i)
    for (int j = -m; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const double x[3] = {(i + 0.5) * spacing, (j + 0.5) * spacing, -(k + 0.5) * spacing};
        bed.add(x, rb, 1190.0 / (M_PI / 6.0), 0, id++);
      }
  TargetRegion region;
  region.shape = TargetRegion::Shape::Hemisphere;
  region.radius = R;
  std::printf("hand-off: %zu SPH particles (dx %.4g m) onto %zu bed spheres, %d threads\n",
              s.size(), dx, bed.size(), omp_get_max_threads());
  const auto t0 = std::chrono::steady_clock::now();
  const HandoffResult r = handoff(s, bed, region, HandoffParams{});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "alpha radius %.4g m, %zu compact, %zu ejecta, %zu bed removed, %zu mapped, %zu triangles\n",
      r.alphaRadius, r.compactCount, r.ejectaCount, r.bedRemoved, r.bedMapped,
      r.triangles.size() / 3);
  std::printf("seconds: split %.2f, alpha shape %.2f, carve %.2f, map %.2f, ejecta %.2f, correct "
              "%.2f; total %.2f\n",
              r.seconds.split, r.seconds.alphaShape, r.seconds.carve, r.seconds.map,
              r.seconds.ejecta, r.seconds.correct, wall);
}
