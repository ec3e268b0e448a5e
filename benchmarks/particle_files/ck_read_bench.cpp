// Reading speed of the particle-file parsers against `cat` of the same file.
//   ck_read_bench [PARTICLES] [DIR]
// Writes a random set of PARTICLES (default 1e6) as a pkdgrav .ss file and as a LAMMPS dump
// in DIR, then times (best of three, file in the page cache) `cat FILE > /dev/null` and
// reading (a memory map, as the reader does) + parse for each. Prints MB/s and the ratio. See
// benchmarks/README.md.
#include "common/Random.h"
#include "io/FileBytes.h"
#include "io/LammpsDump.h"
#include "io/PkdgravSs.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>

using namespace craterkit;

namespace {
double seconds(const std::function<void()>& f) {
  double best = 1e300;
  for (int k = 0; k < 3; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}
void save(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
// The same columns as writeDump with LAMMPS's default `dump custom` format (%g: six
// significant digits), which is what most users' dumps hold.
std::string writeDumpG(const ParticleFrame& f) {
  const std::string full = writeDump(f);
  std::string out = full.substr(0, full.find("ITEM: ATOMS"));
  out += "ITEM: ATOMS id type x y z vx vy vz omegax omegay omegaz radius mass\n";
  const ParticleSet& s = f.particles;
  char line[512];
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double* x = &s.position[3 * i];
    const double* v = &s.velocity[3 * i];
    const double* w = &s.angularVelocity[3 * i];
    const int len = std::snprintf(line, sizeof line, "%lld %d %g %g %g %g %g %g %g %g %g %g %g\n",
                                  static_cast<long long>(s.id[i]), s.material[i] + 1, x[0], x[1],
                                  x[2], v[0], v[1], v[2], w[0], w[1], w[2], s.radius[i], s.mass[i]);
    out.append(line, static_cast<std::size_t>(len));
  }
  return out;
}
// The bound for a text parser: only converting every value of the atom lines with
// std::from_chars (nothing stored), the lines cut in halves for two threads as the parser does.
double convertOnly(std::string_view text) {
  const std::size_t body = text.find('\n', text.find("ITEM: ATOMS")) + 1;
  const std::size_t half = text.find('\n', body + (text.size() - body) / 2) + 1;
  const std::size_t cut[3] = {body, half, text.size()};
  double sum[2] = {0, 0};
#pragma omp parallel for num_threads(2)
  for (int t = 0; t < 2; ++t) {
    const char* p = text.data() + cut[t];
    const char* e = text.data() + cut[t + 1];
    double acc = 0;
    while (p < e) {
      double v = 0;
      p = std::from_chars(p, e, v).ptr + 1; // one blank or newline after each value
      acc += v;
    }
    sum[t] = acc;
  }
  return sum[0] + sum[1];
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
  const std::string ss = dir + "/bench.ss", dump = dir + "/bench.dump",
                    dumpG = dir + "/bench-g.dump";
  save(ss, writeSs(f, true));
  save(dump, writeDump(f));
  save(dumpG, writeDumpG(f));
  std::printf("%zu particles\n%-7s %10s %12s %12s %8s %16s\n", n, "format", "MB", "cat MB/s",
              "parse MB/s", "ratio", "from_chars MB/s");
  for (const auto& [name, path] :
       {std::pair{"ss", ss}, std::pair{"dump", dump}, std::pair{"dump%g", dumpG}}) {
    const std::string p = path;
    const std::string cmd = "cat '" + p + "' > /dev/null";
    const double tc = seconds([&] {
      if (std::system(cmd.c_str()) != 0)
        std::abort();
    });
    std::size_t bytes = 0;
    const double tp = seconds([&] {
      const FileBytes file(p); // memory-mapped, as the reader reads both formats
      bytes = file.view().size();
      if (std::string(name) == "ss") {
        if (parseSs(file.view(), p, true).particles.size() != n)
          std::abort();
        return;
      }
      for (const DumpIndexEntry& e : indexDump(file.view(), p))
        if (parseDumpSnapshot(file.view(), e, p).particles.size() != n)
          std::abort();
    });
    const double mb = bytes / 1e6;
    double tf = 0.0; // the conversion-only bound (text formats)
    if (std::string(name) != "ss") {
      const FileBytes file(p);
      double check = 0;
      tf = seconds([&] { check += convertOnly(file.view()); });
      if (!std::isfinite(check))
        std::abort();
    }
    std::printf("%-7s %10.1f %12.0f %12.0f %8.2f %16s\n", name, mb, mb / tc, mb / tp, tc / tp,
                tf > 0 ? std::to_string(static_cast<int>(mb / tf)).c_str() : "-");
  }
  return 0;
}
