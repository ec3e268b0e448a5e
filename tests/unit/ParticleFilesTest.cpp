// Particle file formats: round trips, files written by LAMMPS itself, and malformed input.
#include "common/Random.h"
#include "io/FileBytes.h"
#include "io/LammpsDump.h"
#include "io/PkdgravSs.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

using namespace craterkit;

namespace {

ParticleFrame randomFrame(std::size_t n, std::uint64_t seed) {
  Random rng(seed);
  ParticleFrame f;
  f.time = 0.125;
  f.timestep = 4200;
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1e-3, 1e3)};
    f.particles.add(x, rng.uniform(0.01, 0.1), 2000.0, static_cast<int>(rng.uniform() * 3),
                    static_cast<std::int64_t>(10 * i + 7));
    f.particles.mass.back() = rng.uniform(0.1, 10.0);
    for (int k = 0; k < 3; ++k) {
      f.particles.velocity[3 * i + k] = rng.uniform(-5, 5) * 1e-7;
      f.particles.angularVelocity[3 * i + k] = rng.uniform(-100, 100);
    }
  }
  ExtraArray force{"f", 3, {}}, energy{"c_ke", 1, {}};
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k)
      force.values.push_back(rng.uniform(-1, 1) / 3.0);
    energy.values.push_back(std::exp(rng.uniform(-30, 30)));
  }
  f.extra = {force, energy};
  return f;
}

void expectSameParticles(const ParticleSet& a, const ParticleSet& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.angularVelocity, b.angularVelocity);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.id, b.id);
}

std::string parseError(const std::function<void()>& f) {
  try {
    f();
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string dumpError(const std::string& text) {
  return parseError([&] {
    for (const DumpIndexEntry& e : indexDump(text, "bad.dump"))
      parseDumpSnapshot(text, e, "bad.dump");
  });
}

const char* kHandDump = "ITEM: TIMESTEP\n"
                        "100\n"
                        "ITEM: NUMBER OF ATOMS\n"
                        "2\n"
                        "ITEM: BOX BOUNDS pp pp fm\n"
                        "0 2\n"
                        "-1 1\n"
                        "0 10\n"
                        "ITEM: ATOMS vx id xs ys zs type diameter fx fy fz c_1\n"
                        "0.5 9 0.25 0.5 0.1 2 0.2 1 2 3 42\n"
                        "-0.5 3 0.75 0.0 0.2 1 0.4 4 5 6 43\n";

} // namespace

TEST(LammpsDump, RoundTripIsExact) {
  const ParticleFrame f = randomFrame(300, 3);
  const std::string text = writeDump(f);
  const std::vector<DumpIndexEntry> index = indexDump(text, "mem.dump");
  ASSERT_EQ(index.size(), 1u);
  EXPECT_EQ(index[0].timestep, 4200);
  EXPECT_EQ(index[0].count, 300u);
  const ParticleFrame g = parseDumpSnapshot(text, index[0], "mem.dump");
  expectSameParticles(f.particles, g.particles);
  EXPECT_EQ(f.particles.material, g.particles.material);
  EXPECT_EQ(g.time, 0.125);
  ASSERT_EQ(g.extra.size(), 2u);
  EXPECT_EQ(g.extra[0].name, "f");
  EXPECT_EQ(g.extra[0].components, 3);
  EXPECT_EQ(g.extra[0].values, f.extra[0].values);
  EXPECT_EQ(g.extra[1].name, "c_ke");
  EXPECT_EQ(g.extra[1].values, f.extra[1].values);
}

TEST(LammpsDump, SeveralSnapshotsAndAnyColumnOrder) {
  const std::string text = writeDump(randomFrame(5, 1)) + "\n" + kHandDump;
  const std::vector<DumpIndexEntry> index = indexDump(text, "two.dump");
  ASSERT_EQ(index.size(), 2u);
  EXPECT_EQ(index[1].timestep, 100);
  const ParticleFrame f = parseDumpSnapshot(text, index[1], "two.dump");
  ASSERT_EQ(f.particles.size(), 2u);
  EXPECT_EQ(f.particles.id[0], 9);
  EXPECT_EQ(f.particles.material[0], 1);          // type 2
  EXPECT_DOUBLE_EQ(f.particles.position[0], 0.5); // xs 0.25 of [0, 2]
  EXPECT_DOUBLE_EQ(f.particles.position[1], 0.0); // ys 0.5 of [-1, 1]
  EXPECT_DOUBLE_EQ(f.particles.position[2], 1.0); // zs 0.1 of [0, 10]
  EXPECT_DOUBLE_EQ(f.particles.radius[1], 0.2);   // diameter 0.4
  EXPECT_DOUBLE_EQ(f.particles.velocity[3], -0.5);
  EXPECT_FALSE(f.hasMass);
  ASSERT_EQ(f.extra.size(), 2u);
  EXPECT_EQ(f.extra[0].name, "f");
  EXPECT_EQ(f.extra[0].values[3], 4.0);
  EXPECT_EQ(f.extra[1].name, "c_1");
  EXPECT_EQ(f.extra[1].values[1], 43.0);
}

TEST(LammpsDump, MalformedInputNamesFileAndLine) {
  const std::string good = kHandDump;
  // Truncated: the last atom line is missing.
  EXPECT_NE(dumpError(good.substr(0, good.rfind("-0.5"))).find("declares more atoms"),
            std::string::npos);
  // A non-numeric field, reported on its line (line 11).
  std::string bad = good;
  bad.replace(bad.find("-0.5"), 4, "abc");
  EXPECT_NE(dumpError(bad).find("bad.dump:11: expected a number for vx, got 'abc'"),
            std::string::npos)
      << dumpError(bad);
  // A missing coordinate column.
  bad = good;
  bad.replace(bad.find(" zs"), 3, " qq");
  EXPECT_NE(dumpError(bad).find("no 'z' column"), std::string::npos);
  // A count no file of this size could hold.
  bad = good;
  bad.replace(bad.find("\n2\n"), 3, "\n999999999999\n");
  EXPECT_NE(dumpError(bad).find("exceeds what the rest of the file can hold"), std::string::npos)
      << dumpError(bad);
  // A row with too few values.
  bad = good;
  bad.replace(bad.find(" 43"), 3, "");
  EXPECT_NE(dumpError(bad).find("expected 11 values, found 10"), std::string::npos)
      << dumpError(bad);
  EXPECT_NE(dumpError("").find("no snapshot"), std::string::npos);
  EXPECT_NE(dumpError("hello\n").find("expected an 'ITEM:' line"), std::string::npos);
  bad = good;
  bad.replace(bad.find("\n2\n"), 3, "\n-4\n");
  EXPECT_NE(dumpError(bad).find("negative NUMBER OF ATOMS"), std::string::npos);
}

TEST(PkdgravSs, RoundTripIsBitExact) {
  const ParticleFrame f = randomFrame(200, 9);
  const std::string bytes = writeSs(f, false);
  ASSERT_EQ(bytes.size(), 16u + 96u * 200u);
  const ParticleFrame g = parseSs(bytes, "mem.ss", false);
  expectSameParticles(f.particles, g.particles);
  EXPECT_EQ(g.time, f.time);
  // Reading and writing again reproduces the bytes, colours included.
  EXPECT_EQ(writeSs(g, false), bytes);
  // With pkdgrav units the values round-trip to a few ulps.
  const ParticleFrame h = parseSs(writeSs(f, true), "mem.ss", true);
  for (std::size_t i = 0; i < f.particles.position.size(); ++i)
    EXPECT_NEAR(h.particles.position[i], f.particles.position[i],
                4e-16 * std::abs(f.particles.position[i]));
  EXPECT_NEAR(h.time, f.time, 1e-15);
  EXPECT_NEAR(PkdgravUnits::time(), 365.25 * 86400 / (2 * M_PI), 2e-4 * PkdgravUnits::time());
}

TEST(PkdgravSs, MalformedInputNamesTheByteOffset) {
  const std::string good = writeSs(randomFrame(3, 2), false);
  auto err = [](const std::string& b) { return parseError([&] { parseSs(b, "bad.ss", false); }); };
  EXPECT_NE(err(good.substr(0, 10)).find("bad.ss: byte 0: truncated header"), std::string::npos);
  EXPECT_NE(err(good.substr(0, good.size() - 5)).find("declares 3 particles"), std::string::npos);
  EXPECT_NE(err(good + "xx").find("2 unexpected bytes"), std::string::npos);
  std::string bad = good;
  bad[15] = 7; // magic
  EXPECT_NE(err(bad).find("byte 12: wrong magic number"), std::string::npos);
  std::string le = good; // the count written little-endian (the magic -1 reads the same)
  std::reverse(le.begin() + 8, le.begin() + 12);
  EXPECT_NE(err(le).find("little-endian"), std::string::npos);
  std::string reduced = good;
  const unsigned char magic[4] = {0xFF, 0xFF, 0xD8, 0x8B}; // -10101
  std::memcpy(&reduced[12], magic, 4);
  EXPECT_NE(err(reduced).find("reduced .ss format"), std::string::npos);
  std::string huge = good;
  const unsigned char count[4] = {0x7F, 0xFF, 0xFF, 0xFF};
  std::memcpy(&huge[8], count, 4);
  EXPECT_NE(err(huge).find("declares 2147483647 particles"), std::string::npos);
  const unsigned char negative[4] = {0xFF, 0xFF, 0xFF, 0xFE};
  std::memcpy(&huge[8], negative, 4);
  EXPECT_NE(err(huge).find("negative particle count"), std::string::npos);
}

TEST(ParticleFiles, GzipDumpsReadLikePlainOnesAndBadGzipIsNamed) {
  const std::string text = writeDump(randomFrame(50, 4));
  const std::string path =
      (std::filesystem::temp_directory_path() / "craterkit_test.dump.gz").string();
  gzFile gz = gzopen(path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  gzclose(gz);
  EXPECT_EQ(readFileBytes(path), text);
  // Truncated compressed stream.
  std::string raw;
  {
    std::ifstream in(path, std::ios::binary);
    raw.assign(std::istreambuf_iterator<char>(in), {});
  }
  EXPECT_NE(parseError([&] { gunzip(raw.substr(0, raw.size() / 2), "half.gz"); }).find("half.gz"),
            std::string::npos);
  std::string corrupt = raw;
  for (std::size_t k = 20; k < 40 && k < corrupt.size(); ++k)
    corrupt[k] = static_cast<char>(~corrupt[k]);
  EXPECT_NE(parseError([&] { gunzip(corrupt, "corrupt.gz"); }).find("corrupt.gz"),
            std::string::npos);
  EXPECT_NE(parseError([&] { readFileBytes("/nonexistent/x.dump"); }).find("cannot open"),
            std::string::npos);
  std::filesystem::remove(path);
}

// A LAMMPS run writes a dump; the reader must agree with LAMMPS's own thermo output.
TEST(LammpsDump, ReadsWhatLammpsWritesAndMatchesItsThermo) {
  if (std::system("command -v lmp > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "LAMMPS (lmp, Debian package lammps) is not installed: skipped";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "craterkit_lammps_dump";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "in.dump") << R"(units si
atom_style sphere
boundary f f f
region box block 0 1 0 1 0 1 units box
create_box 2 box
create_atoms 1 random 300 12345 box
create_atoms 2 random 100 54321 box
set type 1 diameter 0.01
set type 1 density 2500
set type 2 diameter 0.02
set type 2 density 1000
velocity all create 1.0 4928459 loop geom
variable m equal mass(all)
variable vxm equal vcm(all,x)
variable n equal count(all)
thermo_style custom step v_n v_m v_vxm
thermo_modify format float %.17g
dump d all custom 1 dump.out id type x y z vx vy vz radius mass
dump_modify d format float %.17g
run 0
)";
  const std::string cmd =
      "cd '" + dir.string() + "' && timeout 120 lmp -in in.dump -log log.out -screen none";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  // Thermo line after the header "Step v_n c_m v_vxm".
  std::ifstream log(dir / "log.out");
  std::string line;
  double n = 0, mass = 0, vx = 0;
  while (std::getline(log, line))
    if (line.find("Step") != std::string::npos && line.find("v_n") != std::string::npos) {
      std::getline(log, line);
      std::istringstream values(line); // step, count, total mass, centre-of-mass vx
      double step;
      values >> step >> n >> mass >> vx;
      break;
    }
  ASSERT_GT(n, 0.0) << "no thermo line in the LAMMPS log";
  const std::string text = readFileBytes((dir / "dump.out").string());
  const std::vector<DumpIndexEntry> index = indexDump(text, "dump.out");
  ASSERT_EQ(index.size(), 1u);
  const ParticleFrame f = parseDumpSnapshot(text, index[0], "dump.out");
  EXPECT_EQ(static_cast<double>(f.particles.size()), n);
  double m = 0, p = 0;
  for (std::size_t i = 0; i < f.particles.size(); ++i) {
    m += f.particles.mass[i];
    p += f.particles.mass[i] * f.particles.velocity[3 * i];
  }
  EXPECT_NEAR(m, mass, 1e-12 * mass);
  EXPECT_NEAR(p / m, vx, 1e-12 * std::max(1.0, std::abs(vx)));
  EXPECT_EQ(std::count(f.particles.material.begin(), f.particles.material.end(), 1), 100);
  std::filesystem::remove_all(dir);
}

// Large snapshots are indexed block by block and parsed in pieces, one per thread: the same
// values and the same first bad row for any number of pieces; a snapshot after a large one is
// found where it starts.
TEST(LammpsDump, LargeSnapshotsParseInParallelAndReportTheFirstBadRow) {
  const ParticleFrame f = randomFrame(50000, 6);
  const ParticleFrame small = randomFrame(7, 8);
  std::string text = writeDump(f);
  ASSERT_GT(text.size(), 9u << 20); // large enough for the block census of indexDump
  const std::string second = writeDump(small);
  const std::string both = text + second.substr(0, second.size() - 1); // its last line unterminated
  const int threadsBefore = omp_get_max_threads();
  for (int threads : {1, 2, 3, 5}) {
    omp_set_num_threads(threads);
    const std::vector<DumpIndexEntry> index = indexDump(both, "big.dump");
    ASSERT_EQ(index.size(), 2u);
    EXPECT_EQ(index[1].offset, text.size());
    EXPECT_EQ(index[1].end, both.size());
    expectSameParticles(f.particles, parseDumpSnapshot(both, index[0], "big.dump").particles);
    expectSameParticles(small.particles, parseDumpSnapshot(both, index[1], "big.dump").particles);
    DumpIndexEntry unknownEnd = index[0]; // an entry without its end finds it again
    unknownEnd.end = 0;
    expectSameParticles(f.particles, parseDumpSnapshot(both, unknownEnd, "big.dump").particles);
  }
  // Corrupt the rows on file lines 30010 and 45010 (the later one first, so both stay put),
  // then line 20010 with one value too many.
  auto lineStart = [&](std::size_t line) {
    std::size_t pos = 0;
    for (std::size_t k = 1; k < line; ++k)
      pos = text.find('\n', pos) + 1;
    return pos;
  };
  text.insert(lineStart(45010), "x");
  text.insert(lineStart(30010), "y");
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    EXPECT_NE(dumpError(text).find("bad.dump:30010: expected an integer for id, got 'y"),
              std::string::npos)
        << dumpError(text);
  }
  text.insert(text.find('\n', lineStart(20010)), " 7");
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    EXPECT_NE(dumpError(text).find("bad.dump:20010: expected 17 values, found 18"),
              std::string::npos)
        << dumpError(text);
  }
  omp_set_num_threads(threadsBefore);
}

// Dumps written by LIGGGHTS itself (data/samples/liggghts, see its README): counts and mass as
// its thermo output printed them, velocities as free fall.
TEST(ParticleFiles, ReadsTheLiggghtsSampleSeries) {
  const std::string dir = std::string(CRATERKIT_SOURCE_DIR) + "/data/samples/liggghts/";
  for (int step : {0, 1000, 2000, 3000}) {
    const std::string path = dir + "dump." + std::to_string(step) + ".liggghts";
    const std::string text = readFileBytes(path);
    const std::vector<DumpIndexEntry> index = indexDump(text, path);
    ASSERT_EQ(index.size(), 1u);
    EXPECT_EQ(index[0].timestep, step);
    const ParticleFrame f = parseDumpSnapshot(text, index[0], path);
    if (step == 0) {
      EXPECT_EQ(f.particles.size(), 0u); // inserted at step 1
      continue;
    }
    ASSERT_EQ(f.particles.size(), 60u);
    double mass = 0.0, vz = 0.0;
    for (std::size_t i = 0; i < 60; ++i) {
      mass += f.particles.mass[i];
      vz += f.particles.velocity[3 * i + 2] / 60.0;
      EXPECT_EQ(f.particles.radius[i], 0.005);
    }
    EXPECT_NEAR(mass, 0.078539816, 1e-6); // LIGGGHTS prints 6 significant digits per atom
    // LIGGGHTS inserts at step 1 and the first kick is a full step: v = -g (step - 1/2) dt.
    EXPECT_NEAR(vz, -9.81 * (step - 0.5) * 1e-5, 2e-6);
  }
}

// FileBytes maps a plain file in place and decompresses a gzip one; both give the file's bytes,
// so .ss parsing through it equals parsing the copied bytes; errors name the file.
TEST(ParticleFiles, FileBytesMapsPlainFilesAndInflatesGzip) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ck_filebytes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const ParticleFrame f = randomFrame(100, 5);
  const std::string bytes = writeSs(f, false);
  const std::string plain = (dir / "a.ss").string();
  std::ofstream(plain, std::ios::binary) << bytes;
  {
    const FileBytes mapped(plain);
    EXPECT_EQ(mapped.view(), bytes);
    const ParticleFrame g = parseSs(mapped.view(), plain, false);
    EXPECT_EQ(g.particles.position, parseSs(bytes, plain, false).particles.position);
  }
  const std::string gz = (dir / "a.ss.gz").string();
  ASSERT_EQ(std::system(("gzip -c " + plain + " > " + gz).c_str()), 0);
  EXPECT_EQ(FileBytes(gz).view(), bytes);
  const std::string empty = (dir / "empty.ss").string();
  std::ofstream(empty).close();
  EXPECT_TRUE(FileBytes(empty).view().empty());
  EXPECT_NE(
      parseError([&] { FileBytes((dir / "missing.ss").string()); }).find("missing.ss: cannot open"),
      std::string::npos);
  EXPECT_NE(parseError([&] { FileBytes(dir.string()); }).find("not a regular file"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}
