// Event-driven hard disks: collisions per second against N (one core).
//   ck_edmd_bench [AREA_FRACTION] [N ...]
// A periodic hard-disk gas (disks of one size, equal masses, started on a square lattice
// with random velocity directions) is equilibrated for 2 N collisions, then timed over
// 10 N collisions, and at least 2 million (a shorter timing is noise). Prints one JSON object per
// N. See benchmarks/README.md. Environment: CK_SHUFFLE=1 numbers the disks in random order (as a
// long run or a random packing leaves them) instead of along the lattice.
#include "common/Random.h"
#include "edmd/HardDiskSystem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

using namespace craterkit;

int main(int argc, char** argv) {
  const double eta = argc > 1 ? std::atof(argv[1]) : 0.4;
  std::vector<std::size_t> sizes;
  for (int a = 2; a < argc; ++a)
    sizes.push_back(static_cast<std::size_t>(std::atof(argv[a])));
  if (sizes.empty())
    sizes = {1000, 10000, 100000, 1000000};
  for (std::size_t n : sizes) {
    const double r = 1.0, side = std::sqrt(n * M_PI * r * r / eta);
    const std::size_t k = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
    Random rng(5);
    std::vector<std::size_t> site(n);
    for (std::size_t i = 0; i < n; ++i)
      site[i] = i;
    const char* shuffle = std::getenv("CK_SHUFFLE");
    if (shuffle && std::atoi(shuffle) != 0)
      for (std::size_t i = n - 1; i > 0; --i) // Fisher–Yates
        std::swap(
            site[i],
            site[static_cast<std::size_t>(rng.uniform() * static_cast<double>(i + 1)) % (i + 1)]);
    HardDisks d;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * rng.uniform();
      d.add((site[i] % k + 0.5) * side / k, (site[i] / k + 0.5) * side / k, std::cos(a),
            std::sin(a), r, 1.0, 0, static_cast<std::int64_t>(i));
    }
    HardDiskParams p;
    p.width = p.height = side;
    p.periodicX = p.periodicY = true;
    HardDiskSystem sys(d, p);
    while (sys.pairCollisions() < 2 * n)
      sys.processEvents(n);
    const std::uint64_t c0 = sys.pairCollisions(), cells0 = sys.cellCrossings(),
                        stale0 = sys.staleEvents();
    const auto t0 = std::chrono::steady_clock::now();
    const std::uint64_t timed = std::max<std::uint64_t>(10 * n, 2000000);
    while (sys.pairCollisions() - c0 < timed)
      sys.processEvents(n);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double collisions = static_cast<double>(sys.pairCollisions() - c0);
    std::printf("{\"N\": %zu, \"area_fraction\": %.3f, \"collisions\": %.0f, \"seconds\": %.3f, "
                "\"collisions_per_s\": %.4g, \"cell_crossings_per_collision\": %.3f, "
                "\"stale_per_collision\": %.3f, \"ns_per_collision\": %.1f}\n",
                n, eta, collisions, seconds, collisions / seconds,
                (sys.cellCrossings() - cells0) / collisions,
                (sys.staleEvents() - stale0) / collisions, 1e9 * seconds / collisions);
    std::fflush(stdout);
  }
  return 0;
}
