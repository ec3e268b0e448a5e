// Time integration of the bonded-particle model of Watson & Steinhauser 2017 (Materials 10:379,
// seed 003, Eq. 1 with the potentials of Eqs. 3–4; see WatsonSteinhauser2017.h).
//
// Velocity Verlet with a constant Δt, no friction, no damping. Δt is a fixed fraction of the
// bond period 2π√(m/κ); the default fraction gives the paper's 1e-10 s at its headline size
// and, since m ∝ σ³ and κ ∝ σ, scales with σ like every other time of the sized model.
//
// Repulsion acts between every pair closer than r_eq; the pairs come from a full Verlet list
// (within r_eq + skin, built with the common CellList, rebuilt when a particle has moved more
// than half the skin), each particle's neighbours sorted by index. Bonds come from the bond
// list; each step, after the drift, every intact bond longer than r_cut is broken for good and
// its spring energy is booked as dissipated (so that kinetic + repulsive + bond + dissipated
// energy is what the integrator conserves).
//
// OpenMP without atomics: each bond writes its force to its own slot, each particle sums its
// neighbours and then its bonds in index order, and energies are summed over fixed-size chunks
// in chunk order. Results are therefore bit-identical for any thread count; and because pairs
// out of range contribute nothing and sums keep their order, a run restored from a checkpoint
// (which stores positions, velocities, forces and bond states) continues bit-identically.
#pragma once

#include "bonded/BondedBody.h"
#include "common/Progress.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace craterkit {

struct BondedSolverParams {
  double timeStep = 0.0;                                         // s; 0: fraction × period
  double timeStepFraction = ws2017::referenceTimeStepFraction(); // of the bond period
  double skin = 0.3;                                             // Verlet skin, units of σ
  void validate() const;
};

struct BondedEnergies {
  double kinetic = 0.0, repulsive = 0.0, bond = 0.0;
  double dissipated = 0.0; // spring energy of the bonds at the moment they broke
  double total() const { return kinetic + repulsive + bond + dissipated; }
};

class BondedSolver {
public:
  BondedSolver(BondedSystem system, const BondedSolverParams& params = {});

  void step();
  // Advances `steps` steps; reports progress every ~1 % and throws Aborted (after a complete
  // step) when the callback returns false.
  void advance(std::size_t steps, const ProgressCallback& progress = {});
  // Advances to the first step at or after `time`.
  void advanceTo(double time, const ProgressCallback& progress = {});

  BondedEnergies energies() const;
  std::array<double, 3> momentum() const;

  double timeStep() const { return dt_; }
  double time() const { return dt_ * static_cast<double>(step_); }
  std::uint64_t stepCount() const { return step_; }
  std::size_t brokenBonds() const { return broken_; }
  const BondedSystem& system() const { return sys_; }
  const std::vector<std::uint8_t>& bondBroken() const { return bondBroken_; }
  const std::vector<double>& forces() const { return force_; }

  // Whole state, through writeFileAtomically; readCheckpoint gives a bit-identical run.
  void writeCheckpoint(const std::string& path) const;
  static BondedSolver readCheckpoint(const std::string& path);

private:
  BondedSolver() = default;
  void prepare();
  void buildNeighbours();
  bool needsRebuild() const;
  void computeForces();
  void bookBreaks();

  BondedSystem sys_;
  BondedSolverParams params_;
  double dt_ = 0.0;
  std::uint64_t step_ = 0;
  std::size_t broken_ = 0;
  double dissipated_ = 0.0;
  std::vector<double> force_, bondForce_, listOrigin_;
  std::vector<std::uint8_t> bondBroken_; // 0 intact, 1 broken, 2 broken this step
  std::vector<std::size_t> neighbourStart_, bondStart_;
  std::vector<std::uint32_t> neighbours_, bondsOf_;
};

} // namespace craterkit
