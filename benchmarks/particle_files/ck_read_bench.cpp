// Reading speed of the particle-file parsers against `cat` of the same file.
//   ck_read_bench [PARTICLES] [DIR]
// Writes a random set of PARTICLES (default 1e6) as a pkdgrav .ss file and as a LAMMPS dump
// in DIR, then times (best of three, file in the page cache) `cat FILE > /dev/null` and
// reading (a memory map for .ss, as the reader does; a copy for dumps) + parse for each. Prints MB/s and the ratio. See benchmarks/README.md.
#include "common/Random.h"
#include "io/ParticleFiles.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <fstream>
#include <string>

using namespace craterkit;

namespace {
double seconds(const std::function<void()>& f) {
  double best = 1e300;
  for (int k = 0; k < 3; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}
void save(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
} // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? static_cast<std::size_t>(std::atof(argv[1])) : 1000000;
  const std::string dir = argc > 2 ? argv[2] : ".";
  Random rng(1);
  ParticleFrame f;
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 0)};
    f.particles.add(x, rng.uniform(0.4, 0.6), 2000.0, 0, static_cast<std::int64_t>(i + 1));
    for (int k = 0; k < 3; ++k) {
      f.particles.velocity[3 * i + k] = rng.uniform(-1, 1);
      f.particles.angularVelocity[3 * i + k] = rng.uniform(-1, 1);
    }
    f.particles.mass.back() = rng.uniform(1000, 2000);
  }
  const std::string ss = dir + "/bench.ss", dump = dir + "/bench.dump";
  save(ss, writeSs(f, true));
  save(dump, writeDump(f));
  std::printf("%zu particles\n%-6s %10s %12s %12s %8s\n", n, "format", "MB", "cat MB/s", "parse MB/s", "ratio");
  for (const auto& [name, path] : {std::pair{"ss", ss}, std::pair{"dump", dump}}) {
    const std::string p = path;
    const std::string cmd = "cat '" + p + "' > /dev/null";
    const double tc = seconds([&] {
      if (std::system(cmd.c_str()) != 0)
        std::abort();
    });
    std::size_t bytes = 0;
    const double tp = seconds([&] {
      if (std::string(name) == "ss") {
        const FileBytes file(p); // memory-mapped: the reader's path for .ss
        bytes = file.view().size();
        const ParticleFrame g = parseSs(file.view(), p, true);
        if (g.particles.size() != n)
          std::abort();
        return;
      }
      const std::string data = readFileBytes(p); // dumps: the reader keeps a copy
      bytes = data.size();
      for (const DumpIndexEntry& e : indexDump(data, p))
        if (parseDumpSnapshot(data, e, p).particles.size() != n)
          std::abort();
    });
    const double mb = bytes / 1e6;
    std::printf("%-6s %10.1f %12.0f %12.0f %8.2f\n", name, mb, mb / tc, mb / tp, tc / tp);
  }
  return 0;
}
