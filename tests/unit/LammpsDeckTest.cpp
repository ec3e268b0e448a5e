// LAMMPS decks (dem/LammpsDeck.h): the data file's round trip is exact, bad input is refused by
// name, and small decks run in LAMMPS as CraterKit's DEM does (skipped without `lmp`).
#include "dem/LammpsDeck.h"
#include "common/Container.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"
#include "io/FileBytes.h"
#include "io/LammpsDump.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>

using namespace craterkit;

namespace {

bool haveLammps() { return std::system("command -v lmp > /dev/null 2>&1") == 0; }

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

ParticleSet randomState(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ParticleSet s;
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {u(rng) * 3.7, u(rng) * 1e-3, u(rng) * 1e4};
    // Ids out of order and sparse, as after a Morton sort and a removal.
    s.add(x, 0.01 + 0.005 * (u(rng) + 1.0), 2500.0 + u(rng), static_cast<int>(i % 3),
          static_cast<std::int64_t>((i * 7919) % (3 * n)));
    for (int k = 0; k < 3; ++k) {
      s.velocity[3 * i + k] = u(rng) * std::pow(10.0, 3 * k - 3);
      s.angularVelocity[3 * i + k] = u(rng) * 1e2 / 3.0;
    }
  }
  return s;
}

LammpsDeckParams simpleParams(double dt) {
  LammpsDeckParams p;
  p.dem.gravity.type = Gravity::Type::None;
  p.dem.dt = dt;
  p.outputTimes = {100 * dt};
  return p;
}

std::string tempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("craterkit-deck-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

// Runs DIR's deck on one rank (bounded: a stale MPI start can hang) and returns the last
// snapshot of its dump.
ParticleFrame runDeck(const std::string& dir) {
  const std::string cmd =
      "cd '" + dir + "' && timeout 120 lmp -log none -screen none -in in.craterkit";
  if (std::system(cmd.c_str()) != 0)
    throw std::runtime_error("LAMMPS failed: " + cmd);
  const std::string text = readFileBytes(dir + "/dump.craterkit");
  const auto index = indexDump(text, "dump.craterkit");
  return parseDumpSnapshot(text, index.back(), "dump.craterkit");
}

// Velocity of the particle with CraterKit Id ID in a frame from LAMMPS (atom id = Id + 1).
const double* velocityOf(const ParticleFrame& f, std::int64_t id) {
  for (std::size_t i = 0; i < f.particles.size(); ++i)
    if (f.particles.id[i] == id + 1)
      return &f.particles.velocity[3 * i];
  throw std::runtime_error("atom missing from the dump");
}

} // namespace

TEST(LammpsDeck, DataFileRoundTripIsBitExact) {
  const ParticleSet s = randomState(500);
  LammpsDeckParams p = simpleParams(1e-5);
  const ParticleSet back = parseLammpsData(lammpsDataFile(s, p), "data.craterkit");
  ASSERT_EQ(back.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(back.id[i], s.id[i]);
    EXPECT_EQ(back.material[i], s.material[i]);
    EXPECT_TRUE(sameBits(back.radius[i], s.radius[i])) << i;
    // LAMMPS' mass is 4π/3 r³ ρ with ρ from CraterKit's mass: equal to rounding.
    EXPECT_NEAR(back.mass[i], s.mass[i], 4e-16 * s.mass[i]) << i;
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(sameBits(back.position[3 * i + k], s.position[3 * i + k])) << i << " " << k;
      EXPECT_TRUE(sameBits(back.velocity[3 * i + k], s.velocity[3 * i + k])) << i << " " << k;
      EXPECT_TRUE(sameBits(back.angularVelocity[3 * i + k], s.angularVelocity[3 * i + k]));
    }
  }
}

TEST(LammpsDeck, RefusesWhatLammpsCannotRun) {
  const ParticleSet s = randomState(10);
  auto refuses = [&](const LammpsDeckParams& p, const ParticleSet& set, const char* word) {
    try {
      (void)lammpsInputDeck(set, p);
      (void)lammpsDataFile(set, p);
      ADD_FAILURE() << "accepted; expected a refusal naming " << word;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  LammpsDeckParams p = simpleParams(1e-5);
  p.dem.walls = {Wall::disk({0, 0, 0}, {0, 0, 1}, 1.0)};
  refuses(p, s, "disk");
  p = simpleParams(1e-5);
  p.dem.contact.cohesion = 10.0;
  refuses(p, s, "cohesion");
  p = simpleParams(1e-5);
  p.dem.gravity.type = Gravity::Type::PointMass;
  p.dem.gravity.GM = 1.0;
  refuses(p, s, "point-mass");
  p = simpleParams(1e-5);
  p.outputTimes = {1e-3, 1e-3};
  refuses(p, s, "output time");
  p = simpleParams(1e-5);
  p.dem.contact.restitutionN = 0.14; // beyond Tsuji's range once clipped
  refuses(p, s, "Tsuji");
  p = simpleParams(1e-5);
  p.dem.walls = {Wall::cylinder({0, 0, 0}, {0.6, 0, 0.8}, 1.0)};
  refuses(p, s, "cylinder");
  ParticleSet dup = s;
  dup.id[3] = dup.id[4];
  refuses(simpleParams(1e-5), dup, "duplicate Id");
  dup = s;
  dup.id[2] = -5;
  refuses(simpleParams(1e-5), dup, "Id -5");
}

TEST(LammpsDeck, TsujiInverse) {
  for (double a : {0.05, 0.3, 0.4637, 0.9, 1.2})
    EXPECT_NEAR(tsujiAlpha(tsujiRestitutionFor(a)), a, 1e-12);
}

// Unequal grains head-on and a grain bouncing on a wall, for both normal laws: LAMMPS' Tsuji
// damping gives CraterKit's clipped rebound for any masses, the wall's with a partner of
// infinite mass (Hertz: `hertz` + `mindlin` with the wall's E* = E/(1-ν²)).
TEST(LammpsDeck, UnequalPairAndWallReboundAsInCraterKit) {
  if (!haveLammps())
    GTEST_SKIP() << "LAMMPS (lmp, Debian package lammps) is not installed";
  ParticleSet s;
  const double a[3] = {0, 0, 0.5}, b[3] = {0.1305, 0, 0.5}, c[3] = {0.5, 0, 0.0502};
  s.add(a, 0.05, 2000, 0, 0);
  s.add(b, 0.08, 2000, 0, 1);
  s.add(c, 0.05, 2000, 0, 2);
  s.velocity[0] = 1.0;          // 0 towards 1
  s.velocity[3 * 2 + 2] = -1.0; // 2 onto the floor
  for (const char* law : {"LinearSpringDashpot", "Hertz"}) {
    LammpsDeckParams p;
    p.dem.gravity.type = Gravity::Type::None;
    p.dem.contact.normalModel = law;
    p.dem.contact.kN = 1e6;
    p.dem.contact.muS = 0.3;
    p.dem.walls = {Wall::plane({0, 0, 0}, {0, 0, 1})};
    const double m = 2000 * 4.0 / 3.0 * M_PI * std::pow(0.05, 3);
    // Linear: 100 steps per collision; Hertz (E = 1e8 Pa): about 200.
    p.dem.dt = std::string(law) == "Hertz" ? 2e-5 : M_PI * std::sqrt(0.5 * m / 1e6) / 100.0;
    p.outputTimes = {0.04};
    const std::string dir = tempDir("rebound");
    writeLammpsDeck(dir, s, p);
    const ParticleFrame lmp = runDeck(dir);
    DemSolver solver(s, p.dem);
    solver.advanceTo(0.04);
    const ParticleSet& ours = solver.particles();
    for (std::size_t i = 0; i < ours.size(); ++i) {
      const double* v = velocityOf(lmp, ours.id[i]);
      for (int k = 0; k < 3; ++k) // within 0.3 % of the impact speed (measured 0.1 %)
        EXPECT_NEAR(ours.velocity[3 * i + k], v[k], 0.003)
            << law << " Id " << ours.id[i] << " axis " << k;
    }
    std::filesystem::remove_all(dir);
  }
}

// The bowl container (sphere region's lower half + the cylinder above the rim) holds a grain
// that falls into it from above the rim, as CraterKit's bowl walls do.
TEST(LammpsDeck, BowlHoldsAFallingGrain) {
  if (!haveLammps())
    GTEST_SKIP() << "LAMMPS (lmp, Debian package lammps) is not installed";
  Container bowl;
  bowl.type = Container::Type::Bowl;
  bowl.bowlRadius = 1.0;
  ParticleSet s;
  const double x[3] = {0.5, 0.2, 0.3};
  s.add(x, 0.05, 2000, 0, 0);
  LammpsDeckParams p;
  p.dem.walls = containerWalls(bowl);
  p.dem.contact.kN = 1e5;
  p.dem.gravity.vector = {0, 0, -9.81};
  const double m = s.mass[0];
  p.dem.dt = M_PI * std::sqrt(m / 1e5) / 50.0;
  p.outputTimes = {1.5};
  const std::string dir = tempDir("bowl");
  writeLammpsDeck(dir, s, p);
  const ParticleFrame lmp = runDeck(dir);
  ASSERT_EQ(lmp.particles.size(), 1u);
  const double* y = &lmp.particles.position[0];
  const double dist = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  EXPECT_LT(y[2], 0.0);          // fell below the rim
  EXPECT_NEAR(dist, 0.95, 0.01); // and rests on the sphere's inside
  std::filesystem::remove_all(dir);
}
