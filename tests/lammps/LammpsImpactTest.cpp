// The same small impact in CraterKit's DEM and in LAMMPS (2 MPI ranks) from the deck that
// dem/LammpsDeck writes (issue 34, item 5): a steel sphere into a settled box bed of about
// 1,100 grains. Compared: the total momentum while and after the impactor's contact phase
// (within 5 % of the impactor's momentum), the impactor's penetration, and the crater of
// analysis/CraterProfile (diameter and depth within 10 %; the azimuthally averaged surface
// profile within a grain radius). Prints every figure, and the rates in particle-steps/s.
// Skipped without `lmp`. ctest label `lammps`.
#include "analysis/CraterProfile.h"
#include "bed/GranularBed.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"
#include "dem/Impactor.h"
#include "dem/LammpsDeck.h"
#include "io/FileBytes.h"
#include "io/LammpsDump.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

using namespace craterkit;

namespace {

// The impact's share of the total momentum agrees within this fraction of the impactor's,
// plus twice the spread of CraterKit against itself with the impactor moved by 1 nm.
constexpr double kMomentumTolerance = 0.05;

struct Snapshot {
  double time;
  Eigen::Vector3d momentum;
  double impactorZ;
  ParticleSet state;
};

Eigen::Vector3d momentum(const ParticleSet& p) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k)
      m[k] += p.mass[i] * p.velocity[3 * i + k];
  return m;
}

double zOf(const ParticleSet& p, std::int64_t id) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == id)
      return p.position[3 * i + 2];
  return NAN; // the bed-only runs
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

CraterProfileResult crater(const ParticleSet& p, std::int64_t impactor, double z0) {
  ParticleSet bed; // the impactor is not part of the surface
  std::vector<double> x, r;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] != impactor) {
      x.insert(x.end(), &p.position[3 * i], &p.position[3 * i + 3]);
      r.push_back(p.radius[i]);
    }
  CraterProfileParams c;
  c.maxRadius = 0.4;
  c.radialBins = 8;
  c.azimuthalBins = 8;
  c.surfaceHeight = z0;
  return craterProfile(x, r, c);
}

std::vector<Snapshot> runCraterKit(const ParticleSet& state, const LammpsDeckParams& deck,
                                   std::int64_t impactorId) {
  std::vector<Snapshot> out;
  DemSolver solver(state, deck.dem);
  for (double t : deck.outputTimes) {
    solver.advanceTo(t);
    const ParticleSet& s = solver.particles();
    out.push_back({solver.time(), momentum(s), zOf(s, impactorId), s});
  }
  return out;
}

// MPI ranks of the LAMMPS runs: 2, or CRATERKIT_LAMMPS_RANKS (for rate measurements).
std::string ranks() {
  const char* r = std::getenv("CRATERKIT_LAMMPS_RANKS");
  return r ? std::to_string(std::max(1, std::atoi(r))) : "2";
}

// Writes the deck into DIR, runs it on 2 ranks through scripts/run-lammps and reads the dumps.
std::vector<Snapshot> runLammps(const std::string& dir, const ParticleSet& state,
                                const LammpsDeckParams& deck, std::int64_t impactorId) {
  writeLammpsDeck(dir, state, deck);
  const std::string cmd = std::string("'") + CRATERKIT_SOURCE_DIR + "/scripts/run-lammps' '" + dir +
                          "' " + ranks() + " > '" + dir + "/run.txt' 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream runOut(dir + "/run.txt");
  std::cout << runOut.rdbuf();
  if (rc != 0)
    throw std::runtime_error("failed: " + cmd);
  const std::string text = readFileBytes(dir + "/dump.craterkit");
  const auto index = indexDump(text, "dump.craterkit");
  if (index.size() != deck.outputTimes.size())
    throw std::runtime_error("the dump misses output times");
  std::vector<Snapshot> out;
  for (std::size_t k = 0; k < index.size(); ++k) {
    ParticleFrame f = parseDumpSnapshot(text, index[k], "dump.craterkit");
    for (auto& id : f.particles.id)
      id -= 1; // atom id = Id + 1
    out.push_back({f.time, momentum(f.particles), zOf(f.particles, impactorId), f.particles});
  }
  std::filesystem::remove_all(dir);
  return out;
}

} // namespace

// Crater measures and the surface profile of the three final states.
void compareCraters(const ParticleSet& initial, const ParticleSet& ours, const ParticleSet& theirs,
                    const ParticleSet& nudged, std::int64_t impactorId) {
  // z0: the mean height of the bed's surface before the impact.
  const CraterProfileResult before = crater(initial, impactorId, 0.0);
  double z0 = 0.0;
  int bins = 0;
  for (double h : before.height)
    if (std::isfinite(h)) {
      z0 += h;
      ++bins;
    }
  z0 /= bins;
  const CraterProfileResult a = crater(ours, impactorId, z0), b = crater(theirs, impactorId, z0),
                            c = crater(nudged, impactorId, z0);
  std::printf("crater (z0 %.4f m; CraterKit / LAMMPS / CraterKit nudged): found %d/%d/%d  "
              "diameter %.4f / %.4f / %.4f m  depth %.4f / %.4f / %.4f m\n",
              z0, a.all.found, b.all.found, c.all.found, a.all.diameter, b.all.diameter,
              c.all.diameter, a.all.depth, b.all.depth, c.all.depth);
  double worst = 0.0;
  for (std::size_t k = 0; k < a.height.size(); ++k) {
    std::printf("  r %.3f  h %.4f / %.4f / %.4f (before %.4f)\n", a.radius[k], a.height[k],
                b.height[k], c.height[k], before.height[k]);
    if (std::isfinite(a.height[k]) && std::isfinite(b.height[k]))
      worst = std::max(worst, std::abs(a.height[k] - b.height[k]));
  }
  std::printf("surface profile: largest difference %.4f m (grain radius 0.03 m)\n", worst);
  EXPECT_LT(worst, 0.03); // within a grain radius
  ASSERT_TRUE(a.all.found && b.all.found);
  EXPECT_NEAR(b.all.diameter, a.all.diameter, 0.10 * a.all.diameter);
  EXPECT_NEAR(b.all.depth, a.all.depth, 0.10 * a.all.depth);
}

TEST(LammpsImpact, CraterKitAndLammpsAgree) {
  if (std::system("command -v lmp > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "LAMMPS (lmp, Debian package lammps) is not installed";
  // The bed: a settled RCP box bed (seeded: the same for every run).
  GranularBedParams bedParams;
  bedParams.container.type = Container::Type::Box;
  bedParams.container.boxSize = {0.9, 0.9, 0.3};
  bedParams.sizes.type = SizeDistribution::Type::Uniform;
  bedParams.sizes.minRadius = 0.027;
  bedParams.sizes.maxRadius = 0.033;
  auto t0 = std::chrono::steady_clock::now();
  GranularBedReport report;
  const ParticleSet bed = generateGranularBed(bedParams, &report);
  std::printf("bed: %zu grains, settled %d in %.1f s\n", bed.size(), report.settled ? 1 : 0,
              seconds(t0));
  ParticleSet state = bed;
  ImpactorParams imp;
  imp.radius = 0.06;
  imp.density = 7800.0;
  imp.speed = 1.0;
  imp.target[2] = report.topHeight;
  const std::size_t ii = addImpactor(state, imp);
  const std::int64_t impactorId = state.id[ii];
  const double p0 = state.mass[ii] * imp.speed;

  LammpsDeckParams deck;
  deck.dem.walls = containerWalls(bedParams.container);
  deck.dem.gravity.vector = {0, 0, -9.81};
  // Stiff enough that the impactor-grain overlap stays near 7 % of a grain radius (the
  // lever arms of the two codes differ with the overlap).
  deck.dem.contact.kN = 5e7;
  deck.dem.dt = 6e-6;
  deck.outputTimes = {0.02, 0.05, 0.1, 0.15, 0.25};
  const std::string dir = (std::filesystem::temp_directory_path() /
                           ("craterkit-lammps-impact-" + std::to_string(::getpid())))
                              .string();
  const long long steps = std::llround(deck.outputTimes.back() / deck.dem.dt);
  const double work = static_cast<double>(state.size()) * static_cast<double>(steps);

  t0 = std::chrono::steady_clock::now();
  const std::vector<Snapshot> ours = runCraterKit(state, deck, impactorId);
  const double ckSeconds = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const std::vector<Snapshot> theirs = runLammps(dir, state, deck, impactorId);
  const double lmpSeconds = seconds(t0);
  const char* threads = std::getenv("OMP_NUM_THREADS");
  std::printf("rates (particle-steps/s): CraterKit %.3g (OMP_NUM_THREADS %s), LAMMPS %.3g "
              "(%s ranks, incl. start-up)\n",
              work / ckSeconds, threads ? threads : "unset", ranks().c_str(), work / lmpSeconds);
  std::printf("steps %lld, particles %zu\n", steps, state.size());
  // The bed alone in each code: its own settling under the floor's support moves more
  // momentum than the impact, so the impact's share is the difference of the two runs.
  const std::vector<Snapshot> oursBed = runCraterKit(bed, deck, -1);
  const std::vector<Snapshot> theirsBed = runLammps(dir + "-bed", bed, deck, -1);
  // The noise floor: CraterKit again with the impactor moved by 1 nm.
  ParticleSet nudged = state;
  nudged.position[3 * ii] += 1e-9;
  const std::vector<Snapshot> again = runCraterKit(nudged, deck, impactorId);

  for (std::size_t k = 0; k < ours.size(); ++k) {
    EXPECT_NEAR(theirs[k].time, ours[k].time, 1e-9); // the same number of steps
    const Eigen::Vector3d a = (ours[k].momentum - oursBed[k].momentum) / p0;
    const Eigen::Vector3d b = (theirs[k].momentum - theirsBed[k].momentum) / p0;
    const Eigen::Vector3d c = (again[k].momentum - oursBed[k].momentum) / p0;
    std::printf("t %.2f s  impact momentum / p0: CraterKit (%+.4f %+.4f %+.4f) LAMMPS "
                "(%+.4f %+.4f %+.4f)  |diff| %.4f (nudged %.4f)  bed-only |diff| %.4f  "
                "impactor z %.4f / %.4f / nudged %.4f m\n",
                ours[k].time, a[0], a[1], a[2], b[0], b[1], b[2], (a - b).norm(), (a - c).norm(),
                (oursBed[k].momentum - theirsBed[k].momentum).norm() / p0, ours[k].impactorZ,
                theirs[k].impactorZ, again[k].impactorZ);
    // A dense impact is chaotic: LAMMPS cannot agree better than CraterKit with itself.
    EXPECT_LT((a - b).norm(), kMomentumTolerance + 2.0 * (a - c).norm())
        << "impact momentum at t " << ours[k].time;
  }
  compareCraters(state, ours.back().state, theirs.back().state, again.back().state, impactorId);
}
