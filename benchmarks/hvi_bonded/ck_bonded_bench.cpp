// CraterKit side of the bonded hypervelocity benchmark (see run.py beside this file): the
// headline impact of Watson & Steinhauser 2017 (seed 003) at a chosen particle count.
//   ck_bonded_bench lammps-deck DIR PARTICLES STEPS WARMUP
//                                          write the set-up as the LAMMPS deck CraterKit's writer
//                                          makes (bonded/BondedLammpsDeck.h, Eq. 4's pull-only
//                                          bond table: DIR/in.craterkit, data.craterkit,
//                                          bond.table), running WARMUP steps and then STEPS
//                                          more, and print the law and time step
//   ck_bonded_bench run PARTICLES STEPS [WARMUP]
//                                          run WARMUP untimed steps, then STEPS timed ones of
//                                          the same set-up; print timings
//   ck_bonded_bench checkpoint FILE PARTICLES STEPS
//                                          advance the set-up STEPS steps (into the impact) and
//                                          write the solver's checkpoint to FILE
//   ck_bonded_bench continue FILE STEPS    advance the checkpoint FILE STEPS more steps, rewrite it
//   ck_bonded_bench resume FILE STEPS      time STEPS steps from the checkpoint FILE: a window
//                                          inside the impact without repeating the steps to it
// All print one JSON object on the last line; checkpoint, continue and resume also a hash of the
// final positions and velocities (equal hashes: bit-identical states).
#include "bonded/BondedBody.h"
#include "bonded/BondedLammpsDeck.h"
#include "bonded/BondedSolver.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

using namespace craterkit;

namespace {

BondedSystem headline(double particles) {
  BondedImpactParams p; // the paper's headline case: 9.53 mm Al sphere, 6.7 km/s, t/D 0.425
  p.particleCount = particles;
  return buildBondedImpact(p);
}

// FNV-1a over the bytes of the positions and velocities.
std::uint64_t stateHash(const BondedSystem& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const std::vector<double>* v : {&s.positions, &s.velocities})
    for (double d : *v) {
      unsigned char bytes[sizeof d];
      std::memcpy(bytes, &d, sizeof d);
      for (unsigned char c : bytes)
        h = (h ^ c) * 1099511628211ULL;
    }
  return h;
}

// The checkpoint modes: checkpoint / continue write FILE after advancing, resume times the steps.
int checkpointMode(const std::string& mode, int argc, char** argv) {
  const std::string path = argv[2];
  if (mode == "checkpoint" && argc < 5) {
    std::cerr << "usage: ck_bonded_bench checkpoint FILE PARTICLES STEPS\n";
    return 2;
  }
  const long steps = std::max(0L, std::atol(argv[mode == "checkpoint" ? 4 : 3]));
  const auto t0 = std::chrono::steady_clock::now();
  BondedSolver solver = mode == "checkpoint" ? BondedSolver(headline(std::atof(argv[3])))
                                             : BondedSolver::readCheckpoint(path);
  const std::size_t brokenBefore = solver.brokenBonds(), buildsBefore = solver.listBuilds();
  const std::size_t measuredBefore = solver.listMeasurements();
  const auto start = std::chrono::steady_clock::now();
  solver.advance(static_cast<std::size_t>(steps));
  const auto end = std::chrono::steady_clock::now();
  if (mode != "resume")
    solver.writeCheckpoint(path);
  const double seconds = std::chrono::duration<double>(end - start).count();
  const std::size_t n = solver.system().size();
  std::printf("{\"mode\": \"%s\", \"particles\": %zu, \"step\": %llu, \"time\": %.6g, "
              "\"steps\": %ld, \"threads\": %d, \"setup_seconds\": %.6g, "
              "\"loop_seconds\": %.6g, \"steps_per_s\": %.6g, \"particle_steps_per_s\": %.6g, "
              "\"list_builds\": %zu, \"list_measurements\": %zu, \"broken_bonds\": %zu, "
              "\"broken_timed\": %zu, \"compact_lists\": %s, "
              "\"state_hash\": \"%016llx\"}\n",
              mode.c_str(), n, static_cast<unsigned long long>(solver.stepCount()), solver.time(),
              steps, omp_get_max_threads(), std::chrono::duration<double>(start - t0).count(),
              seconds, steps / seconds, static_cast<double>(n) * steps / seconds,
              solver.listBuilds() - buildsBefore, solver.listMeasurements() - measuredBefore,
              solver.brokenBonds(), solver.brokenBonds() - brokenBefore,
              solver.compactLists() ? "true" : "false",
              static_cast<unsigned long long>(stateHash(solver.system())));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: ck_bonded_bench lammps-deck DIR PARTICLES STEPS WARMUP | "
                 "run PARTICLES STEPS [WARMUP] | checkpoint FILE PARTICLES STEPS | "
                 "continue FILE STEPS | resume FILE STEPS\n";
    return 2;
  }
  const std::string mode = argv[1];
  if (mode == "checkpoint" || mode == "continue" || mode == "resume")
    return checkpointMode(mode, argc, argv);
  if (mode == "lammps-deck") {
    if (argc < 6) {
      std::cerr << "usage: ck_bonded_bench lammps-deck DIR PARTICLES STEPS WARMUP\n";
      return 2;
    }
    const BondedSystem s = headline(std::atof(argv[3]));
    const long steps = std::atol(argv[4]), warmup = std::max(0L, std::atol(argv[5]));
    const BondedSolver solver(s); // its time step: the paper's 1e-10 s scaled with sigma
    BondedDeckParams deck;        // the default bond style: Eq. 4, as BondedSolver
    deck.timeStep = solver.timeStep();
    // The deck runs to each output time in turn: WARMUP steps, then the STEPS timed ones.
    if (warmup > 0)
      deck.outputTimes.push_back(static_cast<double>(warmup) * deck.timeStep);
    deck.outputTimes.push_back(static_cast<double>(warmup + steps) * deck.timeStep);
    writeBondedLammpsDeck(argv[2], s, {}, deck);
    std::printf("{\"input\": \"%s\", \"particles\": %zu, \"bonds\": %zu, \"sigma\": %.17g, "
                "\"epsilon\": %.17g, \"kappa\": %.17g, \"r_cut\": %.17g, \"r_eq\": %.17g, "
                "\"dt\": %.17g}\n",
                deck.inputFile.c_str(), s.size(), s.bonds.size(), s.law.sigma, s.law.epsilon,
                s.law.kappa, s.law.rCut, s.law.rEq(), solver.timeStep());
    return 0;
  }
  const long steps = std::atol(argv[3]);
  BondedSolver solver(headline(std::atof(argv[2])));
  const BondedEnergies e0 = solver.energies();
  if (argc > 4)
    solver.advance(static_cast<std::size_t>(std::max(0L, std::atol(argv[4]))));
  const std::size_t brokenBefore = solver.brokenBonds();
  const auto start = std::chrono::steady_clock::now();
  solver.advance(static_cast<std::size_t>(steps));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const BondedEnergies e = solver.energies();
  const std::size_t n = solver.system().size();
  std::printf("{\"particles\": %zu, \"steps\": %ld, \"threads\": %d, \"loop_seconds\": %.6g, "
              "\"particle_steps_per_s\": %.6g, \"broken_bonds\": %zu, \"broken_timed\": %zu, "
              "\"kinetic_start\": %.10g, "
              "\"kinetic_end\": %.10g, \"total_start\": %.10g, \"total_end\": %.10g}\n",
              n, steps, omp_get_max_threads(), seconds, static_cast<double>(n) * steps / seconds,
              solver.brokenBonds(), solver.brokenBonds() - brokenBefore, e0.kinetic, e.kinetic,
              e0.total(), e.total());
  return 0;
}
