// Checkpoint files (common/CheckpointFormat.h): the frame round-trips; for each kind (DEM, SPH,
// bonded) a real checkpoint reads back bit-identically and every one of 100 single flipped bits,
// spread over the whole file, is refused with an InputError naming the file; the version-1 files
// of tests/data/checkpoints (written by the writers before the frame) still read, with a
// warning, and a run resumed from one writes version 2; a refused resume never overwrites the
// file it could not read.
#include "common/CheckpointFormat.h"
#include "bonded/BondedRun.h"
#include "common/Error.h"
#include "dem/ContactModels.h"
#include "dem/DemCheckpoint.h"
#include "dem/DemRun.h"
#include "sph/Material.h"
#include "sph/SphCheckpoint.h"
#include "sph/SphRun.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace craterkit;

namespace {

const std::string kData = std::string(CRATERKIT_SOURCE_DIR) + "/tests/data/checkpoints/";

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("craterkit_ckfmt_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// The set-ups of the version-1 files in tests/data/checkpoints (written from these by the
// writers of format version 1, which wrote the payload alone).
//
// DEM: four grains in a row, slightly overlapping each other and a floor, 5 steps.
ParticleSet demGrains() {
  ParticleSet s;
  for (int k = 0; k < 4; ++k) {
    const double x[3] = {0.0995 * k, 0.001 * k, 0.0499};
    s.add(x, 0.05, 2000.0, k % 2, 100 + k);
  }
  return s;
}
DemParams demParams() {
  DemParams p;
  const StiffnessProposal k = proposeStiffness(0.05, 2000.0, 1.0, 0.01, 9.81, 0.1, 30.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  return p;
}
constexpr int kDemSteps = 5;

// SPH: three particles with distinct values in every array; time 2.5e-5 s, 17 steps, next
// step 1.25e-7 s.
SphState sphParticles() {
  SphState s;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) {
      s.x.push_back(0.25 * i + 0.125 * c);
      s.v.push_back(-1.5 * i + 0.5 * c);
    }
    s.mass.push_back(1.0 + i);
    s.rho.push_back(2500.0 + 10.0 * i);
    s.u.push_back(100.0 * i);
    s.h.push_back(0.03125 * (i + 1));
    for (int c = 0; c < 6; ++c)
      s.S.push_back(1000.0 * i + c);
    s.alpha.push_back(1.0 + 0.25 * i);
    s.damage.push_back(0.125 * i);
    s.material.push_back(i % 2);
  }
  return s;
}

// Bonded: three particles in a row joined by two bonds, the first one moving; step 0.
BondedSystem bondedRow() {
  BondedSystem b;
  const double sigma = 1e-4;
  b.law.sigma = sigma;
  b.law.epsilon = 1e-9;
  b.law.kappa = 10.0;
  b.law.rCut = 1.5 * sigma;
  const double req = b.law.rEq();
  for (int i = 0; i < 3; ++i) {
    b.positions.insert(b.positions.end(), {req * i, 0.0, 0.0});
    b.velocities.insert(b.velocities.end(), {i == 0 ? 10.0 : 0.0, 0.0, 0.0});
    b.masses.push_back(1e-9);
    b.body.push_back(static_cast<std::uint8_t>(i == 0 ? 0 : 1));
  }
  b.bonds.push_back({0, 1, req});
  b.bonds.push_back({1, 2, req});
  b.impactSpeed = 10.0;
  return b;
}

// A small SPH run: a 4 x 4 x 4 block of ideal gas, hotter on one side.
SphState gasBlock() {
  SphState s;
  const double dx = 0.1, rho = 1.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        const double x[3] = {dx * i, dx * j, dx * k}, v[3] = {0.0, 0.0, 0.0};
        s.add(x, v, rho * dx * dx * dx, rho, i < 2 ? 2.5 : 0.25, 0);
      }
  return s;
}
SphParams gasParams() {
  SphParams par;
  EquationOfState gas;
  gas.model = EquationOfState::Model::IdealGas;
  gas.gamma = 1.4;
  par.materials = {fluidMaterial(gas)};
  return par;
}

// Flips 100 single bits of GOOD, one at a time, one in each hundredth of the file (so that the
// header gets its share), writes each to PATH and expects read() to throw an InputError naming
// PATH; a bit of the payload must give the checksum's message. Restores GOOD at the end.
void expectEveryFlipRefused(const std::string& good, const std::string& path,
                            const std::function<void()>& read, std::uint64_t seed) {
  ASSERT_GT(good.size(), 100u);
  std::mt19937_64 random(seed);
  int header = 0;
  for (std::size_t k = 0; k < 100; ++k) {
    const std::size_t from = good.size() * k / 100, to = good.size() * (k + 1) / 100;
    std::uniform_int_distribution<std::size_t> pick(8 * from, 8 * to - 1);
    const std::size_t bit = pick(random);
    std::string bad = good;
    bad[bit / 8] = static_cast<char>(bad[bit / 8] ^ (1 << (bit % 8)));
    writeBytes(path, bad);
    header += bit / 8 < kCheckpointHeaderBytes;
    try {
      read();
      ADD_FAILURE() << "bit " << bit << " (byte " << bit / 8 << ") flipped: the file was read";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(contains(what, path)) << what;
      if (bit / 8 >= kCheckpointHeaderBytes)
        EXPECT_EQ(what, path + ": the checkpoint is corrupt (checksum mismatch)");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "bit " << bit << " flipped: not an InputError but " << e.what();
    }
  }
  EXPECT_GE(header, 1) << "no flip fell in the header";
  writeBytes(path, good);
}

} // namespace

TEST(CheckpointFormat, WriterVersionIsTheProjectVersion) {
  const std::string cmake = bytesOf(std::string(CRATERKIT_SOURCE_DIR) + "/CMakeLists.txt");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(cmake, m, std::regex(R"(project\(CraterKit VERSION ([0-9.]+))")));
  EXPECT_EQ(m[1].str(), kCraterKitVersion);
}

// The frame around a payload: header fields, the stream left at the payload, and the refusals.
TEST(CheckpointFormat, FrameRoundTripsAndRefusesDamage) {
  const CheckpointKind kind{"TEST", "test checkpoint", {'O', 'L', 'D', 'T', 'E', 'S', 'T', '1'}};
  const CheckpointKind other{"OTHER", "other checkpoint", {'O', 'T', 'H', 'E', 'R', '0', '0', '1'}};
  const std::string payload = "OLDTEST1 and the rest of a payload, any bytes \x01\x02";
  std::stringstream out;
  out << "prefix";
  writeCheckpointFrame(out, kind, [&](std::ostream& o) { o << payload; });
  const std::string framed = out.str().substr(6);
  ASSERT_EQ(framed.size(), kCheckpointHeaderBytes + payload.size());
  EXPECT_EQ(framed.substr(0, 8), "CRATERKT");
  EXPECT_EQ(framed.substr(kCheckpointHeaderBytes), payload);
  auto read = [](const std::string& bytes, const CheckpointKind& k) {
    std::istringstream in(bytes);
    const CheckpointFrame frame = readCheckpointFrame(in, bytes.size(), k);
    std::string rest(frame.payloadBytes, '\0');
    in.read(rest.data(), static_cast<std::streamsize>(rest.size()));
    EXPECT_TRUE(in) << "the stream is not left at the payload";
    return std::make_pair(frame, rest);
  };
  const auto [frame, rest] = read(framed, kind);
  EXPECT_EQ(frame.version, kCheckpointFormatVersion);
  EXPECT_EQ(frame.writer, std::string("CraterKit ") + kCraterKitVersion);
  EXPECT_EQ(rest, payload);
  EXPECT_TRUE(frame.warning.empty());
  // Version 1: the bare payload, from its own magic, with a warning.
  const auto [old, oldRest] = read(payload, kind);
  EXPECT_EQ(old.version, 1u);
  EXPECT_EQ(oldRest, payload);
  EXPECT_TRUE(contains(old.warning, "format version 1")) << old.warning;
  auto refusal = [&](const std::string& bytes, const CheckpointKind& k) {
    try {
      read(bytes, k);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_TRUE(contains(refusal(framed, other), "of kind \"TEST\"")) << refusal(framed, other);
  EXPECT_TRUE(contains(refusal(framed.substr(0, framed.size() - 1), kind), "truncated"));
  EXPECT_TRUE(contains(refusal(framed.substr(0, 40), kind), "truncated"));
  EXPECT_TRUE(contains(refusal(framed + "x", kind), "1 byte after its end"));
  EXPECT_TRUE(contains(refusal("CRATER", kind), "truncated"));
  EXPECT_TRUE(contains(refusal("not a checkpoint at all", kind), "unknown magic"));
  std::string newer = framed;
  newer[8] = 3;
  EXPECT_TRUE(contains(refusal(newer, kind), "format version 3")) << refusal(newer, kind);
  std::string flipped = framed;
  flipped[kCheckpointHeaderBytes + 3] ^= 0x10;
  EXPECT_EQ(refusal(flipped, kind), "the checkpoint is corrupt (checksum mismatch)");
  flipped = framed;
  flipped[30] ^= 0x01; // the writer's version
  EXPECT_TRUE(contains(refusal(flipped, kind), "checksum mismatch in its header"));
}

// DEM: a real checkpoint reads back bit-identically (the same state, the same bytes written
// again); 100 flipped bits are each refused.
TEST(CheckpointCorruption, DemCheckpointRefusesEveryFlippedBit) {
  DemSolver solver(demGrains(), demParams());
  for (int k = 0; k < 20; ++k)
    solver.step();
  ASSERT_GT(solver.contactPairs().size(), 0u);
  const std::string path = tempPath("flip.ckdem");
  solver.writeCheckpoint(path);
  const std::string good = bytesOf(path);
  const DemSolver back = DemSolver::readCheckpoint(path);
  EXPECT_TRUE(back.warnings().empty());
  EXPECT_EQ(back.stepCount(), solver.stepCount());
  EXPECT_EQ(back.time(), solver.time());
  EXPECT_TRUE(sameBits(back.particles().position, solver.particles().position));
  EXPECT_TRUE(sameBits(back.particles().velocity, solver.particles().velocity));
  EXPECT_TRUE(sameBits(back.particles().angularVelocity, solver.particles().angularVelocity));
  EXPECT_TRUE(sameBits(back.particles().id, solver.particles().id));
  std::ostringstream again;
  back.writeCheckpoint(again);
  EXPECT_TRUE(again.str() == good) << "the state read back writes other bytes";
  expectEveryFlipRefused(
      good, path, [&] { DemSolver::readCheckpoint(path); }, 20240601);
  expectEveryFlipRefused(
      good, path, [&] { readDemCheckpointState(path); }, 20240602);
  std::filesystem::remove(path);
}

TEST(CheckpointCorruption, SphCheckpointRefusesEveryFlippedBit) {
  SphRun run(gasBlock(), gasParams());
  const std::string path = tempPath("flip.cksph");
  run.advanceTo(0.2, {}, path, 1);
  const std::string good = bytesOf(path);
  double time = 0.0, next = 0.0;
  std::size_t steps = 0;
  std::string warning = "unset";
  const SphState back = readSphCheckpoint(path, time, steps, next, &warning);
  const SphState& s = run.solver().state();
  EXPECT_TRUE(warning.empty()) << warning;
  EXPECT_GT(run.solver().steps(), 0u);
  EXPECT_EQ(steps, run.solver().steps());
  EXPECT_EQ(time, run.solver().time());
  EXPECT_EQ(next, run.solver().stableStep());
  EXPECT_TRUE(sameBits(back.x, s.x) && sameBits(back.v, s.v) && sameBits(back.mass, s.mass) &&
              sameBits(back.rho, s.rho) && sameBits(back.u, s.u) && sameBits(back.h, s.h) &&
              sameBits(back.S, s.S) && sameBits(back.alpha, s.alpha) &&
              sameBits(back.damage, s.damage) && back.material == s.material);
  expectEveryFlipRefused(
      good, path, [&] { readSphCheckpoint(path, time, steps, next); }, 20240603);
  std::filesystem::remove(path);
}

TEST(CheckpointCorruption, BondedCheckpointRefusesEveryFlippedBit) {
  BondedSolver solver(bondedRow());
  solver.advance(30);
  const std::string path = tempPath("flip.ckbonded");
  solver.writeCheckpoint(path);
  const std::string good = bytesOf(path);
  const BondedSolver back = BondedSolver::readCheckpoint(path);
  EXPECT_TRUE(back.warnings().empty());
  EXPECT_EQ(back.stepCount(), solver.stepCount());
  EXPECT_TRUE(sameBits(back.system().positions, solver.system().positions));
  EXPECT_TRUE(sameBits(back.system().velocities, solver.system().velocities));
  EXPECT_TRUE(sameBits(back.forces(), solver.forces()));
  const std::string copy = tempPath("flip_again.ckbonded");
  back.writeCheckpoint(copy);
  EXPECT_TRUE(bytesOf(copy) == good) << "the state read back writes other bytes";
  std::filesystem::remove(copy);
  expectEveryFlipRefused(
      good, path, [&] { BondedSolver::readCheckpoint(path); }, 20240604);
  std::filesystem::remove(path);
}

// The bonded checkpoint holds the shock heating (its parameters and each particle's internal
// energy): a run restored mid-heating continues bit for bit.
TEST(CheckpointCorruption, BondedCheckpointKeepsTheShockHeating) {
  BondedSolverParams params;
  params.dissipation = BondedDissipation::ShockViscosity;
  params.shockViscosityThreshold = 1.0; // m/s: the first particle closes in at 10 m/s
  BondedSolver solver(bondedRow(), params);
  const auto heat = [](const BondedSolver& b) {
    double sum = 0.0;
    for (double e : b.internalEnergy())
      sum += e;
    return sum;
  };
  for (int k = 0; k < 2000 && heat(solver) == 0.0; ++k)
    solver.step();
  ASSERT_GT(heat(solver), 0.0);
  const std::string path = tempPath("heating.ckbonded");
  solver.writeCheckpoint(path);
  BondedSolver back = BondedSolver::readCheckpoint(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.dissipationInterval(), solver.dissipationInterval());
  EXPECT_TRUE(sameBits(back.internalEnergy(), solver.internalEnergy()));
  solver.advance(100);
  back.advance(100);
  EXPECT_TRUE(sameBits(back.system().positions, solver.system().positions));
  EXPECT_TRUE(sameBits(back.system().velocities, solver.system().velocities));
  EXPECT_TRUE(sameBits(back.internalEnergy(), solver.internalEnergy()));
}

// The version-1 files (no frame, no checksum) read as before, with a warning naming the file.
TEST(CheckpointOldFormat, SphVersion1ReadsWithAWarning) {
  const std::string path = kData + "version1.cksph";
  const std::string old = bytesOf(path);
  ASSERT_EQ(old.substr(0, 8), std::string("CKSPH1\n\0", 8));
  double time = 0.0, next = 0.0;
  std::size_t steps = 0;
  std::string warning;
  const SphState s = readSphCheckpoint(path, time, steps, next, &warning);
  const SphState want = sphParticles();
  EXPECT_TRUE(sameBits(s.x, want.x) && sameBits(s.v, want.v) && sameBits(s.mass, want.mass) &&
              sameBits(s.rho, want.rho) && sameBits(s.u, want.u) && sameBits(s.h, want.h) &&
              sameBits(s.S, want.S) && sameBits(s.alpha, want.alpha) &&
              sameBits(s.damage, want.damage) && s.material == want.material);
  EXPECT_EQ(time, 2.5e-5);
  EXPECT_EQ(steps, 17u);
  EXPECT_EQ(next, 1.25e-7);
  EXPECT_TRUE(contains(warning, path) && contains(warning, "format version 1")) << warning;
  // Version 2 holds the same payload after its header.
  const std::string now = tempPath("v2.cksph");
  writeSphCheckpoint(now, want, 2.5e-5, 17, 1.25e-7);
  EXPECT_TRUE(bytesOf(now).substr(kCheckpointHeaderBytes) == old);
  std::filesystem::remove(now);
}

TEST(CheckpointOldFormat, DemVersion1ReadsWithAWarningAndIsRewrittenAsVersion2) {
  const std::string fixture = kData + "version1.ckdem";
  ASSERT_EQ(bytesOf(fixture).substr(0, 8), "CKDEMCP1");
  const DemCheckpointState state = readDemCheckpointState(fixture);
  ASSERT_EQ(state.warnings.size(), 1u);
  EXPECT_TRUE(contains(state.warnings[0], fixture) &&
              contains(state.warnings[0], "format version 1"))
      << state.warnings[0];
  EXPECT_EQ(state.step, kDemSteps);
  // The grains, by their ids, where a run of the same set-up has them.
  DemSolver straight(demGrains(), demParams());
  for (int k = 0; k < kDemSteps; ++k)
    straight.step();
  const ParticleSet& s = straight.particles();
  ASSERT_EQ(state.particles.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = 0; j < s.size(); ++j)
      if (state.particles.id[j] == s.id[i])
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(state.particles.position[3 * j + c], s.position[3 * i + c], 1e-12);
  EXPECT_EQ(DemSolver::readCheckpoint(fixture).contactPairs().size(), 3u);

  // A run resumed from it warns, continues, and writes version 2 at its next checkpoint.
  const std::string path = tempPath("v1.ckdem");
  writeBytes(path, bytesOf(fixture));
  DemRun run(demGrains(), demParams(), 0.0, 0);
  run.resumeFrom(path);
  ASSERT_FALSE(run.solver().warnings().empty());
  EXPECT_TRUE(contains(run.solver().warnings().back(), "format version 1"));
  run.advanceTo((kDemSteps + 3) * demParams().dt, {}, path, 1);
  EXPECT_EQ(bytesOf(path).substr(0, 8), "CRATERKT");
  EXPECT_TRUE(readDemCheckpointState(path).warnings.empty());
  std::filesystem::remove(path);
}

TEST(CheckpointOldFormat, BondedVersion1ReadsWithAWarning) {
  const std::string fixture = kData + "version1.ckbonded";
  ASSERT_EQ(bytesOf(fixture).substr(0, 8), "CKBOND01");
  const BondedSolver solver = BondedSolver::readCheckpoint(fixture);
  const BondedSystem want = bondedRow();
  EXPECT_EQ(solver.stepCount(), 0u);
  EXPECT_TRUE(sameBits(solver.system().positions, want.positions));
  EXPECT_TRUE(sameBits(solver.system().velocities, want.velocities));
  EXPECT_TRUE(sameBits(solver.system().masses, want.masses));
  ASSERT_EQ(solver.system().bonds.size(), 2u);
  EXPECT_EQ(solver.system().bonds[1].j, 2u);
  EXPECT_EQ(solver.dissipationInterval(), 0u); // version 1: the paper's model, no heating
  EXPECT_TRUE(std::all_of(solver.internalEnergy().begin(), solver.internalEnergy().end(),
                          [](double e) { return e == 0.0; }));
  ASSERT_EQ(solver.warnings().size(), 1u);
  EXPECT_TRUE(contains(solver.warnings()[0], fixture) &&
              contains(solver.warnings()[0], "format version 1"))
      << solver.warnings()[0];
  BondedRun run(want);
  run.resumeFrom(fixture);
  EXPECT_EQ(run.solver().warnings(), solver.warnings());
}

// A resume refused for a failed checksum names the file, and the run, if it goes on anyway
// (from its initial state), never writes over the file it could not read.
TEST(CheckpointResume, RefusedResumeNeverOverwritesTheFile) {
  auto damage = [](const std::string& path) {
    std::string bytes = bytesOf(path);
    bytes[bytes.size() / 2] ^= 0x04;
    writeBytes(path, bytes);
    return bytes;
  };
  auto expectRefused = [](const std::function<void()>& resume, const std::string& path) {
    try {
      resume();
      ADD_FAILURE() << "a damaged checkpoint was resumed from";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": the checkpoint is corrupt (checksum mismatch)");
    }
  };
  {
    const std::string path = tempPath("resume.ckdem");
    const double dt = demParams().dt;
    DemRun(demGrains(), demParams(), 0.0, 0).advanceTo(10 * dt, {}, path, 5);
    const std::string bad = damage(path);
    DemRun run(demGrains(), demParams(), 0.0, 0);
    expectRefused([&] { run.resumeFrom(path); }, path);
    run.advanceTo(30 * dt, {}, path, 5);
    EXPECT_EQ(run.solver().stepCount(), 30);
    EXPECT_TRUE(bytesOf(path) == bad) << "the DEM checkpoint was overwritten";
    std::filesystem::remove(path);
  }
  {
    const std::string path = tempPath("resume.cksph");
    SphRun(gasBlock(), gasParams()).advanceTo(0.1, {}, path, 1);
    const std::string bad = damage(path);
    SphRun run(gasBlock(), gasParams());
    expectRefused([&] { run.resumeFrom(path); }, path);
    run.advanceTo(0.2, {}, path, 1);
    EXPECT_DOUBLE_EQ(run.time(), 0.2);
    EXPECT_TRUE(bytesOf(path) == bad) << "the SPH checkpoint was overwritten";
    std::filesystem::remove(path);
  }
  {
    const std::string path = tempPath("resume.ckbonded");
    BondedRun first(bondedRow());
    const double dt = first.solver().timeStep();
    first.advanceTo(20 * dt, {}, path, 10);
    const std::string bad = damage(path);
    BondedRun run(bondedRow());
    expectRefused([&] { run.resumeFrom(path); }, path);
    run.advanceTo(40 * dt, {}, path, 10);
    EXPECT_EQ(run.solver().stepCount(), 40u);
    EXPECT_TRUE(bytesOf(path) == bad) << "the bonded checkpoint was overwritten";
    std::filesystem::remove(path);
  }
}
